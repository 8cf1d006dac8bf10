//! Key shapes while editing (§3.2): when the edited sweep is a shape of a
//! `keyframe` chain, the pair of key shapes at the time slider's place,
//! how the expander matches their segments (the start of segment i of the
//! expanded FIRST joined to the start of segment i of the expanded LAST),
//! and the in-between contour at that time, from the same `goahead` the
//! renderer runs.

use super::curve::{joints, polylines};
use super::document::Target;
use crate::options::Fidelity;
use crate::paper::{chain_time, inbetween, reparam, PaperChain, PaperPair};
use crate::scene::Scene;
use crate::types::{Shape, SweepShape};

/// The chain the edited sweep is a shape of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chain {
    /// The `keyframe` record's index in `Scene::keyframes`.
    pub record: usize,
    /// The edited shape's place in the chain: 0 for FIRST.
    pub place: usize,
    /// How many key shapes the chain has (at least 2).
    pub shapes: usize,
}

impl Chain {
    /// The chain of the sweep at `target`, if it is a key shape.
    pub fn of(scene: &Scene, target: Target) -> Option<Chain> {
        let (record, place) = match target {
            Target::Object(i) => (scene.keyframes.iter().position(|k| k.first == i)?, 0),
            Target::KeyShape { record, index } => (record, index + 1),
        };
        Some(Chain {
            record,
            place,
            shapes: scene.keyframes[record].rest.len() + 1,
        })
    }

    /// The shutter time at which the chain stands at the edited shape.
    pub fn key_time(&self) -> f64 {
        self.place as f64 / (self.shapes - 1) as f64
    }
}

/// What the plane shows of a chain at one time.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChainView {
    /// The pair shown (from 1) and how many pairs the chain has.
    pub pair: usize,
    pub pairs: usize,
    /// The two key shapes of the pair as their own curves, a polyline a segment.
    pub from: Vec<Vec<[f64; 2]>>,
    pub to: Vec<Vec<[f64; 2]>>,
    /// Segment i's start on the expanded FIRST and on the expanded LAST.
    pub matches: Vec<([f64; 2], [f64; 2])>,
    /// The in-between contour at the time, a polyline a segment.
    pub inbetween: Vec<Vec<[f64; 2]>>,
}

/// The chain's view at shutter time `time` in `scene` (the deck's scene
/// with the edited contour), or the error `goahead` gives for it.
pub fn view(scene: &Scene, chain: Chain, time: f64, fidelity: Fidelity) -> Result<ChainView, String> {
    let mut scene = scene.clone();
    crate::shapes::sweep::prepare_sweeps(&mut scene, fidelity);
    let record = &scene.keyframes[chain.record];
    let paper = PaperChain::from_keyframe(&scene, record, fidelity).map_err(|e| e.to_string())?;
    let (k, _) = chain_time(paper.pairs().len(), time);
    let pair = &paper.pairs()[k];
    let shapes = key_shapes(&scene, chain.record);
    let own = |i: usize| shapes.get(i).map(|s| polylines(&s.u, &s.v)).unwrap_or_default();
    let mut scratch = paper.scratch();
    let mut at = |t: f64| {
        contour_of(pair, t, &mut scratch);
        scratch.clone()
    };
    let (start, end) = (at(0.0), at(1.0));
    let matches = joints(&start.u, &start.v)
        .into_iter()
        .zip(joints(&end.u, &end.v))
        .collect();
    paper.inbetween(time, &mut scratch);
    Ok(ChainView {
        pair: k + 1,
        pairs: paper.pairs().len(),
        from: own(k),
        to: own(k + 1),
        matches,
        inbetween: polylines(&scratch.u, &scratch.v),
    })
}

/// The key shapes of the `keyframe` record `record`, in order: FIRST's
/// sweep, then the later shapes'.
pub(crate) fn key_shapes(scene: &Scene, record: usize) -> Vec<&SweepShape> {
    let k = &scene.keyframes[record];
    std::iter::once(&scene.objects[k.first])
        .chain(&k.rest)
        .filter_map(|o| match &o.shape {
            Shape::Sweep(sw) => Some(sw),
            _ => None,
        })
        .collect()
}

/// The pair's in-between at its own time `t`, each segment on [0, 1] (as
/// [`PaperChain::inbetween`] gives it).
fn contour_of(pair: &PaperPair, t: f64, obj: &mut SweepShape) {
    inbetween(pair, t, obj);
    for c in obj.u.iter_mut().chain(obj.v.iter_mut()) {
        *c = reparam(c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::DeckInput;

    fn fig5_10() -> Scene {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/decks/fig5_10.deck");
        DeckInput::read(&path).unwrap().initialize(Fidelity::Thesis).unwrap()
    }

    #[test]
    fn the_chain_of_each_key_shape_and_its_time() {
        let scene = fig5_10();
        let first = Chain::of(&scene, Target::Object(1)).unwrap();
        assert_eq!((first.place, first.shapes, first.key_time()), (0, 2, 0.0));
        let last = Chain::of(&scene, Target::KeyShape { record: 0, index: 0 }).unwrap();
        assert_eq!((last.place, last.key_time()), (1, 1.0));
        assert_eq!(Chain::of(&scene, Target::Object(0)), None, "the floor is no key shape");
    }

    #[test]
    fn the_matches_join_the_expanded_shapes_and_the_inbetween_ends_on_them() {
        let scene = fig5_10();
        let chain = Chain::of(&scene, Target::Object(1)).unwrap();
        let v = view(&scene, chain, 0.0, Fidelity::Thesis).unwrap();
        assert_eq!((v.pair, v.pairs), (1, 1));
        assert_eq!((v.from.len(), v.to.len()), (10, 4));
        // Burtnyk's rule makes 4 segments 10: 10 matches.
        assert_eq!(v.matches.len(), 10);
        // At t = 0 the in-between is FIRST: it starts where the matches do.
        let starts: Vec<[f64; 2]> = v.inbetween.iter().map(|l| l[0]).collect();
        let firsts: Vec<[f64; 2]> = v.matches.iter().map(|m| m.0).collect();
        assert_eq!(starts, firsts);
        let v1 = view(&scene, chain, 1.0, Fidelity::Thesis).unwrap();
        let lasts: Vec<[f64; 2]> = v1.matches.iter().map(|m| m.1).collect();
        let ends: Vec<[f64; 2]> = v1.inbetween.iter().map(|l| l[0]).collect();
        for (a, b) in ends.iter().zip(&lasts) {
            assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9, "{a:?} {b:?}");
        }
    }
}

//! The key-frame families: random rays against the in-between shapes of
//! the key-frame decks, the robust solver's hit the reference.

use raytrace::options::{Fidelity, Options};
use raytrace::types::{DVec3, PrimitiveClass, Ray};

use super::rays::box_size;
use super::{Method, RayCase, RayFamily, Rng, TestSweep};

/// The key-frame decks whose in-between shapes the key-frame families
/// take, and how each matches its key shapes.
pub const KEYFRAME_DECKS: [(&str, &str); 3] = [
    ("fig5_10", "`expanding`/`more` (Burtnyk & Wein), translation"),
    ("fig5_11", "`expanding2`/`more2` (arc length), translation"),
    ("fig5_12", "`expanding2`/`more2` (arc length), rotation"),
];

/// The in-between shapes of each key-frame deck at 8 instants of the
/// shutter ((j + ½)/8), as the renderer builds them (`goahead`, then
/// `inbetween` per instant), in the key shapes' local frame.
pub fn keyframe_shapes() -> Result<Vec<(String, Vec<TestSweep>)>, String> {
    let mut out = Vec::new();
    for (deck, how) in KEYFRAME_DECKS {
        let prepared = crate::decks::prepared(deck, &Options::default(), None)?;
        let scene = prepared.scene();
        let chains = raytrace::raytrace::key_frame_chains(scene, Fidelity::Thesis).map_err(|e| e.to_string())?;
        let mut shapes = Vec::new();
        for (k, chain) in &chains {
            let class = scene.objects[scene.keyframes[*k].first].class;
            for j in 0..8 {
                let t = (j as f64 + 0.5) / 8.0;
                let mut sweep = chain.scratch();
                chain.inbetween(t, &mut sweep);
                let size = box_size(&sweep);
                shapes.push(TestSweep {
                    name: format!("{deck} at t = {t}"),
                    class,
                    sweep,
                    cache: None, // a contour of the moment
                    size,
                });
            }
        }
        out.push((format!("in-between shapes of {deck}: {how}"), shapes));
    }
    Ok(out)
}

/// A random ray from a sphere of radius 8 about the centre of a sweep's
/// box, aimed at a random point of the box (for rotation, the box of
/// the solid of revolution).
fn random_ray(rng: &mut Rng, ts: &TestSweep) -> Ray {
    let b = &ts.sweep.bbox;
    let (lo, hi) = match ts.class {
        PrimitiveClass::Rotation => {
            let r = b.xmax.abs().max(b.xmin.abs());
            (DVec3::new(-r, -r, b.zmin), DVec3::new(r, r, b.zmax))
        }
        _ => (DVec3::new(b.xmin, b.ymin, b.zmin), DVec3::new(b.xmax, b.ymax, b.zmax)),
    };
    let centre = (lo + hi) * 0.5;
    let dir = loop {
        let v = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            break v / l;
        }
    };
    let origin = centre + dir * 8.0;
    let target = DVec3::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y), rng.range(lo.z, hi.z));
    Ray::new(origin, (target - origin).normalize())
}

/// The key-frame families: `per` random rays against the in-between
/// shapes of each key-frame deck. No analytic truth exists for an
/// in-between contour: the true hit is the robust solver's (whose hits
/// lie on the surface within 1e-9 of the size, D12, and which finds every
/// root of the constructed families above), so its own row is the
/// reference and counts nothing.
pub fn keyframe_families(shapes: &[(String, Vec<TestSweep>)], per: usize) -> Vec<RayFamily<'_>> {
    let robust = Method::Robust.options();
    let mut rng = Rng(0x6EA2_0007);
    shapes
        .iter()
        .map(|(name, list)| {
            let cases = (0..per)
                .map(|k| {
                    let ts = &list[k % list.len()];
                    let ray = random_ray(&mut rng, ts);
                    let truth = ts.object().intersect(&ray, 1e-9, &robust, &mut 0).map(|h| h.t);
                    RayCase { sweep: ts, ray, truth }
                })
                .collect();
            RayFamily {
                name: name.clone(),
                truth: "the robust solver's hit (the reference: its own row counts nothing)",
                cases,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every key-frame deck gives 8 in-between shapes, each with segments
    /// and a box, and rays that hit some of them.
    #[test]
    fn keyframe_shapes_are_built() {
        let shapes = keyframe_shapes().unwrap();
        assert_eq!(shapes.len(), KEYFRAME_DECKS.len());
        for (name, list) in &shapes {
            assert_eq!(list.len(), 8, "{name}");
            assert!(list.iter().all(|s| s.sweep.segment > 0 && s.size > 0.0), "{name}");
        }
        let fams = keyframe_families(&shapes, 50);
        for f in &fams {
            assert!(f.cases.iter().any(|c| c.truth.is_some()), "{}", f.name);
        }
    }
}

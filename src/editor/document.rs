//! A deck opened at one of its sweeps: the scene the deck reader made,
//! where the sweep is in it, its record in the text, and the save that
//! checks an edited contour and writes it back.

use std::path::Path;

use super::model::{Contour, Refusal};
use super::record::SweepRecord;
use crate::exit::Failure;
use crate::options::{Fidelity, Options};
use crate::raytrace::Prepared;
use crate::run::DeckInput;
use crate::scene::Scene;
use crate::types::{ObjectRecord, Shape, SweepShape};

/// Where the edited sweep is in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// An object of the scene, by its index in `Scene::objects`.
    Object(usize),
    /// A later key shape of a `keyframe` record: the record's index in
    /// `Scene::keyframes` and the shape's in its `rest`.
    KeyShape { record: usize, index: usize },
}

/// The deck `contour --new` starts from: a view, a light, a floor and one
/// rotation sweep, `shape`, to edit.
pub const NEW_DECK: &str = "\
{ A deck begun by the contour editor (contour --new): a view, a light, a
  floor and one sweep, 'shape', to edit. Format: legacy_pascal/DECK.md. }
view eye 0 -7 3 look 0 0 1 screen 3.2 distance 5
image 256 256 mask 2
background 0.1 0.1 0.2
light sun 5 -6 10 1 1 1
surface grnd opaque color 0.8 0.8 0.8 ka 0.2 kd 0.8 ks 0 kt 0
paint grnd floor scale 1 1 color 0.2 0.2 0.5
surface red opaque color 0.8 0.25 0.15 ka 0.15 kd 0.75 ks 0.1 kt 0
block floor grnd at 0 0 -0.25 size 14 14 0.5

{ U V: U the radius, V the height. }
sweep shape red rotation bspline at 0 0 0
    0    0
  0.6    0
  0.8  0.3
  0.5  0.9
  0.7  1.5
  0.4  1.8
    0  1.8
    0  0.9
end
";

/// The name of the sweep in [`NEW_DECK`].
pub(crate) const NEW_NAME: &str = "shape";

/// A deck and the sweep of it being edited.
#[derive(Clone, Debug)]
pub struct Document {
    pub deck: DeckInput,
    /// The scene as the deck reader made it, before any edit.
    pub scene: Scene,
    /// The sweep's name.
    pub name: String,
    pub target: Target,
    pub record: SweepRecord,
    /// The contour as the deck has it.
    pub original: Contour,
    pub fidelity: Fidelity,
}

/// The sweeps of a scene by name: its sweep objects, then the later key
/// shapes of its `keyframe` records, each with its place.
pub fn sweeps(scene: &Scene) -> Vec<(String, Target)> {
    let objects = scene.objects.iter().enumerate().map(|(i, o)| (o, Target::Object(i)));
    let keys = scene.keyframes.iter().enumerate().flat_map(|(record, k)| {
        k.rest
            .iter()
            .enumerate()
            .map(move |(index, o)| (o, Target::KeyShape { record, index }))
    });
    objects
        .chain(keys)
        .filter(|(o, _)| matches!(o.shape, Shape::Sweep(_)))
        .map(|(o, t)| (o.name.clone(), t))
        .collect()
}

impl Document {
    /// The deck `deck` opened at its sweep `name`: a deck error (at its
    /// line and column) or a name that is no sweep (with the deck's
    /// sweeps listed) is an input error, exit 2.
    pub fn open(deck: DeckInput, name: &str, fidelity: Fidelity) -> Result<Document, Failure> {
        let scene = deck.initialize(fidelity)?;
        let all = sweeps(&scene);
        let Some(&(_, target)) = all.iter().find(|(n, _)| n == name) else {
            let listed: Vec<&str> = all.iter().map(|(n, _)| n.as_str()).collect();
            let what = match scene.objects.iter().find(|o| o.name == name) {
                Some(o) => format!("'{name}' is a {}, not a sweep", kind_of(o)),
                None => format!("'{name}' is not a sweep of {}", deck.name),
            };
            return Err(Failure::input(match listed.len() {
                0 => format!("{what}, and the deck has no sweep"),
                _ => format!("{what}; its sweeps: {}", listed.join(", ")),
            }));
        };
        let line = match target {
            Target::Object(i) => Some(scene.object_pos[i].line),
            Target::KeyShape { .. } => None,
        };
        let record = SweepRecord::find(&deck.source, &deck.name, name, line).map_err(Failure::input)?;
        let object = object_of(&scene, target);
        let Shape::Sweep(sw) = &object.shape else {
            return Err(Failure::input(format!("'{name}' is not a sweep")));
        };
        let original = Contour::of_deck(object.class, sw.curve, &sw.points, sw.length, sw.scale);
        Ok(Document {
            deck,
            scene,
            name: name.to_string(),
            target,
            record,
            original,
            fidelity,
        })
    }

    /// A new deck ([`NEW_DECK`]) to be saved at `path`, opened at its sweep.
    pub fn new_deck(path: &Path, fidelity: Fidelity) -> Result<Document, Failure> {
        let deck = DeckInput {
            source: NEW_DECK.as_bytes().to_vec(),
            name: path.display().to_string(),
            dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            stem: path
                .file_stem()
                .map_or("new".into(), |s| s.to_string_lossy().into_owned()),
        };
        Document::open(deck, NEW_NAME, fidelity)
    }

    /// The scene with the sweep's contour replaced by `contour` (its
    /// segments and boxes to be filled by `spline` when it is prepared).
    pub fn scene_with(&self, contour: &Contour) -> Scene {
        let mut scene = self.scene.clone();
        let object = match self.target {
            Target::Object(i) => &mut scene.objects[i],
            Target::KeyShape { record, index } => &mut scene.keyframes[record].rest[index],
        };
        set_contour(object, contour);
        scene
    }

    /// The deck with `contour` saved into the sweep's record, or why it
    /// cannot be: the contour's own check ([`Contour::check`]), then the
    /// new deck must read and prepare without error and give back the
    /// very contour (anything else is refused, and nothing is written).
    pub fn save(&self, contour: &Contour) -> Result<Vec<u8>, Refusal> {
        contour.check()?;
        let source = self.record.rewrite(&self.deck.source, &self.original, contour);
        let deck = DeckInput {
            source,
            ..self.deck.clone()
        };
        let scene = deck
            .initialize(self.fidelity)
            .map_err(|e| Refusal(format!("the saved deck would not read: {e}")))?;
        let back = Document::open(deck.clone(), &self.name, self.fidelity)
            .map_err(|e| Refusal(format!("the saved deck would lose the sweep: {e}")))?;
        if !same_contour(&back.original, contour) {
            return Err(Refusal(
                "the saved record would not read back as the edited contour (a comment in the way?)".into(),
            ));
        }
        let opts = Options {
            fidelity: self.fidelity,
            ..Options::default()
        };
        Prepared::new(scene, opts).map_err(|e| Refusal(format!("the saved deck would not render: {e}")))?;
        Ok(deck.source)
    }
}

impl Document {
    /// The document once its deck is saved as `source` holding `contour`:
    /// the deck read again, and `contour` (its points' identities kept,
    /// so that an undo after the save still finds their lines) the one
    /// the deck now has.
    pub fn saved(&mut self, source: Vec<u8>, contour: &Contour) -> Result<(), Refusal> {
        let deck = DeckInput {
            source,
            ..self.deck.clone()
        };
        let mut doc = Document::open(deck, &self.name, self.fidelity).map_err(|e| Refusal(e.message))?;
        if !same_contour(&doc.original, contour) {
            return Err(Refusal("the saved deck does not hold the edited contour".into()));
        }
        doc.original = contour.clone();
        *self = doc;
        Ok(())
    }
}

/// Whether two contours have the same curve, kind, points and the fields
/// the kind writes.
fn same_contour(a: &Contour, b: &Contour) -> bool {
    use crate::types::PrimitiveClass as C;
    a.class == b.class
        && a.curve == b.curve
        && a.uv() == b.uv()
        && (a.class == C::Rotation || a.length == b.length)
        && (a.class != C::Conic || a.scale == b.scale)
}

/// The object at `target`.
pub(crate) fn object_of(scene: &Scene, target: Target) -> &ObjectRecord {
    match target {
        Target::Object(i) => &scene.objects[i],
        Target::KeyShape { record, index } => &scene.keyframes[record].rest[index],
    }
}

/// The object's sweep made of `contour`: its kind, curve, points, length
/// and scale, and the bounding radius the deck reader gives such a sweep
/// (src/deck/mod.rs, "Objects"); the segments are left for `spline`.
fn set_contour(object: &mut ObjectRecord, contour: &Contour) {
    use crate::types::PrimitiveClass as C;
    let r2 = contour.points.iter().map(|p| p.u * p.u + p.v * p.v).fold(0.0, f64::max);
    object.class = contour.class;
    object.radius = match contour.class {
        C::Rotation => r2.sqrt(),
        C::Conic => (r2 * contour.scale.max(1.0).powi(2) + contour.length.powi(2)).sqrt(),
        _ => (r2 + contour.length.powi(2)).sqrt(),
    };
    if let Shape::Sweep(sw) = &mut object.shape {
        *sw = SweepShape {
            curve: contour.curve,
            points: contour.uv(),
            segment: 0,
            u: Vec::new(),
            v: Vec::new(),
            length: if contour.class == C::Rotation {
                0.0
            } else {
                contour.length
            },
            scale: if contour.class == C::Conic { contour.scale } else { 1.0 },
            ..sw.clone()
        };
    }
}

/// The deck's word for an object's kind.
fn kind_of(o: &ObjectRecord) -> &'static str {
    match o.shape {
        Shape::Sphere => "sphere",
        Shape::Block { .. } => "block",
        Shape::Cylinder { .. } => "cylinder",
        Shape::Prism { .. } => "prism",
        Shape::Sweep(_) => "sweep",
        Shape::Blob(_) => "blob",
        Shape::Patch(_) => "patch",
    }
}

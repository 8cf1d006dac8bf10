//! What the sweep driver keeps of an object whose contour keeps its
//! shape, made once its box is final (the port's; DEVIATIONS D32, D33):
//! the cap grid and the bounds every ray takes from the box. Owned by the
//! render, not by the object's record, so the records need nothing of the
//! driver and no contour of the moment can carry another shape's cache.

use std::collections::HashMap;
use std::sync::Arc;

use super::{CapGrid, QueryBounds};
use crate::scene::Scene;
use crate::shapes::ShapeCache;
use crate::types::{PrimitiveClass, Shape, SweepShape};

/// See the module doc. Made by [`SweepCache::new`], or for a whole scene
/// by [`prepare_caches`]; given to the intersection with the shape it was
/// made from ([`Sweep`](super::Sweep), [`Posed`](crate::shapes::Posed)).
#[derive(Clone, Debug, PartialEq)]
pub struct SweepCache {
    /// The cells of the contour's box that lie wholly inside or outside
    /// it, so that a cap test there takes no root; made for translation
    /// and conic sweeps (a rotation sweep's contour closes no cap).
    pub(super) cap_grid: Option<CapGrid>,
    /// What every ray takes from the box, kept with the box and class it
    /// was made from: a box changed since is not answered by it.
    pub(super) bounds: Option<QueryBounds>,
}

impl SweepCache {
    /// The cache of `sweep` (its segments and box final) as an object of
    /// `class`; `None` when there is nothing to keep.
    pub fn new(class: PrimitiveClass, sweep: &SweepShape) -> Option<SweepCache> {
        let cap_grid = match class {
            PrimitiveClass::Translation | PrimitiveClass::Conic => CapGrid::new(&sweep.u, &sweep.v),
            _ => None,
        };
        let bounds = QueryBounds::kept(class, sweep);
        (cap_grid.is_some() || bounds.is_some()).then_some(SweepCache { cap_grid, bounds })
    }

    /// Were the kept bounds made from `sweep`'s box as an object of
    /// `class`, so that a ray of it takes them?
    pub fn fits(&self, class: PrimitiveClass, sweep: &SweepShape) -> bool {
        self.bounds.is_some_and(|b| b.holds(class, &sweep.bbox))
    }
}

/// The sweeps' caches of `scene.objects[i]`, in their order: `None` for
/// an object that is not a sweep or has nothing to keep. Made after the boxes are
/// final (`prepare_sweeps`, then `widen_tbox`). Objects with the same
/// contour, box and class share one cache (a scene of a thousand copies of
/// one star makes its cap grid once).
pub fn prepare_caches(scene: &Scene) -> Vec<Option<Arc<ShapeCache>>> {
    let mut made: HashMap<Vec<u64>, Option<Arc<ShapeCache>>> = HashMap::new();
    scene
        .objects
        .iter()
        .map(|obj| match &obj.shape {
            Shape::Sweep(sw) => made
                .entry(key(obj.class, sw))
                .or_insert_with(|| SweepCache::new(obj.class, sw).map(|c| Arc::new(ShapeCache::Sweep(c))))
                .clone(),
            _ => None,
        })
        .collect()
}

/// Everything of an object [`SweepCache::new`] may read, as bits: equal
/// keys make equal caches.
fn key(class: PrimitiveClass, sw: &SweepShape) -> Vec<u64> {
    let b = &sw.bbox;
    let mut k = vec![
        class as u64,
        sw.orientt as u64,
        sw.curve as u64,
        sw.segment as u64,
        sw.length.to_bits(),
        sw.scale.to_bits(),
        sw.orientation.to_bits(),
    ];
    k.extend([b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax].map(f64::to_bits));
    for c in sw.u.iter().chain(&sw.v) {
        k.extend([c.a, c.b, c.c, c.d, c.max, c.min, c.first, c.last].map(f64::to_bits));
    }
    k.push(sw.u.len() as u64);
    k
}

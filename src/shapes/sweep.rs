//! The sweep intersection driver (being written on its own branch; this
//! stand-in refuses nothing and hits nothing).
use crate::types::{Fidelity, LocalHit, Options, PrimitiveClass, Ray, Scene, SweepShape};

pub fn prepare_sweeps(_scene: &mut Scene, _fidelity: Fidelity) {}

pub fn intersect_sweep(
    _class: PrimitiveClass,
    _sweep: &SweepShape,
    _ray: &Ray,
    _tmin: f64,
    _opts: &Options,
) -> Option<LocalHit> {
    None
}

//! Depth of field: the port's extension where the thesis stops (§1.4: Cook's
//! distributed ray tracing "solved at one stroke blurred reflection and
//! depth of field"; the listing's `depthoffield`, OCR lines 2187–2202, is
//! "not completed" and the main program's `if dof=1 then depthoffield(…)`
//! is commented out, lines 3135–3141). Deck `lens APERTURE FOCUS`.
//!
//! - `thesis` fidelity: a thin lens as pbrt-v4's (`lensradius`,
//!   `focaldistance`): each sample takes a point of the aperture disk
//!   (two dimensions of its sampler, mapped to the disk by Shirley &
//!   Chiu's concentric map) and aims through where its pinhole ray meets
//!   the plane FOCUS along the line of sight.
//! - `listing` fidelity: the printed `depthoffield` ([`depthoffield`]):
//!   the ray's far point moved onto the world plane y = `focuslength`, the
//!   eye moved by `fradius*noise[dindex]*2` in z only (one dimension of its
//!   sampler, `noise[dindex]` for `--sampler table`), a lens of one
//!   dimension (DEVIATIONS D45).

use crate::drt::depthoffield;
use crate::options::Fidelity;
use crate::sampler::{concentric_disk, Sampler};
use crate::scene::LensRecord;
use crate::types::{DVec3, Ray};

/// A lens of aperture > 0 with the view's axes in the world.
#[derive(Clone, Debug)]
pub struct Lens {
    aperture: f64,
    focus: f64,
    /// The line of sight, unit.
    forward: DVec3,
    /// The viewer's right and up on the lens plane, unit.
    right: DVec3,
    up: DVec3,
    fidelity: Fidelity,
}

impl Lens {
    /// The lens of a `lens` record; `None` for aperture 0, the pinhole (so
    /// that `lens 0 F` draws nothing and gives the bytes of no lens).
    pub fn new(record: Option<&LensRecord>, forward: DVec3, right: DVec3, fidelity: Fidelity) -> Option<Lens> {
        let r = record.filter(|r| r.aperture > 0.0)?;
        let forward = forward.normalize();
        let right = right.normalize();
        Some(Lens {
            aperture: r.aperture,
            focus: r.focus,
            forward,
            right,
            up: right.cross(forward).normalize(),
            fidelity,
        })
    }

    /// The ray of the lens for the pinhole ray from `eye` through `screen`
    /// (a point of the screen plane), drawing its lens point from
    /// `sampler`.
    pub fn ray(&self, eye: DVec3, screen: DVec3, sampler: &mut dyn Sampler) -> Ray {
        match self.fidelity {
            Fidelity::Thesis => {
                let d = (screen - eye).normalize();
                // Where the pinhole ray meets the plane of focus.
                let along = self.focus / d.dot(self.forward);
                let sharp = eye + d * along;
                let [lx, ly] = concentric_disk(sampler.get_2d());
                let origin = eye + (self.right * lx + self.up * ly) * self.aperture;
                Ray::new(origin, (sharp - origin).normalize())
            }
            Fidelity::Listing => {
                let noise = sampler.get_1d() - 0.5;
                let (x0, y0, mut z0) = (eye.x, eye.y, eye.z);
                let (mut x1, mut y1, mut z1) = (screen.x, screen.y, screen.z);
                depthoffield(
                    x0,
                    y0,
                    &mut z0,
                    &mut x1,
                    &mut y1,
                    &mut z1,
                    self.focus,
                    self.aperture,
                    &[noise],
                    0,
                );
                let origin = DVec3::new(x0, y0, z0);
                let dir = DVec3::new(x1, y1, z1) - origin;
                // A line of sight parallel to the plane y = focuslength
                // (t infinite) or a far point on the eye: the pinhole ray.
                if dir.is_finite() && dir.length() > 0.0 {
                    Ray::new(origin, dir.normalize())
                } else {
                    Ray::new(eye, (screen - eye).normalize())
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::Listed;

    /// The thin lens (`thesis`) moves the eye over a disk across the line
    /// of sight and aims through the pinhole ray's point on the plane of
    /// focus; the printed `depthoffield` (`listing`) moves it in z only.
    #[test]
    fn the_thin_lens_moves_the_eye_across_the_sight_and_the_listings_in_z_only() {
        let record = LensRecord {
            pos: Default::default(),
            aperture: 0.5,
            focus: 10.0,
        };
        // Looking along +y: right is +x, up is +z.
        let lens = |fidelity| Lens::new(Some(&record), DVec3::Y, DVec3::X, fidelity).unwrap();
        let (thesis, listing) = (lens(Fidelity::Thesis), lens(Fidelity::Listing));
        let (eye, screen) = (DVec3::ZERO, DVec3::new(0.3, 5.0, 0.2));
        let d = (screen - eye).normalize();
        let sharp = d * (10.0 / d.y);
        let (mut across_x, mut along_z) = (false, false);
        for u in [0.1, 0.3, 0.7, 0.9] {
            for v in [0.2, 0.8] {
                let r = thesis.ray(eye, screen, &mut Listed(vec![u, v], 0));
                assert!(r.origin.y.abs() < 1e-12 && r.origin.length() <= 0.5 + 1e-12, "{r:?}");
                let at_focus = r.origin + r.dir * ((sharp.y - r.origin.y) / r.dir.y);
                assert!((at_focus - sharp).length() < 1e-9, "{at_focus} against {sharp}");
                across_x |= r.origin.x.abs() > 1e-3;
                let l = listing.ray(eye, screen, &mut Listed(vec![u, v], 0));
                assert_eq!((l.origin.x, l.origin.y), (0.0, 0.0), "listing: the eye moves in z only");
                along_z |= l.origin.z.abs() > 1e-3;
            }
        }
        assert!(across_x && along_z);
    }
}

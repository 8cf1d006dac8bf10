//! The camera of the main program (reconstructed: the thesis prints the
//! calls, not the procedures): `getangle`, the angles of the line of
//! sight; `translookpt`, a point of the screen to the world; and where on
//! the screen a subpixel lies (DEVIATIONS D5).

use super::lens::Lens;
use crate::options::Fidelity;
use crate::sampler::{CameraSample, Sampler};
use crate::scene::{Scene, View};
use crate::types::{DVec3, Ray};

/// `getangle(sinz, cosz, sinx, cosx)`: the angles of the world → view
/// rotation. Reconstructed from the main program, which negates both sines
/// "for inverse rotations in translookpt": the view frame has the eye at
/// its origin, looks along −y (the screen plane is `ypt := -scrndistance`)
/// with z up; the world → view rotation turns about z by −β (the azimuth of
/// the line of sight), then about x by −α (its elevation).
pub fn getangle(view: &View) -> (f64, f64, f64, f64) {
    let f = (view.lookpt - view.eyept).normalize();
    // f = Rz(β)·Rx(α)·(0, −1, 0) = (sinβ cosα, −cosβ cosα, −sinα).
    let cos_a = (f.x * f.x + f.y * f.y).sqrt();
    let (sin_a, sin_b, cos_b) = (-f.z, f.x / cos_a, -f.y / cos_a);
    // The world → view angles are −β and −α.
    (-sin_b, cos_b, -sin_a, cos_a)
}

/// `translookpt(xpt, ypt, zpt, sinz, cosz, sinx, cosx)`: a point of the
/// view frame to the world, with the (already negated) sines of the main
/// program: turn about x by α, about z by β, then move to the eye.
/// Reconstructed.
#[allow(clippy::too_many_arguments)]
pub fn translookpt(xpt: f64, ypt: f64, zpt: f64, sinz: f64, cosz: f64, sinx: f64, cosx: f64, eyept: DVec3) -> DVec3 {
    // About x by α.
    let (y1, z1) = (ypt * cosx - zpt * sinx, ypt * sinx + zpt * cosx);
    // About z by β.
    let (x2, y2) = (xpt * cosz - y1 * sinz, xpt * sinz + y1 * cosz);
    eyept + DVec3::new(x2, y2, z1)
}

/// The camera of the main program: the negated `getangle` sines, the
/// screen window and the virtual (subpixel) raster.
#[derive(Clone, Debug)]
pub struct Camera {
    eyept: DVec3,
    sinz: f64,
    cosz: f64,
    sinx: f64,
    cosx: f64,
    scrndistance: f64,
    /// Width and height of the window on the screen plane.
    screen_w: f64,
    screen_h: f64,
    /// Where on the window subpixel k lies (DEVIATIONS D5): at
    /// (k + `shift` + jitter)/`across_x` of its width, and likewise down
    /// its height over `across_z`, of the subpixel raster `virthighx` by
    /// `virthighy` (width·masksize by height·masksize). Made once from
    /// the fidelity, not converted for every ray.
    shift: f64,
    across_x: f64,
    across_z: f64,
    /// The deck's `lens` of aperture > 0 (the port's extension).
    lens: Option<Lens>,
}

impl Camera {
    pub fn new(scene: &Scene, fidelity: Fidelity) -> Camera {
        let (sinz, cosz, sinx, cosx) = getangle(&scene.view);
        let img = &scene.image;
        let screen_w = scene.view.screensize;
        let eye = scene.view.eyept;
        // The view frame's −x is the viewer's right.
        let right = translookpt(-1.0, 0.0, 0.0, -sinz, cosz, -sinx, cosx, eye) - eye;
        let lens = Lens::new(scene.lens.as_ref(), scene.view.lookpt - eye, right, fidelity);
        // D5. Listing: (scancol+jitter)/(halfvirtualx*2.0-1.0), h =
        // `halfvirtualx` = N div 2 (at least 1 here). Thesis: the centre of
        // cell k of N, moved by the jitter: (k − ½ + jitter)/N.
        let (virthighx, virthighy) = (img.width * img.masksize, img.height * img.masksize);
        let (shift, across): (f64, fn(usize) -> f64) = match fidelity {
            Fidelity::Listing => (0.0, |n| ((2 * (n / 2)) as f64 - 1.0).max(1.0)),
            Fidelity::Thesis => (-0.5, |n| n as f64),
        };
        let screen_h = match fidelity {
            // Erratum 14, listing: `xpt` and `zpt` both span `screensize`,
            // so a raster that is not square gets pixels that are not.
            Fidelity::Listing => screen_w,
            // Thesis: square pixels, the height follows the aspect.
            Fidelity::Thesis => screen_w * img.height as f64 / img.width as f64,
        };
        Camera {
            eyept: scene.view.eyept,
            sinz: -sinz,
            cosz,
            sinx: -sinx,
            cosx,
            scrndistance: scene.view.scrndistance,
            screen_w,
            screen_h,
            shift,
            across_x: across(virthighx),
            across_z: across(virthighy),
            lens,
        }
    }

    /// The primary ray through subpixel (`scancol`, `scanline`), both
    /// 1-based as in the listing, scanline 1 at the top, moved by the jitter
    /// (jx, jz) in subpixels. The listing (OCR lines 3114–3117) puts it at
    /// `xpt := (scancol+noise2[aindex]*aliasing)/(halfvirtualx*2.0-1.0)*
    /// screensize/2`, and `zpt` likewise from `scanline`; `translookpt` is
    /// not printed. DEVIATIONS D5 lists what the port keeps of that: in
    /// both fidelities the window is `screensize` wide, centred on the line
    /// of sight, x to the viewer's right and scanline 1 at the top (the
    /// view frame's +x is the viewer's left, as it looks along −y with z
    /// up, hence the minus sign). Where along it subpixel k lies:
    /// `Fidelity::Listing` at k/(2h − 1) of the window, h =
    /// `halfvirtualx` = N div 2 for N subpixels (column 0, erratum 13's
    /// extra one, at the left edge); `Fidelity::Thesis` at the centre of
    /// the k-th of N equal cells, (k − ½)/N.
    #[inline]
    pub fn ray(&self, scancol: f64, scanline: f64, jx: f64, jz: f64) -> Ray {
        let p = self.screen_point(scancol, scanline, jx, jz);
        Ray::new(self.eyept, (p - self.eyept).normalize())
    }

    /// The primary ray of a sample: [`Camera::ray`] through its place, or
    /// with a `lens` the lens's ray, whose lens point the sample's further
    /// dimensions give. Without a lens nothing is drawn.
    #[inline(always)]
    pub fn ray_of<S: Sampler>(&self, c: CameraSample, sampler: &mut S) -> Ray {
        match &self.lens {
            None => self.ray(c.scancol, c.scanline, c.jx, c.jz),
            Some(lens) => lens.ray(
                self.eyept,
                self.screen_point(c.scancol, c.scanline, c.jx, c.jz),
                sampler,
            ),
        }
    }

    /// The point of the screen plane, in the world, that [`Camera::ray`]
    /// aims through (`translookpt` of `xpt`, `ypt`, `zpt`).
    fn screen_point(&self, scancol: f64, scanline: f64, jx: f64, jz: f64) -> DVec3 {
        // (k + 0) is k, and (k + −½) is k − ½, to the bit.
        let along = |k: f64, j: f64, across: f64| (k + self.shift + j) / across;
        let right = (along(scancol, jx, self.across_x) - 0.5) * self.screen_w;
        let up = (0.5 - along(scanline, jz, self.across_z)) * self.screen_h;
        let xpt = -right;
        let ypt = -self.scrndistance;
        let zpt = up;
        translookpt(xpt, ypt, zpt, self.sinz, self.cosz, self.sinx, self.cosx, self.eyept)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(eye: [f64; 3], look: [f64; 3]) -> View {
        View {
            eyept: DVec3::from_array(eye),
            lookpt: DVec3::from_array(look),
            screensize: 2.0,
            scrndistance: 1.0,
        }
    }

    /// The point straight ahead on the screen lies on the line of sight, for
    /// eyes in every octant.
    #[test]
    fn translookpt_centre_is_on_the_line_of_sight() {
        for eye in [[0.0, -5.0, 0.0], [3.0, 4.0, 2.0], [-2.0, 1.0, -3.0], [0.1, 0.0, 7.0]] {
            let v = view(eye, [0.5, 0.25, 0.0]);
            let (sz, cz, sx, cx) = getangle(&v);
            let p = translookpt(0.0, -v.scrndistance, 0.0, -sz, cz, -sx, cx, v.eyept);
            let want = v.eyept + (v.lookpt - v.eyept).normalize() * v.scrndistance;
            assert!((p - want).length() < 1e-12, "eye {eye:?}: {p} vs {want}");
        }
    }

    /// Right on the screen is the viewer's right, up is world up.
    #[test]
    fn screen_axes_are_right_and_up() {
        let v = view([0.0, -5.0, 0.0], [0.0, 0.0, 0.0]); // looking along +y
        let (sz, cz, sx, cx) = getangle(&v);
        let right = translookpt(-1.0, -1.0, 0.0, -sz, cz, -sx, cx, v.eyept);
        let up = translookpt(0.0, -1.0, 1.0, -sz, cz, -sx, cx, v.eyept);
        // Looking along +y with z up, the right hand is +x.
        assert!((right - DVec3::new(1.0, -4.0, 0.0)).length() < 1e-12);
        assert!((up - DVec3::new(0.0, -4.0, 1.0)).length() < 1e-12);
    }
}

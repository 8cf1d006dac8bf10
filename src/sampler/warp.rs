//! Maps of the unit square onto the shapes Cook's effects sample (the
//! port's extension): the aperture disk of a lens, the cone of directions
//! a sphere of light fills.

/// Shirley & Chiu's concentric map of [0, 1)² onto the unit disk (as
/// pbrt-v4's `SampleUniformDiskConcentric`): keeps strata apart, so a
/// stratified or Sobol pair stays spread over the disk.
pub fn concentric_disk([u, v]: [f64; 2]) -> [f64; 2] {
    use std::f64::consts::FRAC_PI_4;
    let (a, b) = (2.0 * u - 1.0, 2.0 * v - 1.0);
    if a == 0.0 && b == 0.0 {
        return [0.0, 0.0];
    }
    let (r, theta) = if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, 2.0 * FRAC_PI_4 - FRAC_PI_4 * (a / b))
    };
    [r * theta.cos(), r * theta.sin()]
}

/// A direction in the cone about the unit vector `w` of half-angle θmax
/// (`cos_max` = cos θmax), uniform over its solid angle (pbrt-v4's
/// `SampleUniformCone`), from [0, 1)²; with it, the cosine of its angle
/// to `w`.
pub fn uniform_cone([u, v]: [f64; 2], w: glam::DVec3, cos_max: f64) -> (glam::DVec3, f64) {
    let cos = 1.0 - u * (1.0 - cos_max);
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = 2.0 * std::f64::consts::PI * v;
    let (a, b) = w.any_orthonormal_pair();
    ((a * phi.cos() + b * phi.sin()) * sin + w * cos, cos)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// The map lands in the unit disk and reaches its rim.
    #[test]
    fn concentric_points_lie_in_the_disk() {
        let mut far: f64 = 0.0;
        for i in 0..64 {
            for j in 0..64 {
                let [x, y] = concentric_disk([i as f64 / 64.0, j as f64 / 64.0]);
                let r = x.hypot(y);
                assert!(r <= 1.0 + 1e-12, "{i} {j}: {r}");
                far = far.max(r);
            }
        }
        assert!(far > 0.99, "{far}");
        assert_eq!(concentric_disk([0.5, 0.5]), [0.0, 0.0]);
    }

    /// Cone directions are unit, within θmax of the axis, and fill it.
    #[test]
    fn cone_directions_stay_in_the_cone() {
        let w = DVec3::new(1.0, 2.0, -2.0).normalize();
        let cos_max = 0.9;
        let mut widest: f64 = 1.0;
        for i in 0..32 {
            for j in 0..32 {
                let (d, cos) = uniform_cone([i as f64 / 32.0, j as f64 / 32.0], w, cos_max);
                assert!((d.length() - 1.0).abs() < 1e-12);
                assert!((d.dot(w) - cos).abs() < 1e-12);
                assert!(cos >= cos_max - 1e-12 && cos <= 1.0);
                widest = widest.min(cos);
            }
        }
        assert!(widest < cos_max + 0.01, "{widest}");
    }
}

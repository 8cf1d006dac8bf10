//! Cook's distributed ray tracing beyond motion blur, in shading: soft
//! shadows and blurred reflection (the port's extension where the thesis
//! stops; §1.4: Cook 1984 "solved at one stroke blurred reflection and
//! depth of field"; the listing prints `jittering`, "Ref – [Robert 84]",
//! OCR lines 1312 and 2204–2238, and calls it nowhere). Each draws from
//! the sample's own further dimensions ([`Sampler::get_2d`]), so a ray's
//! time decides neither its light point nor its turn. Nothing is drawn
//! for a light of radius 0 or a surface of gloss 0: such decks give the
//! bytes they gave before.

use crate::drt::jittering;
use crate::options::Fidelity;
use crate::sampler::{concentric_disk, uniform_cone, Sampler};
use crate::scene::LightRecord;
use crate::types::DVec3;

/// Where a sample's shadow ray from `p` goes to a light: the unit
/// direction and the distance to the light's surface, or `None` when `p`
/// lies inside its sphere (the light surrounds it: lit, nothing between).
/// A point light (radius 0) is its centre and draws nothing; a sphere of
/// light (`radius` > 0, deck `light … radius R`) gives a direction in the
/// cone it fills seen from `p`, uniform over the solid angle, and the
/// distance to where that direction enters it.
#[inline]
pub(crate) fn toward_light(light: &LightRecord, p: DVec3, sampler: &mut dyn Sampler) -> Option<(DVec3, f64)> {
    let to_light = light.position - p;
    let dist = to_light.length();
    if light.radius <= 0.0 {
        return Some((to_light / dist, dist));
    }
    toward_sphere(light, to_light, dist, sampler)
}

/// [`toward_light`] for a sphere of light, kept out of line: the point
/// lights' path, every deck's before the port's extension, stays as short
/// as it was.
#[inline(never)]
fn toward_sphere(light: &LightRecord, to_light: DVec3, dist: f64, sampler: &mut dyn Sampler) -> Option<(DVec3, f64)> {
    let u = sampler.get_2d();
    // Inside the sphere (or a distance that is NaN): no cone.
    if dist.partial_cmp(&light.radius) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let w = to_light / dist;
    let sin_max = light.radius / dist;
    let cos_max = (1.0 - sin_max * sin_max).max(0.0).sqrt();
    let (l, cos) = uniform_cone(u, w, cos_max);
    // The near root of |p + s·l − centre| = radius.
    let sin2 = (1.0 - cos * cos).max(0.0);
    let s = dist * cos - (light.radius * light.radius - dist * dist * sin2).max(0.0).sqrt();
    Some((l, s.max(0.0)))
}

/// The unit direction `dir` of a reflected or transmitted ray from `p`,
/// turned by `jittering` for a surface of `gloss` G > 0 (Cook 1984's
/// blurred reflection), drawn from the sample: the point 5 along `dir`
/// moved across it by up to 5·G, so G is the tangent of the largest turn.
/// `listing`: `jittering` as printed (erratum 16), moved along its one
/// direction across by r = 5·G·(2u − 1). `thesis`: a point of the disk of
/// radius 5·G across `dir` (Shirley & Chiu's map), on `jittering`'s
/// direction across (erratum 16 fixed) and the one perpendicular to both.
/// A turn that would take the ray through to the other side of the
/// surface (`side` · `n` ≤ 0 for the unit normal `n`, `side` +1 for a
/// reflected ray, −1 for a transmitted one) keeps `dir`.
pub fn glossy(
    p: DVec3,
    dir: DVec3,
    n: DVec3,
    side: f64,
    gloss: f64,
    fidelity: Fidelity,
    sampler: &mut dyn Sampler,
) -> DVec3 {
    let reach = 5.0 * gloss;
    let (mut a, mut b, mut c) = (dir.x, dir.y, dir.z);
    let point = match fidelity {
        Fidelity::Listing => {
            let r = reach * (2.0 * sampler.get_1d() - 1.0);
            jittering(p.x, p.y, p.z, r, &mut a, &mut b, &mut c, fidelity);
            DVec3::new(a, b, c)
        }
        Fidelity::Thesis => {
            let [dx, dy] = concentric_disk(sampler.get_2d());
            jittering(p.x, p.y, p.z, 1.0, &mut a, &mut b, &mut c, fidelity);
            let ahead = p + dir * 5.0;
            let across = DVec3::new(a, b, c) - ahead;
            ahead + (across * dx + dir.cross(across) * dy) * reach
        }
    };
    let turned = (point - p).normalize();
    if turned.is_finite() && turned.dot(n) * side > 0.0 {
        turned
    } else {
        dir
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::Listed;

    /// `listing`'s `jittering` turns a ray along one direction across it,
    /// so every turn lies in one plane with the mirror's direction;
    /// `thesis` turns it over a disk, out of any one plane.
    #[test]
    fn the_listings_gloss_turns_in_one_plane_and_the_thesis_over_a_disk() {
        let (p, n) = (DVec3::new(0.3, -0.2, 1.0), DVec3::Z);
        let dir = DVec3::new(0.2, 0.1, 1.0).normalize();
        let turns = |fidelity| -> Vec<DVec3> {
            [[0.1, 0.35], [0.9, 0.5], [0.6, 0.95]]
                .iter()
                .map(|u| glossy(p, dir, n, 1.0, 0.2, fidelity, &mut Listed(u.to_vec(), 0)))
                .collect()
        };
        let (listing, thesis) = (turns(Fidelity::Listing), turns(Fidelity::Thesis));
        for t in listing.iter().chain(&thesis) {
            assert!(t.dot(n) > 0.0 && (t.length() - 1.0).abs() < 1e-12 && *t != dir, "{t}");
        }
        let out_of_plane = |t: &[DVec3]| (t[0] - dir).cross(t[1] - dir).dot(t[2] - dir).abs();
        assert!(out_of_plane(&listing) < 1e-12, "{listing:?}");
        assert!(out_of_plane(&thesis) > 1e-6, "{thesis:?}");
    }
}

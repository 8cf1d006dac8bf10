//! `tools pov` and Cook's distributed ray tracing (issue 26, item 6): a
//! `lens` becomes POV-Ray's focal blur (`aperture` 4× the lens's radius,
//! `focal_point` FOCUS along the line of sight, `blur_samples` the deck's
//! M×M rays), a light of `radius` R an `area_light` of diameter 2R
//! (`circular`, `orient`, `jitter`, M×M lights); a deck without them, or
//! with `lens 0 F` and `radius 0`, exports as before.

use std::path::Path;

use raytrace::deck::initialize;
use raytrace::options::Fidelity;
use raytrace::scene::Scene;
use raytrace::types::DVec3;
use tools::pov::scene_sdl;

const FIDELITIES: [Fidelity; 2] = [Fidelity::Thesis, Fidelity::Listing];

/// A small deck seen from `eye` toward `look`, with the `light`'s
/// optional field and the records in `extra`.
fn deck(eye: &str, look: &str, light: &str, extra: &str) -> String {
    format!(
        "view eye {eye} look {look} screen 4 distance 5
image 200 100 mask 3
light sun 3 -4 8  1 0.5 0.25 {light}
surface red opaque color 0.9 0.1 0.1  ka 0.2 kd 0.8 ks 0 kt 0
sphere ball red at 0 0 0 radius 1
{extra}
"
    )
}

fn scene(text: &str, fidelity: Fidelity) -> Scene {
    initialize(text, "pov.deck", Path::new("."), fidelity).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The line of `text` that starts with `start`.
fn line<'a>(text: &'a str, start: &str) -> &'a str {
    text.lines()
        .find(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("no {start} line in\n{text}"))
}

/// The POV-Ray vector after `key` in `line`, as our world's point (POV's
/// <x, y, z> is our (x, z, y)).
fn vector_after(line: &str, key: &str) -> DVec3 {
    let rest = &line[line.find(key).unwrap_or_else(|| panic!("no {key} in {line}")) + key.len()..];
    let inner = rest.trim_start().trim_start_matches('<');
    let v: Vec<f64> = inner[..inner.find('>').unwrap()]
        .split(',')
        .map(|s| s.trim().parse().unwrap())
        .collect();
    DVec3::new(v[0], v[2], v[1])
}

#[test]
fn a_lens_is_focal_blur_and_a_sphere_of_light_an_area_light() {
    let text = scene_sdl(
        &scene(&deck("0 -10 0", "0 0 0", "radius 0.5", "lens 0.25 8"), Fidelity::Thesis),
        Fidelity::Thesis,
    );
    let camera = line(&text, "camera {");
    // POV-Ray's lens radius is aperture/4: the deck's radius 0.25 is aperture 1.
    assert!(
        camera.ends_with(" aperture 1.0 focal_point <0.0, 0.0, -2.0> blur_samples 9, 9 }"),
        "{camera}"
    );
    let light = line(&text, "light_source {");
    assert_eq!(
        light,
        "light_source { <3.0, 8.0, -4.0> color rgb <1.0, 0.5, 0.25> area_light <1.0, 0, 0>, <0, 0, 1.0>, 3, 3 jitter circular orient } // sun"
    );
    // Mask 1: 2×2 lights, as POV-Ray refuses `circular` with one.
    let mut one = scene(&deck("0 -10 0", "0 0 0", "radius 0.5", ""), Fidelity::Thesis);
    one.resize(20, 10, 1);
    let text = scene_sdl(&one, Fidelity::Thesis);
    assert!(
        line(&text, "light_source {").contains(", 2, 2 jitter circular orient }"),
        "{text}"
    );
}

/// Seen obliquely, the focal point is FOCUS along the line of sight (the
/// eye toward the look point), which is along the camera's `direction`,
/// so POV-Ray's plane of focus (through `focal_point`, across `direction`)
/// is ours; the aperture is 4 times the lens's radius.
#[test]
fn the_focal_point_is_focus_along_the_line_of_sight() {
    for fidelity in FIDELITIES {
        let (eye, look) = (DVec3::new(3.0, -7.0, 2.0), DVec3::new(0.0, 1.0, 0.5));
        let text = scene_sdl(
            &scene(&deck("3 -7 2", "0 1 0.5", "", "lens 0.1 6.5"), fidelity),
            fidelity,
        );
        let camera = line(&text, "camera {");
        assert_eq!(vector_after(camera, "location"), eye);
        let focal = vector_after(camera, "focal_point");
        let want = eye + (look - eye).normalize() * 6.5;
        assert!((focal - want).length() < 1e-12, "{focal} against {want}");
        let direction = vector_after(camera, "direction").normalize();
        assert!(((focal - eye).normalize() - direction).length() < 1e-12, "{camera}");
        assert!(camera.contains(" aperture 0.4 "), "{camera}");
        // The listing's one-dimensional lens has no POV-Ray form: said so.
        assert_eq!(
            text.contains("// The lens as the thesis's thin lens"),
            fidelity == Fidelity::Listing,
            "{text}"
        );
    }
}

/// `lens 0 F` and `radius 0` are the pinhole and the point light: the
/// export of the deck without them, byte for byte.
#[test]
fn zero_lens_and_radius_export_as_none() {
    for fidelity in FIDELITIES {
        let none = scene_sdl(&scene(&deck("0 -10 1", "0 0 0", "", ""), fidelity), fidelity);
        let zero = scene_sdl(
            &scene(&deck("0 -10 1", "0 0 0", "radius 0", "lens 0 7"), fidelity),
            fidelity,
        );
        assert_eq!(zero, none);
        assert!(!none.contains("aperture") && !none.contains("area_light"), "{none}");
    }
}

/// Every shipped deck: its export differs from the export of the same
/// scene without lens, radii and gloss only by what those add at the end
/// of the camera, light and object lines (and the listing's lens note),
/// so what the base exported stands as it was; a deck with none of them
/// exports exactly that.
#[test]
fn shipped_decks_export_as_before_but_for_the_new_records() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../legacy_pascal/decks");
    let mut decks = 0;
    let mut with_records = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("deck") {
            continue;
        }
        let name = path.display().to_string();
        let src = std::fs::read_to_string(&path).unwrap();
        for fidelity in FIDELITIES {
            let full = initialize(&src, &name, &dir, fidelity).unwrap_or_else(|e| panic!("{e}"));
            let mut bare = full.clone();
            bare.lens = None;
            bare.lights.iter_mut().for_each(|l| l.radius = 0.0);
            bare.surfaces.iter_mut().for_each(|s| s.gloss = 0.0);
            let has_records = bare != full;
            let (a, b) = (scene_sdl(&full, fidelity), scene_sdl(&bare, fidelity));
            if !has_records {
                assert_eq!(a, b, "{name}");
                assert!(!a.contains("aperture") && !a.contains("area_light") && !a.contains("gloss"));
                continue;
            }
            with_records += 1;
            let note = |l: &&str| !l.starts_with("// The lens as the thesis's thin lens");
            let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().filter(note).collect(), b.lines().collect());
            assert_eq!(la.len(), lb.len(), "{name}");
            for (x, y) in la.iter().zip(&lb) {
                if x == y {
                    continue;
                }
                // x is y with one piece inserted: all of y is x's head and tail.
                let head = x.bytes().zip(y.bytes()).take_while(|(p, q)| p == q).count();
                let tail = x.bytes().rev().zip(y.bytes().rev()).take_while(|(p, q)| p == q).count();
                assert!(head + tail >= y.len() && x.len() > y.len(), "{name}:\n{x}\n{y}");
                let extra = &x[head.min(y.len())..x.len() - (y.len() - head.min(y.len()))];
                let added = ["aperture", "area_light", "/* gloss is not exported */"];
                assert!(added.iter().any(|w| extra.contains(w)), "{name}: {extra}");
            }
        }
        decks += 1;
    }
    assert!(decks >= 17, "{decks} decks");
    // cook.deck has a lens, a sphere of light and a glossy floor.
    assert!(with_records >= 2, "{with_records}");
}

/// The value of a POV-Ray function expression as `tools pov` writes them
/// (numbers, x, y, z, + − * /, comparisons giving 1 or 0, & and |,
/// max, ceil, mod), at the POV point (x, y, z): POV-Ray's function
/// semantics, small enough to check the export against our patterns.
fn eval(expr: &str, p: [f64; 3]) -> f64 {
    struct P<'a> {
        s: &'a [u8],
        i: usize,
        p: [f64; 3],
    }
    impl P<'_> {
        fn peek(&self) -> u8 {
            self.s.get(self.i).copied().unwrap_or(0)
        }
        fn eat(&mut self, c: u8) -> bool {
            let yes = self.peek() == c;
            self.i += usize::from(yes);
            yes
        }
        fn or(&mut self) -> f64 {
            let mut v = self.and();
            while self.eat(b'|') {
                let w = self.and();
                v = f64::from(v != 0.0 || w != 0.0);
            }
            v
        }
        fn and(&mut self) -> f64 {
            let mut v = self.cmp();
            while self.eat(b'&') {
                let w = self.cmp();
                v = f64::from(v != 0.0 && w != 0.0);
            }
            v
        }
        fn cmp(&mut self) -> f64 {
            let v = self.sum();
            for (op, f) in [
                ("<=", (|a, b| a <= b) as fn(f64, f64) -> bool),
                (">=", |a, b| a >= b),
                ("<", |a, b| a < b),
                (">", |a, b| a > b),
            ] {
                if self.s[self.i..].starts_with(op.as_bytes()) {
                    self.i += op.len();
                    let w = self.sum();
                    return f64::from(f(v, w));
                }
            }
            v
        }
        fn sum(&mut self) -> f64 {
            let mut v = self.product();
            loop {
                if self.eat(b'+') {
                    v += self.product();
                } else if self.eat(b'-') {
                    v -= self.product();
                } else {
                    return v;
                }
            }
        }
        fn product(&mut self) -> f64 {
            let mut v = self.atom();
            loop {
                if self.eat(b'*') {
                    v *= self.atom();
                } else if self.eat(b'/') {
                    v /= self.atom();
                } else {
                    return v;
                }
            }
        }
        fn atom(&mut self) -> f64 {
            if self.eat(b'(') {
                let v = self.or();
                assert!(self.eat(b')'), "no ) at {}", self.i);
                return v;
            }
            if self.eat(b'-') {
                return -self.atom();
            }
            let start = self.i;
            while self.peek().is_ascii_alphanumeric() || self.peek() == b'.' {
                self.i += 1;
            }
            let word = std::str::from_utf8(&self.s[start..self.i]).unwrap();
            // An exponent's sign (1e-9) belongs to the number.
            if word.ends_with('e') && word.as_bytes()[0].is_ascii_digit() && matches!(self.peek(), b'-' | b'+') {
                self.i += 1;
                while self.peek().is_ascii_digit() {
                    self.i += 1;
                }
                return std::str::from_utf8(&self.s[start..self.i]).unwrap().parse().unwrap();
            }
            match word {
                "x" => self.p[0],
                "y" => self.p[1],
                "z" => self.p[2],
                "max" | "ceil" | "mod" => {
                    assert!(self.eat(b'('));
                    let a = self.or();
                    let v = match word {
                        "ceil" => a.ceil(),
                        _ => {
                            assert!(self.eat(b','));
                            let b = self.or();
                            if word == "max" {
                                a.max(b)
                            } else {
                                a % b
                            }
                        }
                    };
                    assert!(self.eat(b')'));
                    v
                }
                _ => word
                    .parse()
                    .unwrap_or_else(|_| panic!("'{word}' in {}", std::str::from_utf8(self.s).unwrap())),
            }
        }
    }
    let mut parser = P {
        s: expr.as_bytes(),
        i: 0,
        p,
    };
    let v = parser.or();
    assert_eq!(parser.i, expr.len(), "{expr}");
    v
}

/// The text between `start` and the matching brace's `end` in `line`.
fn between<'a>(line: &'a str, start: &str, end: &str) -> &'a str {
    let from = line.find(start).unwrap_or_else(|| panic!("no {start} in {line}")) + start.len();
    &line[from..from + line[from..].find(end).unwrap()]
}

/// The numbers of `<a, b, c>` after `key` in `line`.
fn triple(line: &str, key: &str) -> [f64; 3] {
    let v: Vec<f64> = between(line, key, ">")
        .split(',')
        .map(|s| s.trim().parse().unwrap())
        .collect();
    [v[0], v[1], v[2]]
}

/// A deck of one painted object: `paint` on `shape`.
fn painted(shape: &str, paint: &str) -> String {
    format!(
        "view eye 0 -10 6 look 0 0 0 screen 4 distance 5
image 40 40 mask 1
light sun 3 -4 8  1 1 1
surface own opaque color 0.9 0.1 0.1  ka 0.2 kd 0.8 ks 0 kt 0
paint own {paint} color 0.1 0.2 0.8
{shape}
"
    )
}

/// A pseudo-random number in [0, 1).
fn hashed(k: u64) -> f64 {
    raytrace::hash::hashed_uniform(k)
}

/// `floor` is POV-Ray's `checker` placed so that its first colour (the
/// paint's: floor(X) + floor(Y) + floor(Z) even at the pattern's point) is
/// `floortest`'s painted squares, at points across a block's top face.
#[test]
fn a_floor_paint_is_a_checker_of_floortest_squares() {
    let text = scene_sdl(
        &scene(
            &painted("block slab own at 0 0 0 size 7 5 1", "floor scale 1.5 0.75"),
            Fidelity::Thesis,
        ),
        Fidelity::Thesis,
    );
    let line = line(&text, "box {");
    let colours = between(line, "checker ", " scale");
    assert!(
        colours.starts_with("rgbf <0.1, 0.2, 0.8, 0.0> rgbf <0.9, 0.1, 0.1, 0.0>"),
        "{line}"
    );
    let scale = triple(line, "scale <");
    let translate = triple(line, "translate <");
    let (h, depth) = ([3.5, 2.5], 0.5);
    let mut painted_points = 0;
    for k in 0..4000 {
        let (x, y) = (
            (hashed(2 * k) * 2.0 - 1.0) * h[0],
            (hashed(2 * k + 1) * 2.0 - 1.0) * h[1],
        );
        // POV's point <x, z, y> (ours x, y, z) on the top face.
        let p = [x, depth, y];
        let q: Vec<f64> = (0..3).map(|i| ((p[i] - translate[i]) / scale[i]).floor()).collect();
        let pov_first = (q[0] + q[1] + q[2]).rem_euclid(2.0) == 0.0;
        let ours = raytrace::proc::floortest(x + h[0], y + h[1], 1.5, 0.75).is_some();
        assert_eq!(pov_first, ours, "at ({x}, {y})");
        painted_points += usize::from(ours);
    }
    assert!(painted_points > 1000 && painted_points < 3000, "{painted_points}");
}

/// `star` and `floorstar` are `function` patterns, 1 where our procedure
/// paints, 0 where it does not (the listing's whole odd tiles too), at
/// points across a sphere and a block's top face.
#[test]
fn star_and_floorstar_paint_where_startest_and_floorstar_do() {
    for fidelity in FIDELITIES {
        let sphere = scene_sdl(
            &scene(
                &painted("sphere ball own at 0 0 0 radius 2", "star scale 1.2 0.8"),
                fidelity,
            ),
            fidelity,
        );
        let star = between(line(&sphere, "sphere {"), "function { ", " } color_map");
        let block = scene_sdl(
            &scene(
                &painted("block slab own at 0 0 0 size 9 7 1", "floorstar scale 1.1 0.9"),
                fidelity,
            ),
            fidelity,
        );
        let floorstar = between(line(&block, "box {"), "function { ", " } color_map");
        let (mut stars, mut tiles) = (0, 0);
        for k in 0..4000 {
            let (u, v) = (hashed(3 * k) * 2.0 - 1.0, hashed(3 * k + 1) * 2.0 - 1.0);
            // On the sphere of radius 2: our local (x, y, z), POV <x, z, y>.
            let (x, z) = (2.0 * u * 0.7, 2.0 * v * 0.7);
            let y = -(4.0 - x * x - z * z).sqrt();
            let ours = raytrace::proc::startest(x / 2.0 * 1.2, y / 2.0, z / 2.0 * 0.8, 1).is_some();
            assert_eq!(
                eval(star, [x, z, y]) == 1.0,
                ours,
                "{fidelity:?} star at ({x}, {y}, {z})"
            );
            stars += usize::from(ours);
            let (x, y) = (u * 4.5, v * 3.5);
            let ours = raytrace::proc::floorstar(x + 4.5, y + 3.5, 1.1, 0.9, fidelity).is_some();
            assert_eq!(
                eval(floorstar, [x, 0.5, y]) == 1.0,
                ours,
                "{fidelity:?} floorstar at ({x}, {y})"
            );
            tiles += usize::from(ours);
        }
        assert!(stars > 100 && tiles > 100, "{stars} {tiles}");
    }
}

/// `tools pov` writes a texture's picture beside the .pov as a PNG, the
/// raster's pixels, and names it in the SDL: a block's six faces each
/// with the picture, a cylinder's side by the cylindrical map and its
/// caps; nothing is said to be left out any more.
#[test]
fn a_texture_is_an_image_map_of_its_picture_written_beside() {
    let dir = tempfile::tempdir().unwrap();
    let decks = Path::new(env!("CARGO_MANIFEST_DIR")).join("../legacy_pascal/decks");
    for (deck, shape, faces) in [("fig5_3", "polygon {", 6), ("fig5_4", "map_type 2", 1)] {
        let out = dir.path().join(format!("{deck}.pov"));
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_tools"))
            .args(["pov", decks.join(format!("{deck}.deck")).to_str().unwrap(), "-o"])
            .arg(&out)
            .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(".."))
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let sdl = std::fs::read_to_string(&out).unwrap();
        let png = dir.path().join(format!("{deck}.picture.png"));
        let picture = raytrace::image_file::read_image_file(&png).unwrap();
        let card =
            raytrace::raster::read_raster_file(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../raster/card.tex.ras"))
                .unwrap();
        assert_eq!(picture, card, "{deck}");
        let named = format!("png \"{deck}.picture.png\"");
        assert_eq!(sdl.matches(shape).count(), faces, "{sdl}");
        assert!(sdl.matches(&named).count() >= faces, "{sdl}");
        assert!(!sdl.contains("not exported */"), "{sdl}");
    }
}

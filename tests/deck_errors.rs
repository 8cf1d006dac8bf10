//! `deck::initialize` on malformed decks: each case changes one thing in a
//! small valid deck and checks the exact message, line and column.

use std::path::Path;

use raytrace::deck::{initialize, DeckError};
use raytrace::options::Fidelity;
use raytrace::raster::read_raster_file;
use raytrace::scene::Scene;

/// A valid deck of 11 lines; the cases change one line or add lines 12….
const BASE: &str = "\
view eye 0 -10 4 look 0 0 1 screen 4 distance 5
image 64 64 mask 2
light sun 5 -5 10 1 1 1
surface red opaque color 1 0 0 ka 0.1 kd 0.7 ks 0.2 kt 0
sphere ball red at 0 0 1 radius 1
sweep wave red translation bspline at 0 0 0 length 2
  1 0
  0 1
  -1 0
  0 -1
end
";

/// A rotation sweep `vase` and a conic sweep `cone`, to add to BASE.
const MORE_SWEEPS: &str = "\
sweep vase red rotation bspline at 0 0 0
  0 0
  1 0
  1 1
  0 1
end
sweep wave2 red translation bspline at 0 0 0 length 1
  2 0
  0 2
  -2 0
  0 -2
end
";

fn read(deck: &str, fidelity: Fidelity) -> Result<Scene, DeckError> {
    initialize(deck, "t.deck", Path::new("decks"), fidelity)
}

/// BASE with `extra` added from line 12 on.
fn plus(extra: &str) -> String {
    format!("{BASE}{extra}")
}

/// BASE with line `n` (1-based) replaced by `with`.
fn replacing(n: usize, with: &str) -> String {
    let mut lines: Vec<&str> = BASE.lines().collect();
    lines[n - 1] = with;
    lines.join("\n") + "\n"
}

#[track_caller]
fn check(deck: &str, expected: &str) {
    match read(deck, Fidelity::Thesis) {
        Ok(_) => panic!("the deck was accepted, expected {expected}"),
        Err(e) => assert_eq!(e.to_string(), expected),
    }
}

#[test]
fn the_base_decks_are_valid() {
    let s = read(BASE, Fidelity::Thesis).unwrap();
    assert_eq!(s.objects.len(), 2);
    let s = read(&plus(MORE_SWEEPS), Fidelity::Thesis).unwrap();
    assert_eq!(s.objects.len(), 4);
}

#[test]
fn error_fields_are_kept() {
    let e = read(
        &replacing(6, "sweep wave red translation bspline at 0 0 0 length lenght"),
        Fidelity::Thesis,
    )
    .unwrap_err();
    assert_eq!(
        e,
        DeckError {
            file: "t.deck".into(),
            line: 6,
            column: 52,
            record: "sweep".into(),
            name: Some("wave".into()),
            message: "expected a number after 'length', found 'lenght'".into(),
        }
    );
    assert_eq!(
        e.to_string(),
        "t.deck:6:52: sweep 'wave': expected a number after 'length', found 'lenght'"
    );
}

// Lexical errors.

#[test]
fn unterminated_brace_comment_between_records() {
    check(
        &plus("{ never closed\nsphere b2 red at 0 0 3 radius 1\n"),
        "t.deck:12:1: deck: unterminated comment: '{' has no '}'",
    );
}

#[test]
fn unterminated_paren_comment_in_a_record() {
    check(
        &plus("sphere b2 red at 0 0 3 radius 1 (* open\n"),
        "t.deck:12:33: sphere 'b2': unterminated comment: '(*' has no '*)'",
    );
}

#[test]
fn nested_comment_is_named_at_its_inner_opener() {
    let cases = [
        (
            "{ a { b } c }\n",
            "12:5: deck",
            "{",
            "}",
            "12:1, the '}' at 12:9 ends that comment, and the '}' at 12:13",
        ),
        (
            "sphere b2 red at 0 0 3 { big {\n very } } radius 1\n",
            "12:30: sphere 'b2'",
            "{",
            "}",
            "12:24, the '}' at 13:7 ends that comment, and the '}' at 13:9",
        ),
        // The stray closer is found past a comment of the other kind.
        (
            "(* a (* b *) c { d *) } *)\n",
            "12:6: deck",
            "(*",
            "*)",
            "12:1, the '*)' at 12:11 ends that comment, and the '*)' at 12:25",
        ),
    ];
    for (deck, at, open, close, rest) in cases {
        let inner = format!("'{open} … {close}' comments do not nest (Pascal's), so this '{open}' is text");
        let expected = format!(
            "t.deck:{at}: a comment inside a comment: {inner} of the comment opened at {rest} is outside any comment"
        );
        check(&plus(deck), &expected);
    }
    // Valid Pascal (the inner '{' is text); the lexer's tests hold the rest.
    assert!(read(&plus("{ a { b }\n{ c }\n"), Fidelity::Thesis).is_ok());
}

#[test]
fn malformed_number() {
    check(
        &plus("sphere b2 red at 0 0 1.2.3 radius 1\n"),
        "t.deck:12:22: sphere 'b2': expected a number after 'at', found '1.2.3'",
    );
}

#[test]
fn name_longer_than_ten_characters() {
    check(
        &plus("sphere abcdefghijk red at 0 0 3 radius 1\n"),
        "t.deck:12:8: sphere: the name 'abcdefghijk' is longer than 10 characters",
    );
}

#[test]
fn number_where_a_name_is_expected() {
    check(
        &plus("sphere 5 red at 0 0 3 radius 1\n"),
        "t.deck:12:8: sphere: expected an object name, found the number '5'",
    );
}

#[test]
fn name_with_a_bad_character() {
    check(
        &plus("light la-mp 0 0 0 1 1 1\n"),
        "t.deck:12:7: light: expected a light name (letters, digits and '_'), found 'la-mp'",
    );
}

// Records and fields.

#[test]
fn unknown_record() {
    check(
        &plus("sphear b2 red at 0 0 3 radius 1\n"),
        "t.deck:12:1: deck: unknown record 'sphear' — did you mean 'sphere'?",
    );
}

#[test]
fn misplaced_field() {
    check(
        &plus("sphere b2 red radius 1 at 0 0 0\n"),
        "t.deck:12:15: sphere 'b2': expected 'at', found 'radius' — 'at' comes before 'radius'",
    );
}

#[test]
fn field_out_of_order_misspelt_or_given_twice() {
    let cases = [
        (4, "surface red opaque color 1 0 0 kd 0.7 ka 0.1 ks 0.2 kt 0", "4:32: surface 'red': expected 'ka', found 'kd' — 'ka' comes before 'kd'"),
        (5, "sphere ball red at 0 0 1 radus 1", "5:26: sphere 'ball': expected 'radius', found 'radus' — did you mean 'radius'?"),
        (1, "view look 0 0 1 eye 0 -10 4 screen 4 distance 5", "1:6: view: expected 'eye', found 'look' — 'eye' comes before 'look'"),
        (1, "view eye 0 -10 4 eye 0 0 1 screen 4 distance 5", "1:18: view: expected 'look', found 'eye' — the field 'eye' is given twice"),
        // An optional field before a required one.
        (5, "cylinder ball red at 0 0 1 radius 1 bottom 0 axis x top 1", "5:46: cylinder 'ball': expected 'top', found 'axis' — 'top' comes before 'axis'"),
        // A required field again among the optional ones.
        (4, "surface red opaque color 1 0 0 ka 0.1 kd 0.7 ks 0.2 kt 0 color 1 1 1", "4:58: surface 'red': expected end of line or 'ambient', 'reflect', 'index', 'gloss', found 'color' — the field 'color' is given twice"),
        // A word that is no slip of a field gets no suggestion.
        (5, "sphere ball red at 0 0 1 size 1", "5:26: sphere 'ball': expected 'radius', found 'size'"),
    ];
    for (line, text, expected) in cases {
        check(&replacing(line, text), &format!("t.deck:{expected}"));
    }
}

#[test]
fn extra_token_at_the_end_of_a_record() {
    check(
        &plus("delete ball now\n"),
        "t.deck:12:13: delete 'ball': expected end of line, found 'now'",
    );
}

#[test]
fn missing_number_at_the_end_of_a_line() {
    check(
        &plus("translate ball 1 2\n"),
        "t.deck:12:19: translate 'ball': expected a number for Z, found end of line",
    );
}

#[test]
fn second_view() {
    check(
        &plus("view eye 0 -10 4 look 0 0 1 screen 4 distance 5\n"),
        "t.deck:12:1: view: a second 'view' record (the first is on line 1)",
    );
}

#[test]
fn eye_straight_above_look() {
    check(
        &replacing(1, "view eye 0 0 10 look 0 0 1 screen 4 distance 5"),
        "t.deck:1:17: view: the eye is straight above or below the look point (world z must be up in the image)",
    );
}

#[test]
fn screen_not_positive() {
    check(
        &replacing(1, "view eye 0 -10 4 look 0 0 1 screen 0 distance 5"),
        "t.deck:1:36: view: expected a number in 1e-7..1e7 after 'screen', found '0'",
    );
}

#[test]
fn image_mask_out_of_range() {
    check(
        &replacing(2, "image 64 64 mask 9"),
        "t.deck:2:18: image: expected an integer in 1..8 after 'mask', found '9'",
    );
}

#[test]
fn image_width_not_an_integer() {
    check(
        &replacing(2, "image 64. 64 mask 2"),
        "t.deck:2:7: image: expected an integer for WIDTH, found '64.'",
    );
}

#[test]
fn image_aliasing_out_of_range() {
    check(
        &replacing(2, "image 64 64 mask 2 aliasing 2"),
        "t.deck:2:29: image: expected a number in 0..1 after 'aliasing', found '2'",
    );
}

#[test]
fn missing_view_is_reported_at_the_end_of_the_deck() {
    let deck: String = BASE.lines().skip(1).map(|l| format!("{l}\n")).collect();
    check(&deck, "t.deck:10:4: view: the deck has no 'view' record");
    check("", "t.deck:1:1: view: the deck has no 'view' record");
}

#[test]
fn missing_image() {
    check(
        &replacing(2, "{ no image }"),
        "t.deck:11:4: image: the deck has no 'image' record",
    );
}

#[test]
fn surface_coefficient_out_of_range() {
    check(
        &replacing(4, "surface red opaque color 1 0 0 ka 1.5 kd 0.7 ks 0.2 kt 0"),
        "t.deck:4:35: surface 'red': expected a number in 0..1 after 'ka', found '1.5'",
    );
}

#[test]
fn surface_colour_above_one_on_an_opaque_surface() {
    check(
        &replacing(4, "surface red opaque color 2 0 0 ka 0.1 kd 0.7 ks 0.2 kt 0"),
        "t.deck:4:26: surface 'red': expected a number in 0..1 after 'color', found '2'",
    );
}

#[test]
fn surface_unknown_kind() {
    check(
        &plus("surface s2 plastic color 1 0 0 ka 0 kd 1 ks 0 kt 0\n"),
        "t.deck:12:12: surface 's2': expected a surface kind (opaque, mirrored, transparent, crystal, light, background), found 'plastic'",
    );
}

#[test]
fn surface_field_given_twice() {
    check(
        &plus("surface s2 mirrored color 1 0 0 ka 0 kd 1 ks 0 kt 0 reflect 0.5 REFLECT 0.5\n"),
        "t.deck:12:65: surface 's2': the field 'reflect' is given twice",
    );
}

#[test]
fn surface_index_not_positive() {
    check(
        &plus("surface s2 transparent color 1 1 1 ka 0 kd 0 ks 0 kt 1 index 0\n"),
        "t.deck:12:62: surface 's2': expected a number in 1e-7..1e7 after 'index', found '0'",
    );
}

#[test]
fn duplicate_surface() {
    check(
        &plus("surface red opaque color 1 0 0 ka 0 kd 1 ks 0 kt 0\n"),
        "t.deck:12:9: surface 'red': the surface name 'red' is already used on line 4",
    );
}

#[test]
fn duplicate_light() {
    check(
        &plus("light sun 0 0 1 1 1 1\n"),
        "t.deck:12:7: light 'sun': the light name 'sun' is already used on line 3",
    );
}

#[test]
fn unknown_paint() {
    check(
        &plus("paint red checker\n"),
        "t.deck:12:11: paint 'red': expected a pattern (floor, star, floorstar), found 'checker'",
    );
}

#[test]
fn paint_and_texture_on_one_surface() {
    check(
        &plus("paint red floor\ntexture red pic.ras\n"),
        "t.deck:13:9: texture 'red': the surface already has a paint (line 12); it may have one paint or texture",
    );
}

#[test]
fn texture_file_that_cannot_be_read() {
    let deck = plus("texture red no_such.ras\n");
    let e = read(&deck, Fidelity::Thesis).unwrap_err();
    let reader = read_raster_file(&Path::new("decks").join("no_such.ras")).unwrap_err();
    assert_eq!((e.line, e.column), (12, 13));
    assert_eq!((e.record.as_str(), e.name.as_deref()), ("texture", Some("red")));
    // The path as written, then where it was looked for (from the deck's
    // folder, here `decks`).
    let looked = Path::new("decks").join("no_such.ras");
    assert_eq!(
        e.message,
        format!(
            "cannot read the raster file 'no_such.ras': {reader}; from the deck's folder, that is '{}'",
            looked.display()
        )
    );
    // A deck in the working folder: the path as written is where it was looked for.
    let e = initialize(&deck, "t.deck", Path::new(""), Fidelity::Thesis).unwrap_err();
    assert_eq!(
        e.message,
        format!("cannot read the raster file 'no_such.ras': {reader}")
    );
}

// Objects.

#[test]
fn unknown_surface() {
    check(
        &plus("sphere b2 blue at 0 0 3 radius 1\n"),
        "t.deck:12:11: sphere 'b2': unknown surface 'blue'",
    );
}

#[test]
fn duplicate_object() {
    check(
        &plus("block ball red at 0 0 0 size 1 1 1\n"),
        "t.deck:12:7: block 'ball': the object name 'ball' is already used on line 5",
    );
}

#[test]
fn block_edge_not_positive() {
    check(
        &plus("block b2 red at 0 0 0 size 1 0 1\n"),
        "t.deck:12:30: block 'b2': expected a number in 1e-7..1e7 after 'size', found '0'",
    );
}

#[test]
fn cylinder_top_below_bottom() {
    check(
        &plus("cylinder c red at 0 0 0 radius 1 bottom 2 top 1\n"),
        "t.deck:12:47: cylinder 'c': expected a number > 2 after 'top', found '1'",
    );
}

#[test]
fn prism_not_convex() {
    check(
        &plus("prism p red at 0 0 0 height 1\n 0 0\n 2 0\n 1 0.5\n 2 2\n 0 2\nend\n"),
        "t.deck:15:2: prism 'p': the polygon is not convex at vertex 3",
    );
}

#[test]
fn prism_vertices_in_line() {
    check(
        &plus("prism p red at 0 0 0 height 1\n 0 0\n 1 0\n 2 0\n 1 1\nend\n"),
        "t.deck:14:2: prism 'p': vertex 2 is in line with its neighbours or repeats one",
    );
}

#[test]
fn prism_with_two_vertices() {
    check(
        &plus("prism p red at 0 0 0 height 1\n 0 0\n 1 0\nend\n"),
        "t.deck:15:1: prism 'p': a prism needs at least 3 vertices, found 2",
    );
}

#[test]
fn point_line_with_three_numbers() {
    check(
        &plus("prism p red at 0 0 0 height 1\n 0 0 0\n"),
        "t.deck:13:6: prism 'p': expected end of line after the point 'U V', found '0'",
    );
}

#[test]
fn point_list_without_end() {
    check(
        &plus("prism p red at 0 0 0 height 1\n 0 0\n 1 0\n 0 1\n"),
        "t.deck:15:5: prism 'p': expected a point 'U V' or 'end', found end of file",
    );
}

// Sweeps.

#[test]
fn bezier_count_not_a_multiple_of_three() {
    check(
        &plus("sweep b red translation bezier at 0 0 0 length 1\n 1 0\n 1 1\n 0 1\n -1 0\n -1 -1\n 0 -1\n 1 -1\nend\n"),
        "t.deck:20:1: sweep 'b': a bezier contour needs a multiple of 3 points, found 7",
    );
}

#[test]
fn bezier_single_segment() {
    check(
        &plus("sweep b red translation bezier at 0 0 0 length 1\n 1 0\n 1 1\n 0 1\nend\n"),
        "t.deck:16:1: sweep 'b': a bezier contour needs at least 6 points (2 segments), found 3",
    );
}

#[test]
fn bspline_with_three_points() {
    check(
        &plus("sweep b red translation bspline at 0 0 0 length 1\n 1 0\n 0 1\n -1 0\nend\n"),
        "t.deck:16:1: sweep 'b': a bspline contour needs at least 4 points, found 3",
    );
}

#[test]
fn more_than_sixty_segments() {
    let points: String = (0..61)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 61.0;
            format!(" {:.4} {:.4}\n", a.cos(), a.sin())
        })
        .collect();
    check(
        &plus(&format!(
            "sweep b red translation bspline at 0 0 0 length 1\n{points}end\n"
        )),
        "t.deck:73:2: sweep 'b': more than 60 segments: a bspline contour has one segment per point",
    );
}

#[test]
fn rotation_contour_with_negative_u() {
    check(
        &plus("sweep r red rotation bspline at 0 0 0\n 0 0\n 1 0\n -0.5 1\n 0 1\nend\n"),
        "t.deck:15:2: sweep 'r': expected a number >= 0 for U (a radius), found '-0.5'",
    );
}

#[test]
fn length_not_positive() {
    check(
        &replacing(6, "sweep wave red translation bspline at 0 0 0 length 0"),
        "t.deck:6:52: sweep 'wave': expected a number in 1e-7..1e7 after 'length', found '0'",
    );
}

#[test]
fn length_missing() {
    check(
        &replacing(6, "sweep wave red translation bspline at 0 0 0"),
        "t.deck:6:44: sweep 'wave': a translation sweep needs 'length L'",
    );
}

#[test]
fn length_on_a_rotation_sweep() {
    check(
        &replacing(6, "sweep wave red rotation bspline at 0 0 0 length 2"),
        "t.deck:6:42: sweep 'wave': a rotation sweep takes no 'length'",
    );
}

#[test]
fn conic_scale_negative() {
    check(
        &replacing(6, "sweep wave red conic bspline at 0 0 0 length 2 scale -1"),
        "t.deck:6:54: sweep 'wave': expected a number >= 0 after 'scale', found '-1'",
    );
}

#[test]
fn scale_on_a_translation_sweep() {
    check(
        &replacing(6, "sweep wave red translation bspline at 0 0 0 length 2 scale 2"),
        "t.deck:6:54: sweep 'wave': only a conic sweep takes 'scale', not a translation sweep",
    );
}

#[test]
fn unknown_sweep_field() {
    check(
        &replacing(6, "sweep wave red translation bspline at 0 0 0 lenght 2"),
        "t.deck:6:45: sweep 'wave': expected end of line or 'length', 'scale', 'axis', found 'lenght' — did you mean 'length'?",
    );
}

// Rotate, translate, delete.

#[test]
fn rotate_unknown_object() {
    check(
        &plus("rotate boll z 10\n"),
        "t.deck:12:8: rotate: unknown object 'boll' — did you mean 'ball'?",
    );
}

#[test]
fn rotate_about_an_unknown_axis() {
    check(
        &plus("rotate ball w 10\n"),
        "t.deck:12:13: rotate 'ball': expected an axis (x, y, z), found 'w'",
    );
}

#[test]
fn deleted_object_is_unknown() {
    check(
        &plus("delete ball\nrotate ball z 10\n"),
        "t.deck:13:8: rotate: unknown object 'ball'",
    );
}

// Motion.

#[test]
fn motion_unknown_law() {
    check(
        &plus("motion ball to 1 2 3 law jerky\n"),
        "t.deck:12:26: motion 'ball': expected a law (constant, accelerate, decelerate, smooth), found 'jerky'",
    );
}

#[test]
fn motion_of_an_unknown_object() {
    check(
        &plus("motion bal to 1 2 3\n"),
        "t.deck:12:8: motion: unknown object 'bal' — did you mean 'ball'?",
    );
}

#[test]
fn second_motion_of_an_object() {
    check(
        &plus("motion ball to 1 2 3\nmotion ball to 3 2 1\n"),
        "t.deck:13:8: motion 'ball': 'ball' already has a motion (line 12)",
    );
}

#[test]
fn turning_an_object_after_its_motion() {
    check(
        &plus("motion ball to 1 2 3\nrotate ball x 10\n"),
        "t.deck:13:8: rotate 'ball': 'ball' has a motion (line 12) and can no longer be turned",
    );
}

// Key frames.

#[test]
fn keyframe_classes_differ() {
    check(
        &plus(&format!("{MORE_SWEEPS}keyframe wave vase\n")),
        "t.deck:24:15: keyframe 'wave': 'vase' is a rotation sweep but 'wave' is a translation sweep: key shapes must be of one class",
    );
}

#[test]
fn keyframe_names_an_object_twice() {
    check(
        &plus(&format!("{MORE_SWEEPS}keyframe wave wave2 wave\n")),
        "t.deck:24:21: keyframe 'wave': 'wave' is named twice in this keyframe",
    );
}

#[test]
fn key_shape_in_two_keyframes() {
    let sweep3 = "sweep wave3 red translation bspline at 0 0 0 length 1\n 1 0\n 0 1\n -1 0\n 0 -1\nend\n";
    check(
        &plus(&format!(
            "{MORE_SWEEPS}{sweep3}keyframe wave wave2\nkeyframe wave3 wave2\n"
        )),
        "t.deck:31:16: keyframe 'wave3': 'wave2' is already a key shape of the keyframe on line 30",
    );
}

#[test]
fn keyframe_of_a_sphere() {
    check(
        &plus("keyframe ball wave\n"),
        "t.deck:12:10: keyframe 'ball': 'ball' is a sphere, not a sweep, blob or patch: key shapes are sweeps of one class, blobs or patches",
    );
}

#[test]
fn keyframe_with_one_shape() {
    check(
        &plus("keyframe wave expander burtnyk\n"),
        "t.deck:12:15: keyframe 'wave': expected the LAST key shape's name, found 'expander'",
    );
}

#[test]
fn keyframe_last_shape_is_no_longer_in_the_scene() {
    check(
        &plus(&format!("{MORE_SWEEPS}keyframe wave wave2\ndelete wave2\n")),
        "t.deck:25:8: delete 'wave2': 'wave2' is a key shape (keyframe on line 24) and can no longer be deleted",
    );
}

#[test]
fn motion_of_a_key_shape() {
    check(
        &plus(&format!("{MORE_SWEEPS}keyframe wave wave2\nmotion wave to 0 0 1\n")),
        "t.deck:25:8: motion 'wave': 'wave' is a key shape (keyframe on line 24) and cannot have a motion",
    );
}

#[test]
fn keyframe_unknown_expander() {
    check(
        &plus(&format!("{MORE_SWEEPS}keyframe wave wave2 expander linear\n")),
        "t.deck:24:30: keyframe 'wave': expected an expander (burtnyk, arclength), found 'linear'",
    );
}

// Blur and pattern.

#[test]
fn blur_negative() {
    check(
        &plus("blur -1\n"),
        "t.deck:12:6: blur: expected an integer in 0..1000 for N, found '-1'",
    );
}

#[test]
fn blur_not_an_integer() {
    check(
        &plus("blur 1.5\n"),
        "t.deck:12:6: blur: expected an integer for N, found '1.5'",
    );
}

#[test]
fn second_blur() {
    check(
        &plus("blur 2\nBLUR 3\n"),
        "t.deck:13:1: blur: a second 'blur' record (the first is on line 12)",
    );
}

#[test]
fn pattern_not_a_permutation_in_thesis_fidelity_but_accepted_in_listing() {
    let deck = plus("pattern 2\n 0 1\n 1 3\nend\n");
    check(
        &deck,
        "t.deck:14:2: pattern: the value 1 appears twice: the table must be a permutation of 0..3 (erratum 1; the listing fidelity accepts repeats)",
    );
    let s = read(&deck, Fidelity::Listing).unwrap();
    assert_eq!(s.pattern.map(|p| p.values), Some(vec![vec![0, 1], vec![1, 3]]));
}

#[test]
fn pattern_value_out_of_range() {
    check(
        &plus("pattern 2\n 0 1\n 2 4\nend\n"),
        "t.deck:14:4: pattern: expected an integer in 0..3 for row 2, found '4'",
    );
}

#[test]
fn pattern_ends_early() {
    check(
        &plus("pattern 2\n 0 1\nend\n"),
        "t.deck:14:1: pattern: expected row 2 of 2, found 'end'",
    );
}

#[test]
fn pattern_row_too_long() {
    check(
        &plus("pattern 2\n 0 1 2\n"),
        "t.deck:13:6: pattern: expected end of line, found '2'",
    );
}

// Robustness: nothing panics, whatever the bytes.

#[test]
fn every_prefix_and_mangled_line_reads_without_panicking() {
    let deck = plus(&format!(
        "{MORE_SWEEPS}keyframe wave wave2\nmotion ball to 1 2 3 via 0 0 1 1 1 1 law smooth\n\
         prism p red at 0 0 0 height 1 axis x\n 0 0\n 1 0\n 0 1\nend\npattern 2\n 0 1\n 2 3\nend\nblur 3\n{{ end }}\n"
    ));
    let lines = deck.lines().count() as u32;
    assert!(read(&deck, Fidelity::Thesis).is_ok());
    let mut errors = 0;
    for (cut, _) in deck.char_indices() {
        if let Err(e) = read(&deck[..cut], Fidelity::Thesis) {
            assert!(e.line >= 1 && e.line <= lines, "{e}");
            errors += 1;
        }
    }
    assert!(errors > 0);
    // Replace each word in turn by garbage of several kinds.
    let words: Vec<(usize, usize)> = deck
        .char_indices()
        .filter(|&(i, c)| !c.is_whitespace() && (i == 0 || deck[..i].ends_with(char::is_whitespace)))
        .map(|(i, _)| (i, deck[i..].find(char::is_whitespace).map_or(deck.len(), |n| i + n)))
        .collect();
    for &(a, b) in &words {
        for junk in [
            "",
            "x",
            "-1",
            "1e999",
            "{",
            "(*",
            "é",
            "0",
            "end",
            "9999999999999999999999",
        ] {
            let mangled = format!("{}{}{}", &deck[..a], junk, &deck[b..]);
            let _ = read(&mangled, Fidelity::Thesis);
            let _ = read(&mangled, Fidelity::Listing);
        }
    }
}

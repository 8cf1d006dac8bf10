//! `tools fuzz`: a mutation fuzzer for the deck reader and the raster
//! reader, on stable Rust (cargo-fuzz needs a nightly toolchain). The port's
//! own tool; the thesis has nothing like it.
//!
//! Each input is a seed from the repository (the decks of legacy_pascal/
//! and tests/, the rasters of raster/ and tests/) changed by a few random
//! mutations: bits flipped, bytes set, ranges cut or doubled, tokens and
//! numbers put in, two inputs spliced. An input whose outcome is of a kind
//! not seen yet (an error message of a new shape, a deck accepted with a new
//! mix of objects) joins the pool, so the loop works its way into the
//! reader. The random numbers come from one seed: a run with the same seed
//! and input count tries the same inputs.
//!
//! What counts as a finding, for a deck: a panic of `initialize`, `prepare`
//! or a tiny render; an error whose line and column are not in the deck, or
//! whose message holds a control character or is longer than
//! [`MAX_MESSAGE`]; an accepted deck whose tiny render has a colour that is
//! not finite. For a raster: a panic of `read_raster`; a raster whose pixel
//! count is not width × height, or that does not read back the same after
//! `encode_raster`; an error message as above.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use raytrace::options::{Fidelity, Options};
use raytrace::raster::{encode_raster, read_raster};
use raytrace::raytrace::{render, Prepared, Request};

/// The longest error message that is not a finding (a message must cut what
/// it echoes).
pub const MAX_MESSAGE: usize = 400;

/// The largest input the mutations make.
const MAX_INPUT: usize = 256 << 10;

/// The largest pool of inputs.
const MAX_POOL: usize = 4096;

/// What is fuzzed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// `deck::initialize`, then `prepare` and a 4×4 render of what it accepts.
    Deck,
    /// `raster::read_raster`.
    Raster,
}

/// One input that broke a promise, and which.
#[derive(Clone, Debug)]
pub struct Finding {
    pub input: Vec<u8>,
    pub what: String,
}

/// What a run did.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Inputs tried.
    pub inputs: u64,
    /// Inputs the reader accepted.
    pub accepted: u64,
    /// Distinct outcomes seen (error shapes, accepted object mixes).
    pub outcomes: usize,
    pub findings: Vec<Finding>,
    pub elapsed: Duration,
}

/// How an input came out: its kind (for the pool) or a finding.
pub enum Outcome {
    Accepted(String),
    Refused(String),
    Finding(String),
}

/// splitmix64: a small, fast generator; a run is reproducible from its seed.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number in [0, 1), of 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A number in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }
}

/// Words and numbers the deck mutations put in: keywords, numbers at and
/// past the deck's ranges, comment brackets, bytes that are not ASCII.
const DECK_WORDS: &[&str] = &[
    "view",
    "image",
    "surface",
    "sphere",
    "block",
    "cylinder",
    "prism",
    "sweep",
    "motion",
    "keyframe",
    "pattern",
    "blur",
    "rotate",
    "translate",
    "delete",
    "end",
    "at",
    "radius",
    "length",
    "scale",
    "axis",
    "via",
    "turn",
    "expander",
    "burtnyk",
    "texture",
    "paint",
    "path",
    "by",
    "include",
    "0",
    "-0",
    "1",
    "1e7",
    "-1e7",
    "1.0000001e7",
    "1e-7",
    "9e-8",
    "1e155",
    "1e308",
    "1e400",
    "1e-320",
    "0.5",
    "2.",
    ".5",
    "8192",
    "8193",
    "60",
    "{",
    "}",
    "(*",
    "*)",
    "\n",
    "end\n",
    "\u{e9}",
    "\u{0}",
    "\x1b",
];

/// Big-endian words the raster mutations write into the header.
const RASTER_WORDS: &[u32] = &[
    0,
    1,
    2,
    3,
    4,
    5,
    8,
    24,
    32,
    255,
    256,
    768,
    8192,
    8193,
    0x59a6_6a95,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_ffff,
    0x0001_0000,
    46341,
];

/// Bytes the mutations set.
const BYTES: &[u8] = b"\0\xff\n {}(*-.e0123456789\x80\xe9\x80";

/// One mutation of `input`; `other` is a second input for splicing.
fn mutate(rng: &mut Rng, target: Target, input: &mut Vec<u8>, other: &[u8]) {
    let len = input.len();
    match rng.below(8) {
        0 if len > 0 => {
            let i = rng.below(len);
            input[i] ^= 1 << rng.below(8);
        }
        1 if len > 0 => {
            let i = rng.below(len);
            input[i] = BYTES[rng.below(BYTES.len())];
        }
        2 if len > 0 => {
            let i = rng.below(len);
            let n = (1 + rng.below(16)).min(len - i);
            input.drain(i..i + n);
        }
        3 if len > 0 => {
            let i = rng.below(len);
            let n = (1 + rng.below(64)).min(len - i);
            let piece = input[i..i + n].to_vec();
            let at = rng.below(len + 1);
            input.splice(at..at, piece);
        }
        4 => {
            let at = rng.below(len + 1);
            let other_at = rng.below(other.len() + 1);
            input.truncate(at);
            input.extend_from_slice(&other[other_at..]);
        }
        5 | 6 if target == Target::Deck => {
            // A word or number in place of a word, or put in.
            let word = DECK_WORDS[rng.below(DECK_WORDS.len())].as_bytes();
            let at = rng.below(len + 1);
            if rng.below(2) == 0 {
                let end = input[at..]
                    .iter()
                    .position(|b| b.is_ascii_whitespace())
                    .map_or(len, |k| at + k);
                input.splice(at..end, word.iter().copied());
            } else {
                input.splice(at..at, b" ".iter().chain(word).chain(b" ").copied());
            }
        }
        5 | 6 => {
            // A header word (the first 32 bytes), or any word.
            let at = if rng.below(2) == 0 {
                4 * rng.below(8)
            } else {
                rng.below(len + 1)
            };
            let word = RASTER_WORDS[rng.below(RASTER_WORDS.len())].to_be_bytes();
            for (k, b) in word.iter().enumerate() {
                if let Some(x) = input.get_mut(at + k) {
                    *x = *b;
                }
            }
        }
        7 if target == Target::Deck => {
            // A number in place of a number: ±10^k for k in -9..=9, a
            // mantissa of 1 to 10, so that the range's edges are tried.
            let starts: Vec<usize> = (0..len)
                .filter(|&i| input[i].is_ascii_digit() && (i == 0 || input[i - 1].is_ascii_whitespace()))
                .collect();
            if !starts.is_empty() {
                let at = starts[rng.below(starts.len())];
                let end = input[at..]
                    .iter()
                    .position(|b| b.is_ascii_whitespace())
                    .map_or(len, |k| at + k);
                let sign = if rng.below(2) == 0 { "" } else { "-" };
                let mantissa = 1.0 + rng.below(9000) as f64 / 1000.0;
                let exp = rng.below(19) as i32 - 9;
                let number = format!("{sign}{mantissa}e{exp}");
                input.splice(at..end, number.bytes());
            }
        }
        _ => {
            let at = rng.below(len + 1);
            input.insert(at, BYTES[rng.below(BYTES.len())]);
        }
    }
    input.truncate(MAX_INPUT);
}

/// The shape of an error message: its words without numbers and quoted
/// parts, so that errors differing only in their values count as one.
fn shape(message: &str) -> String {
    let mut out = String::new();
    let mut quoted = false;
    for c in message.chars() {
        if c == '\'' {
            quoted = !quoted;
        } else if !quoted && !c.is_ascii_digit() {
            out.push(c);
        }
    }
    out.chars().take(80).collect()
}

/// A message's faults: a control character, or too long.
fn message_fault(message: &str) -> Option<String> {
    if let Some(c) = message.chars().find(|c| c.is_control()) {
        return Some(format!("the message holds the control character {c:?}: {message:?}"));
    }
    (message.chars().count() > MAX_MESSAGE).then(|| format!("a message of {} characters", message.chars().count()))
}

/// Where `pos` can be in `input`: line 1..=lines, column 1..=line length + 1
/// (in bytes, an upper bound on characters).
fn position_fault(input: &[u8], line: u32, column: u32) -> Option<String> {
    let lines: Vec<&[u8]> = input.split(|&b| b == b'\n').collect();
    let Some(text) = (line as usize).checked_sub(1).and_then(|i| lines.get(i)) else {
        return Some(format!("line {line} is not in the deck ({} lines)", lines.len()));
    };
    if column == 0 || column as usize > text.len() + 1 {
        return Some(format!("column {column} is not on line {line} ({} bytes)", text.len()));
    }
    None
}

/// Reads, prepares and renders (4×4, one subpixel) a deck; `dir` is where
/// its textures are.
pub fn check_deck(input: &[u8], dir: &Path) -> Outcome {
    let read = catch_unwind(AssertUnwindSafe(|| {
        raytrace::deck::initialize(input, "fuzz.deck", dir, Fidelity::Thesis)
    }));
    let mut scene = match read {
        Err(_) => return Outcome::Finding("initialize panicked".into()),
        Ok(Err(e)) => {
            let message = e.to_string();
            // An error in a file the input includes stands in that file.
            let own = || {
                (e.file == "fuzz.deck")
                    .then(|| position_fault(input, e.line, e.column))
                    .flatten()
            };
            if let Some(f) = message_fault(&message).or_else(own) {
                return Outcome::Finding(f);
            }
            return Outcome::Refused(format!("{}: {}", e.record, shape(&e.message)));
        }
        Ok(Ok(scene)) => scene,
    };
    let mut kinds: Vec<String> = scene.objects.iter().map(|o| format!("{:?}", o.class)).collect();
    kinds.sort();
    kinds.dedup();
    let kind = format!("{} keyframes {}", kinds.join(" "), scene.keyframes.len());
    let opts = Options::default();
    // Preparing does not depend on the image's size.
    scene.image.width = 4;
    scene.image.height = 4;
    scene.image.masksize = 1;
    let prepared = match catch_unwind(AssertUnwindSafe(|| Prepared::new(scene, opts))) {
        Err(_) => return Outcome::Finding("prepare panicked".into()),
        Ok(Err(e)) => return Outcome::Refused(format!("prepare: {}", shape(&e.to_string()))),
        Ok(Ok(p)) => p,
    };
    match catch_unwind(AssertUnwindSafe(|| render(&prepared, &Request::STILL))) {
        Err(_) => Outcome::Finding("render panicked".into()),
        Ok(Err(e)) => Outcome::Finding(format!("a whole image refused: {e}")),
        Ok(Ok(r)) if r.nonfinite > 0 => Outcome::Finding(format!("{} of 16 pixels not finite", r.nonfinite)),
        Ok(Ok(_)) => Outcome::Accepted(kind),
    }
}

/// Reads a raster and checks what it gives.
pub fn check_raster(input: &[u8]) -> Outcome {
    match catch_unwind(AssertUnwindSafe(|| read_raster(input))) {
        Err(_) => Outcome::Finding("read_raster panicked".into()),
        Ok(Err(e)) => match message_fault(&e.to_string()) {
            Some(f) => Outcome::Finding(f),
            None => Outcome::Refused(shape(&e.to_string())),
        },
        Ok(Ok(r)) => {
            if r.width.checked_mul(r.height) != Some(r.pixels.len()) {
                return Outcome::Finding(format!("{} pixels for {}×{}", r.pixels.len(), r.width, r.height));
            }
            match read_raster(&encode_raster(&r)) {
                Ok(back) if back.pixels == r.pixels && (back.width, back.height) == (r.width, r.height) => {
                    Outcome::Accepted(format!("{}", r.width.min(2) * r.height.min(2)))
                }
                _ => Outcome::Finding("the raster does not read back the same after encode_raster".into()),
            }
        }
    }
}

/// How long and from what a run goes.
pub struct Config {
    pub seed: u64,
    /// Stop after this many inputs.
    pub inputs: u64,
    /// Stop after this long, if given.
    pub time: Option<Duration>,
}

/// The mutation loop: mutated seeds through `check` until the input count
/// or the time is reached. `check` catches the panics it looks for.
pub fn fuzz(target: Target, seeds: &[Vec<u8>], config: &Config, check: &dyn Fn(&[u8]) -> Outcome) -> Report {
    let started = Instant::now();
    let mut rng = Rng::new(config.seed);
    let mut pool: Vec<Vec<u8>> = seeds.to_vec();
    if pool.is_empty() {
        pool.push(Vec::new());
    }
    let n_seeds = pool.len();
    let mut seen = std::collections::HashSet::new();
    let mut report = Report::default();
    while report.inputs < config.inputs && config.time.is_none_or(|t| started.elapsed() < t) {
        // Half the inputs start from a seed as written: most of the pool is
        // inputs the reader refuses, and a valid deck reaches further.
        let from = if rng.below(2) == 0 { n_seeds } else { pool.len() };
        let mut input = pool[rng.below(from)].clone();
        for _ in 0..1 + rng.below(3) {
            let other = &pool[rng.below(pool.len())];
            mutate(&mut rng, target, &mut input, other);
        }
        report.inputs += 1;
        let kind = match check(&input) {
            Outcome::Finding(what) => {
                report.findings.push(Finding { input, what });
                continue;
            }
            Outcome::Accepted(k) => {
                report.accepted += 1;
                format!("ok {k}")
            }
            Outcome::Refused(k) => k,
        };
        if seen.insert(kind) && pool.len() < MAX_POOL {
            pool.push(input);
        }
    }
    report.outcomes = seen.len();
    report.elapsed = started.elapsed();
    report
}

/// The seeds in the repository under `root`: decks (`*.deck` under
/// legacy_pascal/decks and tests/) or rasters (`*.ras` under raster/ and
/// tests/), in a fixed order.
pub fn seeds(root: &Path, target: Target) -> Vec<Vec<u8>> {
    let (ext, dirs): (&str, &[&str]) = match target {
        Target::Deck => ("deck", &["legacy_pascal/decks", "tests"]),
        Target::Raster => ("ras", &["raster", "tests"]),
    };
    let mut files = Vec::new();
    for d in dirs {
        collect(&root.join(d), ext, &mut files);
    }
    files.sort();
    files.dedup();
    files
        .iter()
        .filter_map(|f| std::fs::read(f).ok())
        .filter(|b| b.len() <= MAX_INPUT)
        .collect()
}

fn collect(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            collect(&p, ext, out);
        } else if p.extension().is_some_and(|x| x == ext) {
            out.push(p);
        }
    }
}

/// `tools fuzz`: runs the loop on one target, prints the report and writes
/// each finding to `out` (`TARGET-N.deck` or `.ras`, with a `.txt` saying
/// what broke). An error if anything was found.
pub fn run(target: Target, root: &Path, config: &Config, out: &Path) -> Result<(), String> {
    let seeds = seeds(root, target);
    let deck_dir = root.join("legacy_pascal/decks");
    let check = |input: &[u8]| match target {
        Target::Deck => check_deck(input, &deck_dir),
        Target::Raster => check_raster(input),
    };
    // The panics are caught and reported as findings: not printed as well.
    std::panic::set_hook(Box::new(|_| {}));
    let report = fuzz(target, &seeds, config, &check);
    drop(std::panic::take_hook());
    let (name, ext) = match target {
        Target::Deck => ("deck", "deck"),
        Target::Raster => ("raster", "ras"),
    };
    println!(
        "fuzz {name}: seed {}, {} seeds, {} inputs in {:.1} s, {} accepted, {} distinct outcomes, {} findings",
        config.seed,
        seeds.len(),
        report.inputs,
        report.elapsed.as_secs_f64(),
        report.accepted,
        report.outcomes,
        report.findings.len()
    );
    if report.findings.is_empty() {
        return Ok(());
    }
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    for (k, f) in report.findings.iter().enumerate() {
        let file = out.join(format!("{name}-{k}.{ext}"));
        std::fs::write(&file, &f.input).map_err(|e| format!("{}: {e}", file.display()))?;
        std::fs::write(file.with_extension("txt"), format!("{}\n", f.what))
            .map_err(|e| format!("{}: {e}", file.display()))?;
        println!("  {}: {}", file.display(), f.what);
    }
    Err(format!(
        "{} findings, written to {}",
        report.findings.len(),
        out.display()
    ))
}

/// `tools fuzz TARGET`: the command line's arguments to [`run`], seeds from
/// this checkout.
pub fn main(target: &str, seed: u64, inputs: u64, seconds: Option<f64>, out: &Path) -> Result<(), String> {
    let target = match target {
        "deck" => Target::Deck,
        "raster" => Target::Raster,
        other => return Err(format!("fuzz {other}: expected deck or raster")),
    };
    let config = Config {
        seed,
        inputs,
        time: seconds.map(|s| Duration::from_secs_f64(s.clamp(0.0, 1e9))),
    };
    run(target, &Path::new(env!("CARGO_MANIFEST_DIR")).join(".."), &config, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
    }

    #[test]
    fn the_loop_reports_what_a_check_finds_and_is_reproducible() {
        // A check that breaks on any byte that is not ASCII: the mutations
        // put such bytes in.
        let check = |input: &[u8]| {
            if !input.is_ascii() {
                panic!("planted");
            }
            Outcome::Refused(format!("{}", input.len() % 7))
        };
        let guarded = |input: &[u8]| match catch_unwind(AssertUnwindSafe(|| check(input))) {
            Ok(o) => o,
            Err(_) => Outcome::Finding("planted panic".into()),
        };
        let config = Config {
            seed: 7,
            inputs: 1000,
            time: None,
        };
        let seeds = vec![b"sphere a b at 0 0 0 radius 1\n".to_vec()];
        let a = fuzz(Target::Deck, &seeds, &config, &guarded);
        assert_eq!(a.inputs, 1000);
        assert!(a.findings.len() > 10, "{}", a.findings.len());
        assert!(a
            .findings
            .iter()
            .all(|f| !f.input.is_ascii() && f.what == "planted panic"));
        let b = fuzz(Target::Deck, &seeds, &config, &guarded);
        let inputs = |r: &Report| r.findings.iter().map(|f| f.input.clone()).collect::<Vec<_>>();
        assert_eq!(inputs(&a), inputs(&b), "the same seed tries the same inputs");
    }

    #[test]
    fn the_seeds_are_the_repositorys_decks_and_rasters() {
        let decks = seeds(&root(), Target::Deck);
        assert!(decks.len() >= 15, "{}", decks.len());
        assert!(decks
            .iter()
            .any(|d| d.starts_with(b"{") || d.windows(4).any(|w| w == b"view")));
        let rasters = seeds(&root(), Target::Raster);
        assert!(rasters.len() >= 3, "{}", rasters.len());
        assert!(rasters.iter().all(|r| r.starts_with(&[0x59, 0xa6, 0x6a, 0x95])));
    }

    #[test]
    fn the_checks_catch_a_bad_position_and_a_raw_control_character() {
        assert!(position_fault(b"ab\ncd", 2, 3).is_none());
        assert!(position_fault(b"ab\ncd", 3, 1).is_some());
        assert!(position_fault(b"ab\ncd", 1, 4).is_some());
        assert!(message_fault("found 'a\0b'").is_some());
        assert!(message_fault(&"x".repeat(MAX_MESSAGE + 1)).is_some());
        assert!(message_fault("found '\\0'").is_none());
    }

    /// A short run of each target, as the long runs go (fixed seed).
    #[test]
    fn a_short_run_finds_nothing() {
        let config = Config {
            seed: 1,
            inputs: 1500,
            time: None,
        };
        let dir = root().join("legacy_pascal/decks");
        let deck = fuzz(Target::Deck, &seeds(&root(), Target::Deck), &config, &|i: &[u8]| {
            check_deck(i, &dir)
        });
        let what: Vec<&str> = deck.findings.iter().map(|f| f.what.as_str()).collect();
        assert!(what.is_empty(), "{what:?}");
        assert!(deck.accepted > 0 && deck.outcomes > 20, "{deck:?}");
        let raster = fuzz(Target::Raster, &seeds(&root(), Target::Raster), &config, &check_raster);
        let what: Vec<&str> = raster.findings.iter().map(|f| f.what.as_str()).collect();
        assert!(what.is_empty(), "{what:?}");
        assert!(raster.accepted > 0, "{raster:?}");
    }
}

//! The main program `raytrace` (OCR text, lines 3013–3229): `initialize`,
//! `getangle`, `goahead` for each key-frame pair, the motion table, the
//! scanline loop with `translookpt`, `motionblur` and `raytrace` for every
//! subpixel, `antialias` of each block of `masksize` scanlines, and
//! `outputframe`.
//!
//! The steps keep the listing's order; what changes is the sharing (see
//! DESIGN, "State"): the scene is read-only while rendering, rows of
//! pixels are traced in parallel, and every lookup-table cursor is a
//! function of the subpixel's (scanline, scancol), so an image is the same
//! for any number of threads and equal to the listing's sequential order.
//!
//! Reconstructed here, as the thesis does not print them: `getangle`,
//! `translookpt`, `antialias`, and where on the screen a subpixel lies.

use rayon::prelude::*;

use crate::adaptive;
use crate::drt::{motionblur, noise2_table, random_time, strata, stratified_time, Isblur, TimeTable, MAXINDEX};
use crate::film::Frame;
use crate::paper::PaperChain;
use crate::raster::{rgbtochars, Raster};
use crate::trace::{raytrace, rest_poses, Deforming, Snapshot, TraceStats};
use crate::types::{DVec3, Fidelity, Intensity, Options, Pos, Ray, Scene, TimeSampler, View};

/// A scene the renderer cannot draw yet or at all.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A record whose rendering is not part of the port yet: named with
    /// where it stands, never dropped silently.
    #[error("{}:{}: the '{record}' record is read and checked, but this version of the renderer cannot draw it yet", .pos.line, .pos.column)]
    Unsupported { pos: Pos, record: &'static str },
    /// A record that does not fit the rest of the scene.
    #[error("{}:{}: {record}: {message}", .pos.line, .pos.column)]
    Misfit {
        pos: Pos,
        record: &'static str,
        message: String,
    },
    /// Pixels whose colour came out NaN or infinite (the port's extension:
    /// the listing wrote them as black). The deck reader's ranges keep every
    /// deck in range from this; it is the last guard, so that such an image
    /// is refused rather than written.
    #[error("{pixels} of {total} pixels have a colour that is not finite (NaN or infinite): the scene's numbers overflowed; nothing was written")]
    NonFinite { pixels: usize, total: usize },
}

/// The subpixel times of a scene: its `pattern` and `blur` records, or
/// the defaults.
pub fn time_table(scene: &Scene, fidelity: Fidelity) -> Result<TimeTable, RenderError> {
    let blur = scene.blur.as_ref().map_or(0, |b| b.n);
    TimeTable::new(scene.image.masksize, scene.pattern.as_ref(), blur, fidelity).map_err(|message| {
        let pos = scene.pattern.as_ref().map(|p| p.pos).unwrap_or_default();
        RenderError::Misfit {
            pos,
            record: "pattern",
            message,
        }
    })
}

/// The set-up the main program does between `initialize` and the scanline
/// loop: the sweeps' `spline` coefficients and boxes, the subpixel time
/// table, and `goahead` for each key-frame pair (a chain of pairs for a
/// `keyframe` record of more than two shapes). The in-between object's
/// bounding sphere is widened to hold its contour at every time.
pub fn prepare(scene: &mut Scene, opts: &Options) -> Result<(), RenderError> {
    time_table(scene, opts.fidelity)?;
    crate::shapes::sweep::prepare_sweeps(scene, opts.fidelity);
    crate::paper::widen_tbox(scene, opts.fidelity);
    for (k, chain) in key_frame_chains(scene, opts.fidelity)? {
        let b = chain.bbox();
        let corner = DVec3::new(
            b.xmin.abs().max(b.xmax.abs()),
            b.ymin.abs().max(b.ymax.abs()),
            b.zmin.abs().max(b.zmax.abs()),
        );
        let first = scene.keyframes[k].first;
        if corner.is_finite() {
            scene.objects[first].radius = scene.objects[first].radius.max(corner.length() * (1.0 + 1e-9));
        }
    }
    Ok(())
}

/// `goahead(i2, …)` for every key-frame pair of the main program
/// (`for i2 := 1 to papernumber`): the chain of each `keyframe` record,
/// with the record's index.
pub fn key_frame_chains(scene: &Scene, fidelity: Fidelity) -> Result<Vec<(usize, PaperChain)>, RenderError> {
    scene
        .keyframes
        .iter()
        .enumerate()
        .map(|(k, record)| {
            PaperChain::from_keyframe(scene, record, fidelity)
                .map(|chain| (k, chain))
                .map_err(|e| RenderError::Misfit {
                    pos: record.pos,
                    record: "keyframe",
                    message: e.to_string(),
                })
        })
        .collect()
}

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
    /// `virthighx`, `virthighy`: the subpixel raster, width·masksize by
    /// height·masksize.
    virthighx: usize,
    virthighy: usize,
    /// Where on the window subpixel k lies (DEVIATIONS D5).
    fidelity: Fidelity,
}

impl Camera {
    pub fn new(scene: &Scene, fidelity: Fidelity) -> Camera {
        let (sinz, cosz, sinx, cosx) = getangle(&scene.view);
        let img = &scene.image;
        let screen_w = scene.view.screensize;
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
            virthighx: img.width * img.masksize,
            virthighy: img.height * img.masksize,
            fidelity,
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
    pub fn ray(&self, scancol: f64, scanline: f64, jx: f64, jz: f64) -> Ray {
        let along = |k: f64, j: f64, n: usize| match self.fidelity {
            // Listing: (scancol+jitter)/(halfvirtualx*2.0-1.0).
            Fidelity::Listing => (k + j) / ((2 * (n / 2)) as f64 - 1.0).max(1.0),
            // Thesis: the centre of cell k of n, moved by the jitter.
            Fidelity::Thesis => (k - 0.5 + j) / n as f64,
        };
        let right = (along(scancol, jx, self.virthighx) - 0.5) * self.screen_w;
        let up = (0.5 - along(scanline, jz, self.virthighy)) * self.screen_h;
        let xpt = -right;
        let ypt = -self.scrndistance;
        let zpt = up;
        let p = translookpt(xpt, ypt, zpt, self.sinz, self.cosz, self.sinx, self.cosx, self.eyept);
        Ray::new(self.eyept, (p - self.eyept).normalize())
    }
}

/// The scene as it stands at one instant `time` of the shutter, still:
/// every moving object at its pose then (`motionblur`), every key-frame
/// object at its in-between contour and pose (`chains` as
/// [`key_frame_chains`] gives them), and no motion or key frames left. For
/// looking at in-between shapes without blur (`tools frames`), and for
/// tests.
pub fn still_at(scene: &Scene, chains: &[(usize, PaperChain)], time: f64, fidelity: Fidelity) -> Scene {
    let mut still = scene.clone();
    for mo in &scene.motions {
        let pose = motionblur(&scene.objects[mo.object], mo, time, fidelity);
        let obj = &mut still.objects[mo.object];
        (obj.transfm, obj.inverse, obj.sphereo) = (pose.transfm, pose.inverse, pose.sphereo);
    }
    for (k, chain) in chains {
        let obj = &mut still.objects[scene.keyframes[*k].first];
        let mut contour = chain.scratch();
        chain.inbetween(time, &mut contour);
        obj.shape = crate::types::Shape::Sweep(contour);
        let pose = chain.pose(time);
        (obj.transfm, obj.inverse, obj.sphereo) = (pose.transfm, pose.inverse, pose.sphereo);
    }
    still.motions.clear();
    still.keyframes.clear();
    still
}

/// What a render returns: the raster and its counts.
#[derive(Clone, Debug)]
pub struct Render {
    pub raster: Raster,
    pub stats: TraceStats,
    /// Primary rays traced, the listing's extra column included.
    pub primary: u64,
    /// Pixels whose colour was NaN or infinite before `rgbtochars` (which
    /// would write them black); see [`Render::check_finite`].
    pub nonfinite: usize,
}

impl Render {
    /// An error if any pixel's colour was not finite: such a raster must
    /// not be written.
    pub fn check_finite(&self) -> Result<(), RenderError> {
        match self.nonfinite {
            0 => Ok(()),
            pixels => Err(RenderError::NonFinite {
                pixels,
                total: self.raster.pixels.len(),
            }),
        }
    }
}

/// The scanline loop of the main program over a prepared scene. `progress`
/// is called once per finished row of final pixels (from worker threads).
///
/// Erratum 13: the listing's column loop runs `for scancol := quickx to
/// quickx2` with `quickx = 0`, tracing one column more than the raster
/// has; `listing` fidelity traces it (and `antialias` never reads it),
/// `thesis` fidelity starts at 1.
///
/// Erratum 15 (the port's own reading): `aindex := aindex + 1` is commented
/// out in the listing, so every subpixel moves by the same
/// `noise2[aindex]*aliasing`, in x and z alike; `thesis` fidelity (§2.1.3
/// (4), stochastic sampling) advances the cursor: subpixel k of the scan
/// order takes entries 2k and 2k+1 (mod `maxindex`) for x and z.
///
/// Moving objects (the motion table, `motionmatrix`): each subpixel gets a
/// time from [`TimeTable::time`] and `motionblur` poses every object that
/// `Isblur` says moves; the others keep their rest pose at no cost.
pub fn render(scene: &Scene, opts: &Options, progress: &(dyn Fn() + Sync)) -> Render {
    render_frame(scene, opts, Frame::STILL, progress)
}

/// [`render`] for one frame of a film (the port's extension,
/// [`crate::film`]): every subpixel time τ the sampler gives becomes the
/// film time [`Frame::time`] before `motionblur` and the key-frame chains
/// see it. [`Frame::STILL`] is [`render`] itself.
pub fn render_frame(scene: &Scene, opts: &Options, frame: Frame, progress: &(dyn Fn() + Sync)) -> Render {
    let Traced {
        colours,
        stats,
        primary,
        ..
    } = render_rows(scene, opts, frame, progress);
    let nonfinite = colours.iter().filter(|c| !c.is_finite()).count();
    let pixels = colours.iter().map(|&c| rgbtochars(c)).collect();
    let img = &scene.image;
    Render {
        raster: Raster {
            width: img.width,
            height: img.height,
            pixels,
        },
        stats,
        primary,
        nonfinite,
    }
}

/// The image as colours, before `rgbtochars` clamps and rounds them (row
/// 0 at the top): for checks that must see a NaN or a colour above 1.
pub fn render_colours(scene: &Scene, opts: &Options) -> Vec<Intensity> {
    render_rows(scene, opts, Frame::STILL, &|| {}).colours
}

/// The image as colours and the primary rays each pixel got (`masksize`²
/// for the table and the samplers like it, the need of the pixel for
/// `--sampler adaptive`): for the adaptive sampler's heat map.
pub fn render_counted(scene: &Scene, opts: &Options) -> (Vec<Intensity>, Vec<u32>) {
    let traced = render_rows(scene, opts, Frame::STILL, &|| {});
    (traced.colours, traced.counts)
}

/// What the scanline loop returns.
struct Traced {
    colours: Vec<Intensity>,
    /// Primary rays a pixel (the listing's extra column not counted).
    counts: Vec<u32>,
    stats: TraceStats,
    primary: u64,
}

/// What every sample of a render shares: the scene, the objects `Isblur`
/// says move (the motion table, `motionmatrix`), the key-frame chains.
struct Shared<'a> {
    scene: &'a Scene,
    opts: &'a Options,
    moving: Vec<&'a crate::types::MotionRecord>,
    chains: Vec<(usize, PaperChain)>,
    timed: bool,
    /// The film frame the sampler's times τ fall in ([`Frame::STILL`]
    /// outside a film).
    frame: Frame,
}

impl<'a> Shared<'a> {
    fn new(scene: &'a Scene, opts: &'a Options, frame: Frame) -> Self {
        let motionmatrix: Vec<usize> = scene.motions.iter().map(|mo| mo.object).collect();
        let moving: Vec<&crate::types::MotionRecord> = scene
            .motions
            .iter()
            .filter(|mo| !Isblur(mo.object, &motionmatrix))
            .collect();
        // `prepare` has reported a pair that cannot be built; a caller that
        // skipped it renders the key shapes as they stand.
        let chains: Vec<(usize, PaperChain)> = key_frame_chains(scene, opts.fidelity)
            .unwrap_or_default()
            .into_iter()
            .map(|(k, chain)| (scene.keyframes[k].first, chain))
            .collect();
        let timed = !moving.is_empty() || !chains.is_empty();
        Shared {
            scene,
            opts,
            moving,
            chains,
            timed,
            frame,
        }
    }
}

/// One worker's scratch for a row: the poses, the in-between objects'
/// contours (reused for every sample), the counts.
struct Tracer<'s> {
    poses: Vec<crate::types::Pose>,
    deforming: Vec<Deforming<'s>>,
    stats: TraceStats,
    primary: u64,
}

impl<'s> Tracer<'s> {
    fn new(shared: &'s Shared) -> Self {
        Tracer {
            poses: rest_poses(shared.scene),
            deforming: shared
                .chains
                .iter()
                .map(|(first, chain)| Deforming::new(*first, chain))
                .collect(),
            stats: TraceStats::default(),
            primary: 0,
        }
    }

    /// `raytrace` of the primary ray `aray` with the scene at the film time
    /// of the sampler's `tau()` (asked only when something moves; the
    /// film's hook [`Frame::time`], the identity for a still): `motionblur` poses every moving
    /// object; its `paper = 1` branch moves the in-between object's pose by
    /// `diff`, and the contour (`do34` at time 0 or 1, else `Hermite`) is
    /// made when a ray first needs it.
    fn trace(&mut self, shared: &Shared, aray: &Ray, tau: impl FnOnce() -> f64) -> Intensity {
        if shared.timed {
            self.at(shared, tau());
        }
        self.shoot(shared, aray)
    }

    /// The scene at the film time of the sampler's time `tau`: the poses
    /// and in-between contours of [`Tracer::trace`], for the rays that
    /// follow.
    fn at(&mut self, shared: &Shared, tau: f64) {
        let time = shared.frame.time(tau);
        for mo in &shared.moving {
            self.poses[mo.object] = motionblur(&shared.scene.objects[mo.object], mo, time, shared.opts.fidelity);
        }
        for (d, (_, chain)) in self.deforming.iter().zip(&shared.chains) {
            self.poses[d.object] = chain.pose(time);
            d.at(time);
        }
    }

    /// `raytrace` of the primary ray `aray` with the scene as the last
    /// [`Tracer::at`] left it.
    fn shoot(&mut self, shared: &Shared, aray: &Ray) -> Intensity {
        let snap = Snapshot {
            scene: shared.scene,
            poses: &self.poses,
            deforming: &self.deforming,
        };
        self.primary += 1;
        raytrace(&snap, aray, 1.0, false, 1, shared.opts, &mut self.stats)
    }
}

/// The scanline loop: the colour of every pixel, the counts, the primary rays.
fn render_rows(scene: &Scene, opts: &Options, frame: Frame, progress: &(dyn Fn() + Sync)) -> Traced {
    let camera = Camera::new(scene, opts.fidelity);
    let shared = Shared::new(scene, opts, frame);
    if opts.sampler == TimeSampler::Adaptive {
        return render_adaptive(&shared, &camera, progress);
    }
    let img = &scene.image;
    let m = img.masksize;
    let noise2 = noise2_table();
    // `prepare` has refused a pattern that does not fit; a caller that
    // skipped it gets the default table.
    let blur = scene.blur.as_ref().map_or(0, |b| b.n);
    let times =
        time_table(scene, opts.fidelity).unwrap_or_else(|_| TimeTable::with_default_pattern(m, blur, opts.fidelity));
    let first_col = match opts.fidelity {
        Fidelity::Listing => 0,
        Fidelity::Thesis => 1,
    };
    let jitter = |scanline: usize, scancol: usize| -> (f64, f64) {
        match opts.fidelity {
            Fidelity::Listing => {
                let j = noise2[0] * img.aliasing;
                (j, j)
            }
            Fidelity::Thesis => {
                let k = (scanline - 1) * camera.virthighx + scancol.max(1) - 1;
                let ax = (2 * k) % MAXINDEX;
                let az = (2 * k + 1) % MAXINDEX;
                (noise2[ax] * img.aliasing, noise2[az] * img.aliasing)
            }
        }
    };

    let mut pixels = vec![Intensity::ZERO; img.width * img.height];
    let per_row: Vec<(TraceStats, u64)> = pixels
        .par_chunks_mut(img.width)
        .enumerate()
        .map(|(row, out)| {
            let mut tracer = Tracer::new(&shared);
            let mut virtual_rows = vec![Intensity::ZERO; m * img.width];
            let row_strata: Vec<Vec<u32>> = match opts.sampler {
                TimeSampler::Stratified if shared.timed => {
                    (0..img.width).map(|x| strata(row * img.width + x, m * m)).collect()
                }
                _ => Vec::new(),
            };
            for sub in 0..m {
                let scanline = row * m + sub + 1;
                for scancol in first_col..=camera.virthighx {
                    let (jx, jz) = jitter(scanline, scancol);
                    let aray = camera.ray(scancol as f64, scanline as f64, jx, jz);
                    let tau = || {
                        let k = (scanline - 1) * camera.virthighx + scancol.max(1) - 1;
                        match opts.sampler {
                            TimeSampler::Table => times.time(scanline, scancol, k),
                            TimeSampler::Random => random_time(k),
                            TimeSampler::Stratified => {
                                let c = scancol.max(1) - 1;
                                let j = sub * m + c % m;
                                stratified_time(row * img.width + c / m, j, row_strata[c / m][j], m * m)
                            }
                            // Drawn by `render_adaptive`.
                            TimeSampler::Adaptive => 0.5,
                        }
                    };
                    let acolor = tracer.trace(&shared, &aray, tau);
                    if scancol >= 1 {
                        virtual_rows[sub * img.width + (scancol - 1) / m] += acolor;
                    }
                }
            }
            antialias(&virtual_rows, m, out);
            progress();
            (tracer.stats, tracer.primary)
        })
        .collect();
    let (stats, primary) = sum_counts(per_row);
    Traced {
        colours: pixels,
        counts: vec![(m * m) as u32; img.width * img.height],
        stats,
        primary,
    }
}

/// The rows' counts, added up.
fn sum_counts(per_row: Vec<(TraceStats, u64)>) -> (TraceStats, u64) {
    let mut stats = TraceStats::default();
    let mut primary = 0;
    for (s, p) in per_row {
        stats += s;
        primary += p;
    }
    (stats, primary)
}

/// The scanline loop of `--sampler adaptive` (the port's extension, see
/// [`crate::adaptive`]): a first pass of a few rays a pixel, then the
/// passes that deal out the rest of the deck's budget of `masksize`² rays
/// a pixel by need. Each sample is a place in the pixel and a time, from
/// [`adaptive::PixelSamples`]; a row is traced instant by instant (the
/// times its pixels share), the scene posed once an instant ([`Tracer::at`])
/// and each due pixel's ray shot at it ([`Tracer::shoot`]); a pixel is the
/// mean of its samples (the box filter of `antialias`). `progress` is
/// called for each row of the last pass.
fn render_adaptive(shared: &Shared, camera: &Camera, progress: &(dyn Fn() + Sync)) -> Traced {
    let img = &shared.scene.image;
    let (w, m) = (img.width, img.masksize as f64);
    let budget = (img.masksize * img.masksize) as u32;
    let first = adaptive::first_pass(img.masksize);
    let mut sums = vec![adaptive::PixelSum::default(); w * img.height];
    let mut counts = vec![first; sums.len()];
    // The first pass, then the passes that have rays to deal out (none
    // for a budget of one ray).
    let mut passes = vec![0];
    passes.extend(
        adaptive::later_passes(sums.len(), budget, first)
            .into_iter()
            .filter(|&e| e > 0),
    );
    let samples: Vec<_> = (0..sums.len()).map(|i| adaptive::PixelSamples::new(i, w)).collect();
    let mut per_row = Vec::new();
    for (pass, &extra) in passes.iter().enumerate() {
        if pass > 0 {
            counts = adaptive::allocate(&sums, w, budget, extra, adaptive::quantum(budget));
        }
        let last = pass + 1 == passes.len();
        let rows: Vec<(TraceStats, u64)> = sums
            .par_chunks_mut(w)
            .zip(counts.par_chunks(w))
            .zip(samples.par_chunks(w))
            .enumerate()
            .map(|(row, ((sums, counts), samples))| {
                let mut tracer = Tracer::new(shared);
                let start: Vec<u32> = sums.iter().map(|s| s.n).collect();
                // The row's instants k in the blocks its samples reach: at
                // each, every pixel whose sample k ⊕ c is due, with the
                // scene posed once (`PixelSamples`).
                let block = adaptive::SHIFT_BLOCK;
                for (b, pixels) in adaptive::blocks_due(&start, counts) {
                    for k in b * block..(b + 1) * block {
                        let mut posed = false;
                        for &x in &pixels {
                            let j = samples[x].at_instant(k);
                            if j < start[x] || j >= counts[x] {
                                continue;
                            }
                            if shared.timed && !posed {
                                tracer.at(shared, samples[x].tau(j));
                                posed = true;
                            }
                            let (u, v) = samples[x].place(j);
                            // Subpixel units: pixel x spans scancol − ½ in [x·M, (x+1)·M).
                            let scancol = (x as f64 + u) * m + 0.5;
                            let scanline = (row as f64 + v) * m + 0.5;
                            let aray = camera.ray(scancol, scanline, 0.0, 0.0);
                            let before = crate::shapes::sweep::searched();
                            sums[x].add(tracer.shoot(shared, &aray));
                            sums[x].add_searched(crate::shapes::sweep::searched() - before);
                        }
                    }
                }
                if last {
                    progress();
                }
                (tracer.stats, tracer.primary)
            })
            .collect();
        per_row.extend(rows);
    }
    let (stats, primary) = sum_counts(per_row);
    Traced {
        colours: sums.iter().map(adaptive::PixelSum::mean).collect(),
        counts,
        stats,
        primary,
    }
}

/// `antialias(1, i4, acthighx, i4)`: one row of final pixels from the
/// `masksize` scanlines of subpixels above it. Reconstructed: the box
/// filter, the mean of the masksize × masksize subpixels of each pixel
/// (§2.1.3 (2), supersampling). `sums` holds, for each of the `m` subpixel
/// rows, each pixel's sum over its `m` subpixel columns.
fn antialias(sums: &[Intensity], m: usize, out: &mut [Intensity]) {
    let width = out.len();
    for (x, px) in out.iter_mut().enumerate() {
        let total: Intensity = (0..m).map(|sub| sums[sub * width + x]).sum();
        *px = total / (m * m) as f64;
    }
}

/// The lines the listing writes to `debugf` for a frame: first what
/// `goahead` writes for each key-frame pair ([`PaperChain`]'s pairs in
/// order, `PaperPair::debug_lines`, with the expanders' messages, which the
/// listing wrote to standard output), then one line per scanline of the
/// subpixel raster, `kfTIRcnt`, and the frame's end; and the count of
/// `roottesting`'s `**** impossible ****` (erratum 8), which the listing
/// wrote to standard output.
pub fn debug_log(scene: &Scene, render: &Render, fidelity: Fidelity) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for (_, chain) in key_frame_chains(scene, fidelity).unwrap_or_default() {
        for pair in chain.pairs() {
            for line in pair.debug_lines() {
                let _ = writeln!(s, "{line}");
            }
        }
    }
    for scanline in 1..=scene.image.height * scene.image.masksize {
        let _ = writeln!(s, " scanline={scanline:5}");
    }
    let _ = writeln!(s, "kfTIRcnt={:9}", render.stats.kftircnt);
    // What the listing wrote to standard output from `roottesting`, counted.
    let _ = writeln!(
        s,
        "**** impossible ****{:9}",
        crate::proc::sweep::roottesting_impossible_count()
    );
    let _ = writeln!(s);
    let _ = writeln!(s, "FRAME NUMBER{:4}---DONE", 1);
    s
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

//! What the chart measures: image error, silhouettes, medians of timings.

use std::time::Instant;

use raytrace::raytrace::{first_hit, Camera, Prepared};
use raytrace::types::{Intensity, PrimitiveClass};

/// The root mean square of the differences of two float images, over
/// every pixel and channel. Images of different sizes have no RMSE (NaN).
pub fn rmse(a: &[Intensity], b: &[Intensity]) -> f64 {
    if a.len() != b.len() || a.is_empty() {
        return f64::NAN;
    }
    let sum: f64 = a.iter().zip(b).map(|(x, y)| (*x - *y).length_squared()).sum();
    (sum / (3 * a.len()) as f64).sqrt()
}

/// The median of some samples (the upper one of an even count); NaN for none.
pub fn median(samples: &[f64]) -> f64 {
    if samples.is_empty() {
        return f64::NAN;
    }
    let mut s = samples.to_vec();
    s.sort_by(f64::total_cmp);
    s[s.len() / 2]
}

/// Times every job `rounds` times, interleaved (round r runs each job
/// once, in order), after one untimed round; the median seconds of each.
/// On a shared machine a burst of other work then spreads over all jobs
/// instead of spoiling every run of one.
pub fn interleaved_medians(jobs: &mut [&mut dyn FnMut()], rounds: usize) -> Vec<f64> {
    let mut timed: Vec<Box<dyn FnMut() -> Result<f64, String> + '_>> = jobs
        .iter_mut()
        .map(|job| {
            Box::new(move || {
                let t = Instant::now();
                job();
                Ok(t.elapsed().as_secs_f64())
            }) as Box<dyn FnMut() -> Result<f64, String>>
        })
        .collect();
    let mut refs: Vec<&mut dyn FnMut() -> Result<f64, String>> = timed.iter_mut().map(|j| j.as_mut() as _).collect();
    interleaved_medians_of(&mut refs, rounds).unwrap_or_else(|e| unreachable!("a clock never fails: {e}"))
}

/// As [`interleaved_medians`], each job measuring itself: it returns the
/// seconds it took (a CPU time, say, or what a program it ran reports),
/// or why it could not run. The untimed round's seconds are dropped.
pub fn interleaved_medians_of(
    jobs: &mut [&mut dyn FnMut() -> Result<f64, String>],
    rounds: usize,
) -> Result<Vec<f64>, String> {
    for job in jobs.iter_mut() {
        job()?;
    }
    let mut secs = vec![Vec::with_capacity(rounds); jobs.len()];
    for _ in 0..rounds.max(1) {
        for (k, job) in jobs.iter_mut().enumerate() {
            secs[k].push(job()?);
        }
    }
    Ok(secs.iter().map(|s| median(s)).collect())
}

/// The CPU time the calling thread has used, in seconds
/// (`clock_gettime` of `CLOCK_THREAD_CPUTIME_ID`, to the nanosecond).
/// Unlike the wall clock it does not count the time other work on a
/// shared machine takes the core away.
pub fn thread_cpu_secs() -> f64 {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// The CPU seconds `f` takes on the calling thread, and what it returns.
pub fn thread_cpu_timed<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let before = thread_cpu_secs();
    let out = f();
    (thread_cpu_secs() - before, out)
}

/// Our render of a prepared still on `pool` (of one thread, for the
/// comparisons): the rendering thread's CPU seconds ([`thread_cpu_timed`]:
/// the render only, as POV-Ray's reported trace time is its trace only)
/// and the raster's pixels.
pub fn timed_still(pool: &rayon::ThreadPool, prepared: &Prepared) -> (f64, Vec<[u8; 3]>) {
    let (secs, r) = pool.install(|| thread_cpu_timed(|| crate::decks::still(prepared)));
    (secs, r.raster.pixels)
}

/// A pool of one thread: the timings of one thread each.
pub fn one_thread() -> Result<rayon::ThreadPool, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| e.to_string())
}

/// A new folder for a tool's scratch files, `tools-NAME-PID` in the
/// system's temporary folder (the caller removes it).
pub fn scratch_dir(name: &str) -> Result<std::path::PathBuf, String> {
    let dir = std::env::temp_dir().join(format!("tools-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    Ok(dir)
}

/// Whether an object is a sweep (translation, conic, rotation).
pub fn is_sweep(class: PrimitiveClass) -> bool {
    matches!(
        class,
        PrimitiveClass::Translation | PrimitiveClass::Conic | PrimitiveClass::Rotation
    )
}

/// What each pixel's probe rays see: for every pixel (row-major), the
/// first object each of its `k`×`k` rays meets (`None`: the background),
/// through the subpixel centres, objects at rest. The scene's image size is
/// kept; its mask is ignored (the probe has its own `k`).
pub fn probe_objects(prepared: &Prepared, k: usize) -> Vec<Vec<Option<usize>>> {
    use rayon::prelude::*;
    let scene = prepared.scene();
    let mut probe = scene.clone();
    probe.image.masksize = k;
    let camera = Camera::new(&probe, prepared.options().fidelity);
    let (w, h) = (scene.image.width, scene.image.height);
    (0..w * h)
        .into_par_iter()
        .map(|p| {
            let (x, y) = (p % w, p / w);
            let mut seen = Vec::with_capacity(k * k);
            for sy in 0..k {
                for sx in 0..k {
                    let ray = camera.ray((x * k + sx + 1) as f64, (y * k + sy + 1) as f64, 0.0, 0.0);
                    seen.push(first_hit(prepared, &ray, None).map(|hit| hit.object));
                }
            }
            seen
        })
        .collect()
}

/// The silhouette pixels: those whose probe rays do not all see the same
/// thing, one of them seeing an object for which `of_interest` holds.
pub fn silhouette(seen: &[Vec<Option<usize>>], of_interest: impl Fn(usize) -> bool) -> Vec<bool> {
    seen.iter()
        .map(|rays| {
            let mixed = rays.windows(2).any(|w| w[0] != w[1]);
            mixed && rays.iter().any(|r| r.is_some_and(&of_interest))
        })
        .collect()
}

/// The pixels where two images differ by more than `threshold` in some channel.
pub fn differing(a: &[Intensity], b: &[Intensity], threshold: f64) -> Vec<bool> {
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).abs().max_element() > threshold)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rmse_of_identical_images_is_zero() {
        let a = vec![Intensity::new(0.1, 0.5, 0.9); 16];
        assert_eq!(rmse(&a, &a), 0.0);
    }

    /// One channel of one pixel of four off by 0.6: √(0.36 / 12).
    #[test]
    fn rmse_of_a_known_difference() {
        let a = vec![Intensity::ZERO; 4];
        let mut b = a.clone();
        b[2].y = 0.6;
        assert!((rmse(&a, &b) - (0.36f64 / 12.0).sqrt()).abs() < 1e-15);
        assert!(rmse(&a, &b[..3]).is_nan());
    }

    /// Each job runs once untimed and then once a round; one median each.
    #[test]
    fn interleaved_runs_every_job_each_round() {
        let (mut a, mut b) = (0, 0);
        let m = interleaved_medians(&mut [&mut || a += 1, &mut || b += 1], 3);
        assert_eq!(m.len(), 2);
        assert!(m.iter().all(|s| *s >= 0.0));
        assert_eq!((a, b), (4, 4));
    }

    /// Each job's own seconds are its median; an error stops the rounds.
    #[test]
    fn self_measured_jobs_give_their_medians() {
        let mut k = 0.0;
        let mut rising = || {
            k += 1.0;
            Ok(k)
        };
        let mut fixed = || Ok(0.5);
        let m = interleaved_medians_of(&mut [&mut rising, &mut fixed], 3).unwrap();
        // The untimed round gave 1; the rounds 2, 3, 4.
        assert_eq!(m, vec![3.0, 0.5]);
        let mut failing = || Err::<f64, _>("no".to_string());
        assert_eq!(interleaved_medians_of(&mut [&mut failing], 3), Err("no".into()));
    }

    /// A busy loop takes CPU time; a sleep takes almost none.
    #[test]
    fn thread_cpu_time_counts_work_not_sleep() {
        let (busy, _) = thread_cpu_timed(|| (0..20_000_000u64).fold(0, |a, k| std::hint::black_box(a ^ k)));
        let (asleep, _) = thread_cpu_timed(|| std::thread::sleep(std::time::Duration::from_millis(20)));
        assert!(busy > 0.0 && asleep < busy, "busy {busy} s, asleep {asleep} s");
    }

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 3.0);
        assert!(median(&[]).is_nan());
    }

    /// A known 3-pixel image: all background, half object 0 and half
    /// background, all object 0; and a pixel split between objects 1 and 2.
    #[test]
    fn silhouette_of_a_known_image() {
        let seen = vec![
            vec![None; 4],
            vec![Some(0), Some(0), None, None],
            vec![Some(0); 4],
            vec![Some(1), Some(2), Some(2), Some(2)],
        ];
        assert_eq!(silhouette(&seen, |o| o == 0), vec![false, true, false, false]);
        assert_eq!(silhouette(&seen, |o| o == 2), vec![false, false, false, true]);
        assert_eq!(silhouette(&seen, |_| true), vec![false, true, false, true]);
    }

    #[test]
    fn differing_pixels_by_threshold() {
        let a = vec![Intensity::ZERO; 3];
        let b = vec![
            Intensity::ZERO,
            Intensity::new(0.0, 0.0, 0.02),
            Intensity::new(-0.2, 0.0, 0.0),
        ];
        assert_eq!(differing(&a, &b, 0.05), vec![false, false, true]);
        assert_eq!(differing(&a, &b, 0.01), vec![false, true, true]);
    }
}

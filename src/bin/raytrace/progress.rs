//! The progress bar on a terminal: rows of pixels done, the time so far,
//! and the time left estimated from the rate over all the rows done so far
//! (elapsed × rows left / rows done). indicatif's own `{eta}` weighs the
//! latest rows most, so a picture whose rows cost unequal times (sky, then
//! a goblet) made it jump (3 minutes, then 6 s, then rising on a 2048²
//! render); the mean rate over all the rows moves only as the picture's
//! cost does.

use std::time::Duration;

use indicatif::{HumanDuration, ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use raytrace::exit::Failure;

/// The bar's line: `{eta}` is [`eta`]'s, not indicatif's.
const TEMPLATE: &str = "{msg} [{bar:40}] {pos}/{len} rows, {elapsed} (eta {rate_eta})";

/// The progress bar over `rows` rows of pixels (hidden with `--quiet`).
pub fn bar(quiet: bool, rows: u64) -> Result<ProgressBar, Failure> {
    if quiet {
        return Ok(ProgressBar::hidden());
    }
    let bar = ProgressBar::with_draw_target(Some(rows), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template(TEMPLATE)
            .map_err(Failure::other)?
            .with_key("rate_eta", |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                let left = eta(state.elapsed(), state.pos(), state.len().unwrap_or(0));
                let _ = match left {
                    Some(d) => write!(w, "{:#}", HumanDuration(d)),
                    None => write!(w, "…"),
                };
            })
            .progress_chars("=> "),
    );
    Ok(bar)
}

/// The time left when `done` of `total` rows took `elapsed`: the mean
/// rate over the rows done; none before the first row.
pub fn eta(elapsed: Duration, done: u64, total: u64) -> Option<Duration> {
    if done == 0 {
        return None;
    }
    let left = total.saturating_sub(done);
    Some(elapsed.mul_f64(left as f64 / done as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The estimate is the mean rate's: rows of unequal cost (100 fast
    /// rows in 1 s, then 10 slow ones in 10 s) move it only as far as the
    /// mean moves, and it is exact for rows of equal cost.
    #[test]
    fn the_time_left_follows_the_mean_rate_over_the_rows_done() {
        let s = Duration::from_secs;
        assert_eq!(eta(s(0), 0, 100), None);
        assert_eq!(eta(s(10), 50, 100), Some(s(10)));
        assert_eq!(eta(s(7), 100, 100), Some(s(0)));
        // 100 rows in 1 s, then 10 rows in 10 s: 11 s for 110 rows, 0.1 s a row.
        assert_eq!(eta(s(1), 100, 2048), Some(Duration::from_millis(19480)));
        assert_eq!(eta(s(11), 110, 2048), Some(Duration::from_millis(193800)));
        assert!(TEMPLATE.contains("(eta {rate_eta})") && !TEMPLATE.contains("{eta}"));
    }
}

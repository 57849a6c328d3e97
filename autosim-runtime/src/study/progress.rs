//! The progress bar of a study (indicatif): cases done, cases per second,
//! time left; drawn on standard error only when it is a terminal.

use core::fmt::Write;
use std::string::String;

use indicatif::{HumanCount, ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};

/// A bar over `total` cases, hidden unless `shown` (and standard error is
/// a terminal: indicatif draws nothing otherwise).
pub(super) fn bar(shown: bool, total: u64) -> ProgressBar {
    if !shown {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(
        "{elapsed_precise} [{wide_bar}] {human_pos}/{human_len} cases, {rate}, ETA {eta}",
    ) {
        let style = style.with_key("rate", |state: &ProgressState, w: &mut dyn Write| {
            let _ = w.write_str(&rate(state.per_sec()));
        });
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// Cases per second to three significant digits or as a whole number
/// (`2,166/s`, `21.7/s`, `0.35/s`), not indicatif's four decimals.
fn rate(per_second: f64) -> String {
    if !per_second.is_finite() || per_second < 0.0 {
        return "-/s".into();
    }
    if per_second >= 99.5 {
        std::format!("{}/s", HumanCount(per_second.round() as u64))
    } else if per_second >= 9.95 {
        std::format!("{per_second:.1}/s")
    } else {
        std::format!("{per_second:.2}/s")
    }
}

#[cfg(test)]
mod tests {
    use super::rate;

    #[test]
    fn rates_are_rounded_to_three_digits_or_whole_cases() {
        assert_eq!(rate(2165.9731), "2,166/s");
        assert_eq!(rate(123_456.7), "123,457/s");
        assert_eq!(rate(99.7), "100/s");
        assert_eq!(rate(21.66), "21.7/s");
        assert_eq!(rate(9.96), "10.0/s");
        assert_eq!(rate(0.3456), "0.35/s");
        assert_eq!(rate(0.0), "0.00/s");
        assert_eq!(rate(f64::NAN), "-/s");
    }
}

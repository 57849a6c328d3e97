//! What the measurements become: the terminal table of the runs,
//! `results.csv`, the work–precision plots, `summary.md` and the cheapest
//! run reaching each error level.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use autosim::runtime::io::{Axes, Corner, Scale, XySeries, write_xy_svg_plot};

use crate::method::Method;
use crate::scenes::SceneTable;
use crate::study::{REPEATS, References, Row};

/// Error levels of the summary tables.
const LEVELS: [f64; 4] = [1e-2, 1e-4, 1e-6, 1e-8];

/// Prints the head of the table of runs.
pub(crate) fn print_header() {
    println!(
        "{:<22} {:<4} {:<7} {:>10} {:>9} {:>10} {:>10} {:>10}  status",
        "study", "f", "method", "h or tol", "steps", "evals", "wall ms", "error"
    );
}

/// Prints one run as a line of the table.
pub(crate) fn print_row(r: &Row) {
    println!(
        "{:<22} {:<4} {:<7} {:>10.2e} {:>9} {:>10} {:>10.3} {:>10.2e}  {}",
        r.study,
        r.float,
        r.method.name(),
        r.setting,
        r.steps,
        r.evaluations,
        r.wall_s * 1e3,
        r.error,
        r.status
    );
}

/// The cheapest successful run of each method reaching `target`.
fn cheapest<'a>(
    rows: &'a [Row],
    study: &str,
    float: &str,
    method: Method,
    target: f64,
) -> Option<&'a Row> {
    rows.iter()
        .filter(|r| r.study == study && r.float == float && r.method == method)
        .filter(|r| r.status == "ok" && r.error <= target)
        .min_by_key(|r| r.evaluations)
}

/// Writes one line per run (see the example's documentation for the columns).
fn write_csv(path: &Path, rows: &[Row]) -> std::io::Result<()> {
    let mut s = String::from(
        "study,float,method,setting_kind,setting,steps,rejected_steps,evaluations,wall_ms,error,integration_error,status\n",
    );
    for r in rows {
        let kind = if r.method == Method::Dopri {
            "tol"
        } else {
            "h"
        };
        let num = |v: f64| {
            if v.is_finite() {
                format!("{v:e}")
            } else {
                String::new()
            }
        };
        let _ = writeln!(
            s,
            "{},{},{},{kind},{:e},{},{},{},{:.4},{},{},{}",
            r.study,
            r.float,
            r.method.name(),
            r.setting,
            r.steps,
            r.rejected,
            r.evaluations,
            r.wall_s * 1e3,
            num(r.error),
            num(r.integration_error),
            r.status.replace(',', ";")
        );
    }
    std::fs::write(path, s)
}

/// One line of a plot.
struct Line {
    name: String,
    x: Vec<f64>,
    y: Vec<f64>,
    color: usize,
    dashed: bool,
}

/// A study's plot: its name, title, y label, and an optional horizontal
/// line (name, level).
pub(crate) type Plot<'a> = (&'a str, &'a str, &'a str, Option<(&'a str, f64)>);

/// Work–precision plots of one study: error against evaluations and
/// against wall time, f64 solid, f32 dashed.
fn plot_study(
    folder: &Path,
    study: &str,
    title: &str,
    error_label: &str,
    rows: &[Row],
    floor: Option<(&str, f64)>,
) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    let mut written = Vec::new();
    for (suffix, x_label, cost) in [
        (
            "",
            "derivative evaluations",
            (|r: &Row| r.evaluations as f64) as fn(&Row) -> f64,
        ),
        ("_time", "wall time [ms]", |r: &Row| r.wall_s * 1e3),
    ] {
        let mut lines: Vec<Line> = Vec::new();
        for method in Method::ALL.iter() {
            for float in ["f64", "f32"] {
                let mut pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| r.study == study && r.float == float && r.method == *method)
                    .filter(|r| r.status == "ok")
                    .map(|r| (cost(r), r.error.max(1e-16)))
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                let name = if float == "f64" {
                    method.name().to_string()
                } else {
                    format!("{} f32", method.name())
                };
                lines.push(Line {
                    name,
                    x: pts.iter().map(|p| p.0).collect(),
                    y: pts.iter().map(|p| p.1).collect(),
                    color: method.color(),
                    dashed: float == "f32",
                });
            }
        }
        if let Some((name, level)) = floor {
            let xs: Vec<f64> = lines.iter().flat_map(|l| l.x.iter().copied()).collect();
            let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = xs.iter().copied().fold(0.0, f64::max);
            lines.push(Line {
                name: name.to_string(),
                x: vec![lo, hi],
                y: vec![level, level],
                color: 19,
                dashed: true,
            });
        }
        let series: Vec<XySeries<'_>> = lines
            .iter()
            .map(|l| XySeries {
                name: &l.name,
                x: &l.x,
                y: &l.y,
                color: l.color,
                dashed: l.dashed,
            })
            .collect();
        let path = folder.join(format!("{study}{suffix}.svg"));
        write_xy_svg_plot(
            &path,
            title,
            &Axes {
                x_label,
                y_label: error_label,
                x_scale: Scale::Log,
                y_scale: Scale::Log,
                legend: Corner::LowerLeft,
            },
            &series,
        )?;
        written.push(path);
    }
    Ok(written)
}

/// The plots of the studies, in the order of the summary: the
/// satellite-small one also draws the error of the small-variable model.
pub(crate) fn plots(small_model_error: f64) -> [Plot<'static>; 6] {
    [
        (
            "satellite",
            "Satellite slew, thrusters off: bus attitude error at 15 s",
            "max |error| of q4, q5, q6 [rad]",
            None,
        ),
        (
            "satellite-small",
            "Small-variable satellite vs the full model's reference, 15 s",
            "max |error| of q4, q5, q6 [rad]",
            Some(("small-model error", small_model_error)),
        ),
        (
            "satellite-thrusters",
            "Satellite slew with bang-bang thrusters: attitude error at 15 s",
            "max |error| of q4, q5, q6 [rad]",
            None,
        ),
        (
            "satellite-events",
            "Satellite slew, thrusters as events: attitude error at 15 s",
            "max |error| of q4, q5, q6 [rad]",
            None,
        ),
        (
            "chain-spatial-5",
            "chain-spatial-5: coordinate error at 5 s",
            "max |error| of q1..q5 [rad]",
            None,
        ),
        (
            "chain-spatial-3-stiff",
            "chain-spatial-3, joint stiffness x 1e4: coordinate error at 1 s",
            "max |error| of q1..q3 [rad]",
            None,
        ),
    ]
}

/// Writes `results.csv` and the plots of every study into `folder`.
pub(crate) fn write_files(
    folder: &Path,
    rows: &[Row],
    plots: &[Plot<'_>],
) -> Result<Vec<PathBuf>, Box<dyn std::error::Error>> {
    let csv = folder.join("results.csv");
    write_csv(&csv, rows)?;
    let mut files = vec![csv];
    for &(study, title, label, floor) in plots {
        files.extend(plot_study(folder, study, title, label, rows, floor)?);
    }
    Ok(files)
}

/// Writes `summary.md` into `folder`: the references' own errors, the
/// cheapest run reaching each error level, the scene table.
pub(crate) fn write_summary(
    folder: &Path,
    rows: &[Row],
    plots: &[Plot<'_>],
    refs: &References,
    chatter: f64,
    scenes: &SceneTable,
) -> std::io::Result<PathBuf> {
    let (peak_on, peak_off) = (scenes.peak_on, scenes.peak_off);
    let mut md = String::new();
    write_set_up(&mut md, refs, chatter);
    let _ = writeln!(
        md,
        "## The cheapest run reaching an error level\n\nEach cell: evaluations (wall time) of the cheapest setting whose error is at most the level; `—` if none did.\n"
    );
    for &(study, _, _, _) in plots {
        for float in ["f64", "f32"] {
            if !rows.iter().any(|r| r.study == study && r.float == float) {
                continue;
            }
            write_cheapest_table(&mut md, rows, study, float);
        }
    }
    let _ = writeln!(
        md,
        "## Scene options on the satellite\n\nThe slew with the Figure 8 user code, thrusters on and off, RK4 at h = 1 ms for 15 s. \
         ns / call: median over 101 rounds of `derivatives()` at 500 states of the scene's own slew \
         (including the Figure 8 user code), best of 7 passes interleaved over the scenes. Largest |attitude| of the full model over the slew: {peak_on:.2e} rad with the thrusters, {peak_off:.2e} rad without.\n"
    );
    md.push_str(&scenes.markdown);
    let summary = folder.join("summary.md");
    std::fs::write(&summary, md)?;
    Ok(summary)
}

/// The summary's title, how it was measured, and the references' own
/// errors.
fn write_set_up(md: &mut String, refs: &References, chatter: f64) {
    let small_model_error = refs.small_model_error;
    let _ = writeln!(md, "# Speed against accuracy: measurements\n");
    let _ = writeln!(
        md,
        "Generated by `cargo run --release --example tradeoff` (see the example's documentation for the set-up). \
         Error: largest absolute error at the end time, of the bus attitude q4..q6 (satellite, 15 s) or of the \
         coordinates (chains), against a Dormand–Prince reference at rtol = atol = 1e-12 in f64 \
         (satellite with thrusters in user code: against RK4 at h = 10 µs). Cost: derivative evaluations \
         (with events, including the driver's end-point derivatives of fixed steps), and wall time \
         on the machine that ran it (median of {REPEATS}).\n"
    );
    let _ = writeln!(
        md,
        "Own error of each reference (against a second, tighter run):\n"
    );
    for (label, e) in &refs.notes {
        let _ = writeln!(md, "- {label}: {e:.1e}");
    }
    let _ = writeln!(
        md,
        "- small-variable satellite against the full model (thrusters off, 15 s): {small_model_error:.2e} rad"
    );
    let _ = writeln!(
        md,
        "- thrusters on: RK4 runs at any h ≤ 10 ms end up to {chatter:.1e} rad from RK4 at h = 10 µs \
         (the bang-bang switching times move with the step: the attitude at 15 s is defined to about that)\n"
    );
}

/// The table of one study in one float type: a line per method.
fn write_cheapest_table(md: &mut String, rows: &[Row], study: &str, float: &str) {
    let _ = writeln!(md, "### {study}, {float}\n");
    let heads: Vec<String> = LEVELS.iter().map(|l| format!("≤ {l:.0e}")).collect();
    let _ = writeln!(
        md,
        "| method | {} | smallest error reached |",
        heads.join(" | ")
    );
    let _ = writeln!(md, "| --- |{} --- |", " --- |".repeat(LEVELS.len()));
    for method in Method::ALL {
        let line = cheapest_line(rows, study, float, method);
        let _ = writeln!(md, "{line} |");
    }
    let _ = writeln!(md);
}

/// One method's line of a table (without its closing `|`): the cheapest
/// run reaching each level, the smallest error reached, and how many
/// settings failed.
fn cheapest_line(rows: &[Row], study: &str, float: &str, method: Method) -> String {
    let mut line = format!("| {} |", method.name());
    for target in LEVELS {
        match cheapest(rows, study, float, method, target) {
            Some(r) => {
                let setting = if method == Method::Dopri {
                    format!("tol {:.0e}", r.setting)
                } else {
                    format!("h {:.0e}", r.setting)
                };
                let _ = write!(
                    line,
                    " {} ({:.2} ms, {setting}) |",
                    r.evaluations,
                    r.wall_s * 1e3
                );
            }
            None => line.push_str(" — |"),
        }
    }
    let best = rows
        .iter()
        .filter(|r| r.study == study && r.float == float && r.method == method && r.status == "ok")
        .map(|r| r.error)
        .fold(f64::INFINITY, f64::min);
    let failures = rows
        .iter()
        .filter(|r| r.study == study && r.float == float && r.method == method && r.status != "ok")
        .count();
    if best.is_finite() {
        let _ = write!(line, " {best:.1e}");
    } else {
        line.push_str(" —");
    }
    if failures > 0 {
        let _ = write!(
            line,
            " ({failures} setting{} failed or diverged)",
            if failures == 1 { "" } else { "s" }
        );
    }
    line
}

/// Prints the evaluations of the cheapest run reaching each error level.
pub(crate) fn print_cheapest(rows: &[Row], plots: &[Plot<'_>]) {
    println!();
    println!("Cheapest run reaching each error level (evaluations):");
    print!("{:<22} {:<4} {:<7}", "study", "f", "method");
    for level in LEVELS {
        print!(" {:>12}", format!("<= {level:.0e}"));
    }
    println!();
    for &(study, _, _, _) in plots {
        for float in ["f64", "f32"] {
            for method in Method::ALL {
                if !rows
                    .iter()
                    .any(|r| r.study == study && r.float == float && r.method == method)
                {
                    continue;
                }
                print!("{:<22} {:<4} {:<7}", study, float, method.name());
                for level in LEVELS {
                    let cell = cheapest(rows, study, float, method, level)
                        .map_or("-".to_string(), |r| r.evaluations.to_string());
                    print!(" {cell:>12}");
                }
                println!();
            }
        }
    }
    println!();
}

//! SVG line plots of recorded columns against time.

use std::prelude::rust_2024::*;
use std::{format, vec};

use std::path::Path;

use plotters::prelude::*;

use super::error::OutputError;
use super::record::Recording;
use crate::Model;

/// One line of a plot: a name and unit for the legend and axis label, and
/// one value per time.
#[derive(Clone, Copy, Debug)]
pub struct Series<'a> {
    /// Name shown in the legend.
    pub name: &'a str,
    /// Unit shown in the legend and on the y axis.
    pub unit: &'a str,
    /// Values, one per entry of the time vector.
    pub values: &'a [f64],
}

/// Plot size in pixels.
const SIZE: (u32, u32) = (900, 560);

/// Draws `series` against `time` as an SVG document: the x axis labelled
/// `time [s]`, the y axis with the series' names and units, and a legend.
/// Non-finite values are left out of the lines.
///
/// Use it for a quick look at a run ([`Recording::plot_svg`] picks the
/// columns by name); use the CSV output for anything quantitative.
///
/// # Errors
/// [`OutputError::Plot`] if there is nothing to draw or drawing fails.
pub fn svg_plot(title: &str, time: &[f64], series: &[Series<'_>]) -> Result<String, OutputError> {
    let (x_range, y_range) = ranges(time, series)?;
    let mut svg = String::new();
    draw(&mut svg, title, time, series, x_range, y_range)
        .map_err(|e| OutputError::Plot(e.to_string()))?;
    Ok(svg)
}

/// Writes [`svg_plot`] to `path`.
///
/// # Errors
/// As [`svg_plot`], and [`OutputError::Io`] if the file cannot be written.
pub fn write_svg_plot(
    path: impl AsRef<Path>,
    title: &str,
    time: &[f64],
    series: &[Series<'_>],
) -> Result<(), OutputError> {
    let svg = svg_plot(title, time, series)?;
    let path = path.as_ref();
    std::fs::write(path, svg).map_err(|source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    })
}

impl<M: Model> Recording<M> {
    /// Plots the named columns (states or outputs) against time into an
    /// SVG file at `path`, titled with the model's name.
    ///
    /// # Errors
    /// [`OutputError::UnknownColumn`] for a name that is not a column
    /// (suggesting the closest), otherwise as [`write_svg_plot`].
    pub fn plot_svg(&self, path: impl AsRef<Path>, columns: &[&str]) -> Result<(), OutputError> {
        let series = columns
            .iter()
            .map(|name| {
                self.column(name).map(|c| Series {
                    name: c.name,
                    unit: c.unit,
                    values: &c.values,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        write_svg_plot(path, M::NAME, self.time(), &series)
    }
}

type Range = (f64, f64);

/// Data ranges of the axes, padded so flat lines are visible.
fn ranges(time: &[f64], series: &[Series<'_>]) -> Result<(Range, Range), OutputError> {
    let bounds = |values: &mut dyn Iterator<Item = f64>| {
        values
            .filter(|v| v.is_finite())
            .fold(None, |acc: Option<Range>, v| match acc {
                None => Some((v, v)),
                Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
            })
    };
    let nothing = || OutputError::Plot("no finite data to plot".to_string());
    if series.is_empty() {
        return Err(OutputError::Plot("no columns chosen".to_string()));
    }
    let x = bounds(&mut time.iter().copied()).ok_or_else(nothing)?;
    let y =
        bounds(&mut series.iter().flat_map(|s| s.values.iter().copied())).ok_or_else(nothing)?;
    let pad = |(lo, hi): Range, fraction: f64| {
        let span = hi - lo;
        if span > 0.0 {
            (lo - fraction * span, hi + fraction * span)
        } else {
            let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo - d, hi + d)
        }
    };
    Ok((pad(x, 0.0), pad(y, 0.05)))
}

/// `a [u], b [u]` when units differ, `a, b [u]` when they agree.
fn y_label(series: &[Series<'_>]) -> String {
    let first_unit = series.first().map(|s| s.unit).unwrap_or("");
    if series.iter().all(|s| s.unit == first_unit) {
        let names: Vec<&str> = series.iter().map(|s| s.name).collect();
        format!("{} [{first_unit}]", names.join(", "))
    } else {
        let parts: Vec<String> = series
            .iter()
            .map(|s| format!("{} [{}]", s.name, s.unit))
            .collect();
        parts.join(", ")
    }
}

fn draw(
    svg: &mut String,
    title: &str,
    time: &[f64],
    series: &[Series<'_>],
    x_range: Range,
    y_range: Range,
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::with_string(svg, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(72)
        .build_cartesian_2d(x_range.0..x_range.1, y_range.0..y_range.1)?;
    chart
        .configure_mesh()
        .x_desc("time [s]")
        .y_desc(y_label(series))
        .axis_desc_style(("sans-serif", 16))
        .draw()?;
    for (i, s) in series.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
        let style = ShapeStyle::from(color).stroke_width(2);
        // Split the line at non-finite values rather than drawing through them.
        let points = time.iter().copied().zip(s.values.iter().copied());
        let mut segment: Vec<(f64, f64)> = Vec::new();
        let mut segments: Vec<Vec<(f64, f64)>> = Vec::new();
        for (t, v) in points {
            if t.is_finite() && v.is_finite() {
                segment.push((t, v));
            } else if !segment.is_empty() {
                segments.push(std::mem::take(&mut segment));
            }
        }
        segments.push(segment);
        let mut first = true;
        for seg in segments {
            let drawn = chart.draw_series(LineSeries::new(seg, style))?;
            if first {
                let label = format!("{} [{}]", s.name, s.unit);
                drawn
                    .label(label)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
                first = false;
            }
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn y_label_merges_a_shared_unit() {
        let v = [0.0];
        let a = Series {
            name: "x",
            unit: "m",
            values: &v,
        };
        let b = Series {
            name: "y",
            unit: "m",
            values: &v,
        };
        let c = Series {
            name: "v",
            unit: "m/s",
            values: &v,
        };
        assert_eq!(y_label(&[a, b]), "x, y [m]");
        assert_eq!(y_label(&[a, c]), "x [m], v [m/s]");
    }

    #[test]
    fn flat_and_empty_data() {
        let t = [0.0, 1.0];
        let flat = [2.0, 2.0];
        let s = Series {
            name: "x",
            unit: "m",
            values: &flat,
        };
        let (_, y) = ranges(&t, &[s]).unwrap();
        assert!(y.0 < 2.0 && y.1 > 2.0);
        let nan = [f64::NAN, f64::NAN];
        let s = Series {
            name: "x",
            unit: "m",
            values: &nan,
        };
        assert!(matches!(ranges(&t, &[s]), Err(OutputError::Plot(_))));
        assert!(matches!(ranges(&t, &[]), Err(OutputError::Plot(_))));
    }
}

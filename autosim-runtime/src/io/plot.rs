//! SVG line plots of recorded columns against time.

use std::prelude::rust_2024::*;
use std::{format, vec};

use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
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
/// Non-finite values are left out of the lines. Series of different units
/// never share an axis: each unit gets its own panel, stacked in the order
/// the units first appear.
///
/// Use it for a quick look at a run ([`Recording::plot_svg`] picks the
/// columns by name); use the CSV output for anything quantitative.
///
/// # Errors
/// [`OutputError::Plot`] if there is nothing to draw or drawing fails.
pub fn svg_plot(title: &str, time: &[f64], series: &[Series<'_>]) -> Result<String, OutputError> {
    ranges(time, series)?;
    let mut units: Vec<&str> = Vec::new();
    for s in series {
        if !units.contains(&s.unit) {
            units.push(s.unit);
        }
    }
    let panels: Vec<Vec<Series<'_>>> = units
        .iter()
        .map(|u| series.iter().filter(|s| s.unit == *u).copied().collect())
        .collect();
    let mut svg = String::new();
    draw_panels(&mut svg, title, time, &panels).map_err(|e| OutputError::Plot(e.to_string()))?;
    Ok(svg)
}

/// One chart per panel, stacked, the title over the first.
fn draw_panels(
    svg: &mut String,
    title: &str,
    time: &[f64],
    panels: &[Vec<Series<'_>>],
) -> Result<(), Box<dyn std::error::Error>> {
    let rows = panels.len().max(1);
    let height = match rows {
        1 => SIZE.1,
        n => 60 + 360 * n as u32,
    };
    let root = SVGBackend::with_string(svg, (SIZE.0, height)).into_drawing_area();
    root.fill(&WHITE)?;
    let areas = root.split_evenly((rows, 1));
    for (k, (area, series)) in areas.iter().zip(panels).enumerate() {
        let (x_range, y_range) = ranges(time, series)?;
        let caption = if k == 0 { title } else { "" };
        draw(area, caption, time, series, x_range, y_range)?;
    }
    root.present()?;
    Ok(())
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
    write_svg(path.as_ref(), svg_plot(title, time, series)?)
}

/// Writes an SVG document to `path`, naming the path if that fails.
fn write_svg(path: &Path, svg: String) -> Result<(), OutputError> {
    std::fs::write(path, svg).map_err(|source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// How an axis of an [`xy_svg_plot`] maps values to positions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Scale {
    /// Equal distances for equal differences.
    #[default]
    Linear,
    /// Equal distances for equal ratios (base 10); values that are not
    /// positive are left out.
    Log,
}

/// Where the legend of an [`xy_svg_plot`] goes, inside the plotting area.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Corner {
    /// Upper left.
    UpperLeft,
    /// Upper right.
    #[default]
    UpperRight,
    /// Lower left (the empty corner of an error-against-cost diagram).
    LowerLeft,
    /// Lower right.
    LowerRight,
}

/// Titles and scales of the axes of an [`xy_svg_plot`], and where its
/// legend goes.
#[derive(Clone, Copy, Debug)]
pub struct Axes<'a> {
    /// Label of the x axis, with its unit.
    pub x_label: &'a str,
    /// Label of the y axis, with its unit.
    pub y_label: &'a str,
    /// Scale of the x axis.
    pub x_scale: Scale,
    /// Scale of the y axis.
    pub y_scale: Scale,
    /// Corner of the legend.
    pub legend: Corner,
}

/// One line of an [`xy_svg_plot`]: the points `(x[i], y[i])` joined in
/// order and marked with dots.
#[derive(Clone, Copy, Debug)]
pub struct XySeries<'a> {
    /// Name shown in the legend.
    pub name: &'a str,
    /// Abscissas.
    pub x: &'a [f64],
    /// Ordinates, one per abscissa.
    pub y: &'a [f64],
    /// Index into the plot's palette: series with the same index share a
    /// colour (e.g. one method in two precisions).
    pub color: usize,
    /// Draw the line dashed rather than solid.
    pub dashed: bool,
}

/// Draws `series` as lines through their points, with linear or
/// logarithmic axes, as an SVG document.
///
/// Use it for plots that are not time histories: work–precision diagrams
/// (error against cost on log–log axes), convergence plots, parameter
/// sweeps. Points with a non-finite coordinate, or a non-positive one on a
/// log axis, are left out (the line is broken there); a log axis spans
/// whole decades.
///
/// # Errors
/// [`OutputError::Plot`] if there is no point to draw, a series' `x` and `y`
/// differ in length, or drawing fails.
pub fn xy_svg_plot(
    title: &str,
    axes: &Axes<'_>,
    series: &[XySeries<'_>],
) -> Result<String, OutputError> {
    if let Some(s) = series.iter().find(|s| s.x.len() != s.y.len()) {
        return Err(OutputError::Plot(format!(
            "series `{}` has {} x values but {} y values",
            s.name,
            s.x.len(),
            s.y.len()
        )));
    }
    let x_range = axis_range(
        series.iter().flat_map(|s| s.x.iter().copied()),
        axes.x_scale,
    )?;
    let y_range = axis_range(
        series.iter().flat_map(|s| s.y.iter().copied()),
        axes.y_scale,
    )?;
    let mut svg = String::new();
    let (x, y) = (x_range.0..x_range.1, y_range.0..y_range.1);
    let drawn = match (axes.x_scale, axes.y_scale) {
        (Scale::Linear, Scale::Linear) => draw_xy(&mut svg, title, axes, series, x, y),
        (Scale::Linear, Scale::Log) => draw_xy(&mut svg, title, axes, series, x, y.log_scale()),
        (Scale::Log, Scale::Linear) => draw_xy(&mut svg, title, axes, series, x.log_scale(), y),
        (Scale::Log, Scale::Log) => {
            draw_xy(&mut svg, title, axes, series, x.log_scale(), y.log_scale())
        }
    };
    drawn.map_err(|e| OutputError::Plot(e.to_string()))?;
    Ok(svg)
}

/// Writes [`xy_svg_plot`] to `path`.
///
/// # Errors
/// As [`xy_svg_plot`], and [`OutputError::Io`] if the file cannot be written.
pub fn write_xy_svg_plot(
    path: impl AsRef<Path>,
    title: &str,
    axes: &Axes<'_>,
    series: &[XySeries<'_>],
) -> Result<(), OutputError> {
    write_svg(path.as_ref(), xy_svg_plot(title, axes, series)?)
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

/// `a, b [u]` (one panel's series share their unit); `value [u]` when the
/// names are long (the legend names them); no brackets without a unit.
fn y_label(series: &[Series<'_>]) -> String {
    let unit = series.first().map(|s| s.unit).unwrap_or("");
    let names: Vec<&str> = series.iter().map(|s| s.name).collect();
    let joined = names.join(", ");
    match joined.chars().count() > 40 {
        true => super::names::labelled("value", unit),
        false => super::names::labelled(&joined, unit),
    }
}

fn draw(
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    title: &str,
    time: &[f64],
    series: &[Series<'_>],
    x_range: Range,
    y_range: Range,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut chart = chart_frame(root, title, 72)
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
        let segments = split_line(points, |t, v| t.is_finite() && v.is_finite());
        let mut first = true;
        for seg in segments {
            let drawn = chart.draw_series(LineSeries::new(seg, style))?;
            if first {
                let label = super::names::labelled(s.name, s.unit);
                drawn
                    .label(label)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
                first = false;
            }
        }
    }
    draw_legend(&mut chart, 14, SeriesLabelPosition::UpperLeft)?;
    Ok(())
}

/// A white drawing area of [`SIZE`] that draws into `svg`.
fn canvas(
    svg: &mut String,
) -> Result<DrawingArea<SVGBackend<'_>, Shift>, Box<dyn std::error::Error>> {
    let root = SVGBackend::with_string(svg, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    Ok(root)
}

/// The frame of a chart on `root`: the title, the margins, and room for the
/// axis labels (`y_label_width` pixels left of the plot).
fn chart_frame<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, Shift>,
    title: &str,
    y_label_width: u32,
) -> ChartBuilder<'a, 'static, SVGBackend<'b>> {
    let mut frame = ChartBuilder::on(root);
    frame
        .caption(title, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(y_label_width);
    frame
}

/// The runs of consecutive points that `keep` accepts, in order: a line
/// split where it cannot be drawn. The last run is there even when empty
/// (a series with nothing to draw still gets its legend entry).
fn split_line(
    points: impl Iterator<Item = (f64, f64)>,
    keep: impl Fn(f64, f64) -> bool,
) -> Vec<Vec<(f64, f64)>> {
    let mut segment: Vec<(f64, f64)> = Vec::new();
    let mut segments: Vec<Vec<(f64, f64)>> = Vec::new();
    for (x, y) in points {
        if keep(x, y) {
            segment.push((x, y));
        } else if !segment.is_empty() {
            segments.push(std::mem::take(&mut segment));
        }
    }
    segments.push(segment);
    segments
}

/// The legend: a framed box of the labelled series at `position`.
fn draw_legend<'a, DB, CT>(
    chart: &mut ChartContext<'a, DB, CT>,
    font_size: u32,
    position: SeriesLabelPosition,
) -> Result<(), Box<dyn std::error::Error>>
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    CT: CoordTranslate,
{
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", font_size))
        .position(position)
        .draw()?;
    Ok(())
}

/// Whether `v` can be drawn on an axis with this scale.
fn drawable(v: f64, scale: Scale) -> bool {
    v.is_finite() && (scale == Scale::Linear || v > 0.0)
}

/// The range of one axis of an xy plot: padded by 5 % (linear), or out to
/// whole decades (log).
fn axis_range(values: impl Iterator<Item = f64>, scale: Scale) -> Result<Range, OutputError> {
    let (lo, hi) = values
        .filter(|v| drawable(*v, scale))
        .fold(None, |acc: Option<Range>, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
        .ok_or_else(|| OutputError::Plot("no point to plot".to_string()))?;
    Ok(match scale {
        Scale::Linear => {
            let span = hi - lo;
            let d = if span > 0.0 {
                0.05 * span
            } else if lo == 0.0 {
                1.0
            } else {
                0.1 * lo.abs()
            };
            (lo - d, hi + d)
        }
        Scale::Log => {
            let lo_decade = lo.log10().floor();
            let hi_decade = hi.log10().ceil().max(lo_decade + 1.0);
            (decade(lo_decade), decade(hi_decade))
        }
    })
}

/// 10^k, exactly as the decimal `1ek` reads (`powf` can be off by an ulp).
fn decade(k: f64) -> f64 {
    format!("1e{k}").parse().unwrap_or(10f64.powf(k))
}

/// A tick label of a log axis: the value rounded to three significant
/// digits (the axis computes its decades in floating point), plain near 1
/// (`0.01`, `100`), in exponent form otherwise (`1e-7`, `2.5e6`).
fn log_label(v: f64) -> String {
    let rounded: f64 = format!("{v:.2e}").parse().unwrap_or(v);
    if rounded == 0.0 || (1e-3..1e4).contains(&rounded.abs()) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}

fn draw_xy<X, Y>(
    svg: &mut String,
    title: &str,
    axes: &Axes<'_>,
    series: &[XySeries<'_>],
    x_spec: X,
    y_spec: Y,
) -> Result<(), Box<dyn std::error::Error>>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let root = canvas(svg)?;
    let mut chart = chart_frame(&root, title, 80).build_cartesian_2d(x_spec, y_spec)?;
    let x_log = axes.x_scale == Scale::Log;
    let y_log = axes.y_scale == Scale::Log;
    let x_fmt = |v: &f64| if x_log { log_label(*v) } else { format!("{v}") };
    let y_fmt = |v: &f64| if y_log { log_label(*v) } else { format!("{v}") };
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(axes.x_label)
        .y_desc(axes.y_label)
        .axis_desc_style(("sans-serif", 16));
    if x_log {
        mesh.x_label_formatter(&x_fmt);
    }
    if y_log {
        mesh.y_label_formatter(&y_fmt);
    }
    mesh.draw()?;
    for s in series {
        let color = Palette99::pick(s.color).to_rgba();
        let style = ShapeStyle::from(color).stroke_width(2);
        // Split the line where a point cannot be drawn.
        let points = s.x.iter().copied().zip(s.y.iter().copied());
        let segments = split_line(points, |x, y| {
            drawable(x, axes.x_scale) && drawable(y, axes.y_scale)
        });
        let mut first = true;
        for seg in segments.into_iter().filter(|seg| !seg.is_empty()) {
            chart.draw_series(seg.iter().map(|p| Circle::new(*p, 3, style.filled())))?;
            let drawn = if s.dashed {
                chart.draw_series(DashedLineSeries::new(seg, 8, 5, style))?
            } else {
                chart.draw_series(LineSeries::new(seg, style))?
            };
            if first {
                // Two strokes: touching for a solid line, apart for a dashed one.
                let gap = if s.dashed { 6 } else { 0 };
                drawn.label(s.name).legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (12 - gap / 2, 0)], style)
                        + PathElement::new(vec![(12 + gap / 2, 0), (24, 0)], style)
                });
                first = false;
            }
        }
    }
    let position = match axes.legend {
        Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
        Corner::UpperRight => SeriesLabelPosition::UpperRight,
        Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
        Corner::LowerRight => SeriesLabelPosition::LowerRight,
    };
    draw_legend(&mut chart, 13, position)?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn y_label_merges_a_panels_unit() {
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
            name: "h",
            unit: "",
            values: &v,
        };
        assert_eq!(y_label(&[a, b]), "x, y [m]");
        assert_eq!(y_label(&[c]), "h");
        let long = Series {
            name: "a rather long series name",
            unit: "rad",
            values: &v,
        };
        assert_eq!(y_label(&[long, long]), "value [rad]");
    }

    #[test]
    fn log_axes_span_whole_decades_and_skip_non_positive_values() {
        let v = [3e-7, 0.0, -1.0, f64::NAN, 2e-2];
        let r = axis_range(v.iter().copied(), Scale::Log).unwrap();
        assert_eq!(r, (1e-7, 1e-1));
        let r = axis_range([5.0].into_iter(), Scale::Log).unwrap();
        assert_eq!(r, (1.0, 10.0));
        assert!(matches!(
            axis_range([0.0, -2.0].into_iter(), Scale::Log),
            Err(OutputError::Plot(_))
        ));
        let r = axis_range([0.0, -2.0].into_iter(), Scale::Linear).unwrap();
        assert!(r.0 < -2.0 && r.1 > 0.0);
    }

    #[test]
    fn xy_plot_draws_log_log_lines_and_checks_lengths() {
        let x = [10.0, 100.0, 1000.0];
        let y = [1e-2, 1e-6, 0.0];
        let axes = Axes {
            x_label: "evaluations",
            y_label: "error [rad]",
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            legend: Corner::LowerLeft,
        };
        let series = [
            XySeries {
                name: "RK4",
                x: &x,
                y: &y,
                color: 0,
                dashed: false,
            },
            XySeries {
                name: "RK4 f32",
                x: &x,
                y: &y[..2],
                color: 0,
                dashed: true,
            },
        ];
        assert!(matches!(
            xy_svg_plot("t", &axes, &series),
            Err(OutputError::Plot(m)) if m.contains("RK4 f32")
        ));
        let svg = xy_svg_plot("work-precision", &axes, &series[..1]).unwrap();
        assert!(svg.starts_with("<svg"));
        for text in [
            "work-precision",
            "evaluations",
            "error [rad]",
            "RK4",
            "1e-5",
        ] {
            assert!(svg.contains(text), "{text} missing from the plot");
        }
        assert_eq!(log_label(1e-6), "1e-6");
        assert_eq!(log_label(0.01), "0.01");
        assert_eq!(log_label(1e5), "1e5");
        assert_eq!(log_label(0.0009999999999999998), "0.001");
        assert_eq!(log_label(9.999999999999999e-5), "1e-4");
        assert_eq!(log_label(2.5e6), "2.5e6");
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

//! Eigenvalues over a swept speed or parameter, their plots (real and
//! imaginary parts against the parameter; root locus), and the search for
//! where a quantity crosses zero (weave and capsize speeds).

use super::{Complex, LinearSystem};
use crate::io::{Axes, Corner, OutputError, Scale, XySeries, xy_svg_plot};
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

/// Eigenvalues of a linear model at each value of a parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// What was swept, with its unit (axis label).
    pub parameter: String,
    /// The values.
    pub values: Vec<f64>,
    /// The eigenvalues at each value, sorted by real part.
    pub eigenvalues: Vec<Vec<Complex<f64>>>,
}

impl Sweep {
    /// Linearizes with `at(value)` at every value and keeps the
    /// eigenvalues.
    ///
    /// # Errors
    /// The first error of `at`.
    pub fn run<E>(
        parameter: &str,
        values: &[f64],
        mut at: impl FnMut(f64) -> Result<LinearSystem, E>,
    ) -> Result<Sweep, E> {
        let mut eigenvalues = Vec::with_capacity(values.len());
        for v in values {
            eigenvalues.push(at(*v)?.eigenvalues());
        }
        Ok(Sweep {
            parameter: parameter.to_string(),
            values: values.to_vec(),
            eigenvalues,
        })
    }

    /// The most eigenvalues at any value (the number of series to plot).
    fn eigenvalue_count(&self) -> usize {
        self.eigenvalues.iter().map(Vec::len).max().unwrap_or(0)
    }

    /// `part` of the `k`-th eigenvalue at each value (NaN where there are
    /// fewer eigenvalues).
    fn trace(&self, k: usize, part: fn(&Complex<f64>) -> f64) -> Vec<f64> {
        self.eigenvalues
            .iter()
            .map(|ev| ev.get(k).map_or(f64::NAN, part))
            .collect()
    }

    /// Real parts (solid) and imaginary parts (dashed, the frequencies)
    /// of the eigenvalues against the parameter, as an SVG document; the
    /// k-th series joins the k-th eigenvalue by real part at each value.
    ///
    /// # Errors
    /// [`OutputError::Plot`] if there is nothing to draw.
    pub fn eigenvalues_svg(&self, title: &str) -> Result<String, OutputError> {
        let n = self.eigenvalue_count();
        let re: Vec<Vec<f64>> = (0..n).map(|k| self.trace(k, |c| c.re)).collect();
        let im: Vec<Vec<f64>> = (0..n).map(|k| self.trace(k, |c| c.im.abs())).collect();
        let names: Vec<(String, String)> = (0..n)
            .map(|k| (format!("Re λ{}", k + 1), format!("|Im λ{}|", k + 1)))
            .collect();
        let mut series = Vec::with_capacity(2 * n);
        for k in 0..n {
            // In the eigenvalue's color: the real part solid, the imaginary
            // part dashed.
            let line = |name, y, dashed| XySeries {
                name,
                x: &self.values,
                y,
                color: k,
                dashed,
            };
            series.push(line(&names[k].0, &re[k], false));
            series.push(line(&names[k].1, &im[k], true));
        }
        let axes = Axes {
            x_label: &self.parameter,
            y_label: "eigenvalue [1/s]",
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            legend: Corner::UpperRight,
        };
        xy_svg_plot(title, &axes, &series)
    }

    /// The root locus: imaginary against real part of every eigenvalue,
    /// one series per eigenvalue index, as an SVG document.
    ///
    /// # Errors
    /// [`OutputError::Plot`] if there is nothing to draw.
    pub fn root_locus_svg(&self, title: &str) -> Result<String, OutputError> {
        let n = self.eigenvalue_count();
        let points: Vec<(Vec<f64>, Vec<f64>)> = (0..n)
            .map(|k| (self.trace(k, |c| c.re), self.trace(k, |c| c.im)))
            .collect();
        let names: Vec<String> = (0..n).map(|k| format!("λ{}", k + 1)).collect();
        let series: Vec<XySeries<'_>> = (0..n)
            .map(|k| XySeries {
                name: &names[k],
                x: &points[k].0,
                y: &points[k].1,
                color: k,
                dashed: false,
            })
            .collect();
        let axes = Axes {
            x_label: "Re λ [1/s]",
            y_label: "Im λ [1/s]",
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            legend: Corner::UpperLeft,
        };
        xy_svg_plot(title, &axes, &series)
    }
}

/// A zero of `f` between `lo` and `hi` (where `f` changes sign), by
/// bisection to `tolerance` (about 40 evaluations per 1e-12 of a unit
/// bracket). `None` if `f` has the same sign at both ends or is not finite.
pub fn find_crossing(
    mut f: impl FnMut(f64) -> f64,
    lo: f64,
    hi: f64,
    tolerance: f64,
) -> Option<f64> {
    let (mut a, mut b) = (lo, hi);
    let fa = f(a);
    let fb = f(b);
    if !(fa.is_finite() && fb.is_finite()) || fa * fb > 0.0 {
        return None;
    }
    if fa == 0.0 {
        return Some(a);
    }
    if fb == 0.0 {
        return Some(b);
    }
    let negative_at_a = fa < 0.0;
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (b - a).abs() <= tolerance || m == a || m == b {
            return Some(m);
        }
        let fm = f(m);
        if !fm.is_finite() {
            return None;
        }
        if fm == 0.0 {
            return Some(m);
        }
        if (fm < 0.0) == negative_at_a {
            a = m;
        } else {
            b = m;
        }
    }
    Some(0.5 * (a + b))
}

//! Modes of a linear system: each eigenvalue as a natural frequency and
//! damping ratio (oscillatory) or a time constant (real), with its shape
//! labelled by state. Eigenvectors by inverse iteration on `A − λI`
//! (nalgebra gives eigenvalues of general real matrices, not vectors).

use super::{Complex, LinearSystem};
use nalgebra::DMatrix;
use std::fmt;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

/// One mode of a linear system.
#[derive(Clone, Debug, PartialEq)]
pub struct Mode {
    /// The eigenvalue `λ` (1/s).
    pub eigenvalue: Complex<f64>,
    /// `|λ|` (rad/s).
    pub natural_frequency: f64,
    /// `−Re λ / |λ|`: 1 critically damped, 0 undamped, negative unstable
    /// (0 for `λ = 0`).
    pub damping_ratio: f64,
    /// `−1 / λ` for a real eigenvalue (s): the time to decay by `e`
    /// (negative: to grow by `e`); `None` for an oscillatory mode.
    pub time_constant: Option<f64>,
    /// The eigenvector, scaled so its largest entry is 1, with the state
    /// names.
    pub shape: Vec<(String, Complex<f64>)>,
}

impl Mode {
    /// `true` if the mode grows.
    pub fn is_unstable(&self) -> bool {
        self.eigenvalue.re > 0.0
    }
}

/// `x` to `decimals` places, never `-0.000…` (a value that rounds to
/// zero prints without a sign).
pub(super) fn fixed(x: f64, decimals: usize) -> String {
    let text = format!("{x:.decimals$}");
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let l = self.eigenvalue;
        match self.time_constant {
            _ if l.norm() == 0.0 => write!(f, "λ = 0 (a rigid-body or ignorable motion)")?,
            Some(tau) if tau < 0.0 => write!(
                f,
                "λ = {} 1/s, unstable: grows by a factor e every {} s",
                fixed(l.re, 6),
                fixed(-tau, 6)
            )?,
            Some(tau) => write!(
                f,
                "λ = {} 1/s, time constant {} s",
                fixed(l.re, 6),
                fixed(tau, 6)
            )?,
            None => write!(
                f,
                "λ = {} ± {}i 1/s, ωn = {} rad/s, ζ = {}{}",
                fixed(l.re, 6),
                fixed(l.im.abs(), 6),
                fixed(self.natural_frequency, 6),
                fixed(self.damping_ratio, 6),
                if self.is_unstable() { ", unstable" } else { "" }
            )?,
        }
        let mut main: Vec<&(String, Complex<f64>)> = self.shape.iter().collect();
        main.sort_by(|a, b| b.1.norm().total_cmp(&a.1.norm()));
        let parts: Vec<String> = main
            .iter()
            .take(3)
            .map(|(n, v)| format!("{n} {:.3}", v.norm()))
            .collect();
        write!(f, " [{}]", parts.join(", "))
    }
}

impl LinearSystem {
    /// The modes of `A`: one per real eigenvalue, one per complex pair (the
    /// one with positive imaginary part), sorted by real part. Eigenvalues
    /// within `1e-6 ‖A‖` of zero (rigid-body and ignorable motions, whose
    /// multiple zeros the eigenvalue solver spreads by about the square
    /// root of the rounding) are reported as exactly zero, and a complex
    /// pair's real part within `1e-12 ‖A‖` of zero (an undamped
    /// oscillation's rounding) as zero (`‖A‖` the largest entry's
    /// magnitude, at least 1).
    pub fn modes(&self) -> Vec<Mode> {
        let scale = self.a.amax().max(1.0);
        let mut modes = Vec::new();
        for l in self.eigenvalues() {
            let zero = l.norm() <= 1e-6 * scale;
            let l = if zero { Complex::new(0.0, 0.0) } else { l };
            let real = l.im.abs() <= 1e-12 * scale;
            if !real && l.im < 0.0 {
                continue;
            }
            let l = if real { Complex::new(l.re, 0.0) } else { l };
            // An oscillation's real part within rounding of zero is zero:
            // neutral, not unstable by 1e-16.
            let neutral = !real && l.re.abs() <= 1e-12 * scale;
            let l = if neutral { Complex::new(0.0, l.im) } else { l };
            let wn = l.norm();
            // An undamped mode's ratio is 0, not the -0 of `-0.0 / wn`.
            let zeta = if l.re == 0.0 { 0.0 } else { -l.re / wn };
            let tau = (real && l.re != 0.0).then(|| -1.0 / l.re);
            let shape = self
                .eigenvector(l)
                .into_iter()
                .zip(&self.states)
                .map(|(v, s)| (s.name.clone(), v))
                .collect();
            modes.push(Mode {
                eigenvalue: l,
                natural_frequency: wn,
                damping_ratio: zeta,
                time_constant: tau,
                shape,
            });
        }
        // Sorted again: a neutral pair's real part is now zero.
        modes.sort_by(|a, b| {
            let (a, b) = (a.eigenvalue, b.eigenvalue);
            a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im))
        });
        modes
    }

    /// An eigenvector for `λ` by two steps of inverse iteration, scaled so
    /// its largest entry is 1.
    fn eigenvector(&self, l: Complex<f64>) -> Vec<Complex<f64>> {
        let n = self.a.nrows();
        let shift = l + Complex::new(1e-10 * (1.0 + l.norm()), 0.0);
        let m: DMatrix<Complex<f64>> = DMatrix::from_fn(n, n, |i, j| {
            let a = Complex::new(self.a[(i, j)], 0.0);
            if i == j { a - shift } else { a }
        });
        let lu = m.lu();
        let mut v = nalgebra::DVector::from_element(n, Complex::new(1.0, 0.0));
        for _ in 0..3 {
            match lu.solve(&v) {
                Some(w) => {
                    let big = w.iter().map(|c| c.norm()).fold(0.0, f64::max);
                    if !(big > 0.0 && big.is_finite()) {
                        break;
                    }
                    v = w / Complex::new(big, 0.0);
                }
                None => break,
            }
        }
        // Scale the largest entry to 1 (real).
        let (k, _) = v.iter().enumerate().fold((0, 0.0), |best, (k, c)| {
            if c.norm() > best.1 {
                (k, c.norm())
            } else {
                best
            }
        });
        let pivot = v[k];
        if pivot.norm() > 0.0 {
            v /= pivot;
        }
        v.iter().copied().collect()
    }

    /// A table of the modes, one per line (for reports).
    /// Zero eigenvalues (rigid-body and ignorable motions) are one line
    /// with their count: their shapes are any combination of the motions,
    /// so listing one shape each says nothing.
    pub fn modes_report(&self) -> String {
        let mut s = String::new();
        for line in self.mode_lines() {
            s.push_str(&line);
            s.push('\n');
        }
        s
    }

    /// The modes as lines of text, the zero eigenvalues grouped in one.
    pub(super) fn mode_lines(&self) -> Vec<String> {
        let modes = self.modes();
        let zeros = modes.iter().filter(|m| m.eigenvalue.norm() == 0.0).count();
        let mut lines = Vec::new();
        let mut grouped = false;
        for m in &modes {
            if m.eigenvalue.norm() == 0.0 && zeros > 1 {
                if !grouped {
                    lines.push(format!(
                        "λ = 0, {zeros} times (rigid-body or ignorable motions; their shapes are any combination of them)"
                    ));
                    grouped = true;
                }
                continue;
            }
            lines.push(m.to_string());
        }
        lines
    }

    /// The names of the states, in order.
    pub fn state_names(&self) -> Vec<String> {
        self.states.iter().map(|s| s.name.to_string()).collect()
    }
}

//! Modes of a linear system: each eigenvalue as a natural frequency and
//! damping ratio (oscillatory) or a time constant (real), with its shape
//! labelled by state. Eigenvectors by inverse iteration on `A − λI`
//! (nalgebra gives eigenvalues of general real matrices, not vectors); a
//! repeated eigenvalue's from the null space of `A − λI` (a singular value
//! decomposition), so its copies have independent shapes.

use super::{Complex, LinearSystem};
use nalgebra::{DMatrix, DVector};
use std::fmt;
use std::format;
use std::string::{String, ToString};
use std::vec;
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
    /// names. The copies of a repeated eigenvalue have independent
    /// eigenvectors (any combination of them is one too); where there are
    /// fewer independent eigenvectors than copies (a defective eigenvalue,
    /// such as a coordinate whose rate is itself a state: `λ = 0` twice
    /// with one eigenvector), the extra copies have generalized
    /// eigenvectors (of the null space of `(A − λI)^k` for `k` copies)
    /// independent of the eigenvectors, so the copies' shapes span the
    /// motions of that eigenvalue.
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

/// One entry of a shape as a report prints it: signed for a real mode
/// (`-1.000`: against the largest entry), magnitude and phase in degrees
/// for an oscillation (`0.500∠-90°`: a quarter period behind it).
fn component(v: Complex<f64>, real: bool) -> String {
    if real {
        return fixed(v.re, 3);
    }
    let phase = v.im.atan2(v.re).to_degrees();
    format!("{}∠{}°", fixed(v.norm(), 3), fixed(phase, 0))
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
        let real = self.eigenvalue.im == 0.0;
        let parts: Vec<String> = main
            .iter()
            .take(3)
            .map(|(n, v)| format!("{n} {}", component(*v, real)))
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
        let values: Vec<Complex<f64>> = self
            .eigenvalues()
            .into_iter()
            .filter_map(|l| snapped(l, scale))
            .collect();
        let shapes = self.shapes(&values, scale);
        let mut modes: Vec<Mode> = values
            .into_iter()
            .zip(shapes)
            .map(|(l, vector)| {
                let real = l.im == 0.0;
                let wn = l.norm();
                // An undamped mode's ratio is 0, not the -0 of `-0.0 / wn`.
                let zeta = if l.re == 0.0 { 0.0 } else { -l.re / wn };
                let tau = (real && l.re != 0.0).then(|| -1.0 / l.re);
                let shape = vector
                    .into_iter()
                    .zip(&self.states)
                    .map(|(v, s)| (s.name.clone(), v))
                    .collect();
                Mode {
                    eigenvalue: l,
                    natural_frequency: wn,
                    damping_ratio: zeta,
                    time_constant: tau,
                    shape,
                }
            })
            .collect();
        // Sorted again: a neutral pair's real part is now zero.
        modes.sort_by(|a, b| {
            let (a, b) = (a.eigenvalue, b.eigenvalue);
            a.re.total_cmp(&b.re).then(a.im.total_cmp(&b.im))
        });
        modes
    }

    /// The shape of each eigenvalue in `values`. Equal eigenvalues
    /// (within `1e-6 ‖A‖`) share out a basis of their eigenvectors and,
    /// where there are fewer of those than copies (a defective
    /// eigenvalue), generalized eigenvectors; one inverse iteration would
    /// give every copy the same vector.
    fn shapes(&self, values: &[Complex<f64>], scale: f64) -> Vec<Vec<Complex<f64>>> {
        let close = |a: Complex<f64>, b: Complex<f64>| (a - b).norm() <= 1e-6 * scale;
        let mut shapes: Vec<Option<Vec<Complex<f64>>>> = vec![None; values.len()];
        for (i, &l) in values.iter().enumerate() {
            if shapes[i].is_some() {
                continue;
            }
            let copies: Vec<usize> = (i..values.len())
                .filter(|&j| shapes[j].is_none() && close(values[j], l))
                .collect();
            let vectors = match copies.len() {
                1 => vec![self.eigenvector(l)],
                k => self.eigenspace(l, k, scale),
            };
            for (j, v) in copies.into_iter().zip(vectors) {
                shapes[j] = Some(v);
            }
        }
        shapes.into_iter().map(Option::unwrap_or_default).collect()
    }

    /// `k` shapes for an eigenvalue `λ` repeated `k` times: a basis of
    /// the null space of `A − λI` (its eigenvectors: right singular
    /// vectors whose singular values are below `1e-6` of `‖A‖`), completed
    /// where it is smaller by vectors of the null space of `(A − λI)^k`
    /// (the generalized eigenvectors) independent of it; each scaled so its
    /// largest entry is 1.
    fn eigenspace(&self, l: Complex<f64>, k: usize, scale: f64) -> Vec<Vec<Complex<f64>>> {
        let m = self.shifted(l) / Complex::new(scale, 0.0);
        let mut basis = null_space(&m, k, Some(1e-6));
        if basis.is_empty() {
            // Orthonormal, as the projections of `independent_of` need.
            basis.push(DVector::from_vec(self.eigenvector(l)).normalize());
        }
        if basis.len() < k {
            let mut power = m.clone();
            for _ in 1..k {
                power = &power * &m;
            }
            let general = null_space(&power, k, None);
            basis.extend(independent_of(&basis, &general, k - basis.len()));
        }
        basis
            .into_iter()
            .map(|v| scaled(v).iter().copied().collect())
            .collect()
    }

    /// `A − λI`, complex.
    fn shifted(&self, l: Complex<f64>) -> DMatrix<Complex<f64>> {
        let n = self.a.nrows();
        DMatrix::from_fn(n, n, |i, j| {
            let a = Complex::new(self.a[(i, j)], 0.0);
            if i == j { a - l } else { a }
        })
    }

    /// An eigenvector for `λ` by two steps of inverse iteration, scaled so
    /// its largest entry is 1.
    fn eigenvector(&self, l: Complex<f64>) -> Vec<Complex<f64>> {
        let n = self.a.nrows();
        let lu = self
            .shifted(l + Complex::new(1e-10 * (1.0 + l.norm()), 0.0))
            .lu();
        let mut v = DVector::from_element(n, Complex::new(1.0, 0.0));
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
        scaled(v).iter().copied().collect()
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

/// An eigenvalue as a mode reports it, or `None` for the second of a
/// complex pair (the one with negative imaginary part): within
/// `1e-6 ‖A‖` of zero exactly zero, an imaginary part within `1e-12 ‖A‖`
/// zero (real), a pair's real part within `1e-12 ‖A‖` zero (neutral, not
/// unstable by 1e-16).
fn snapped(l: Complex<f64>, scale: f64) -> Option<Complex<f64>> {
    if l.norm() <= 1e-6 * scale {
        return Some(Complex::new(0.0, 0.0));
    }
    if l.im.abs() <= 1e-12 * scale {
        return Some(Complex::new(l.re, 0.0));
    }
    if l.im < 0.0 {
        return None;
    }
    let re = if l.re.abs() <= 1e-12 * scale {
        0.0
    } else {
        l.re
    };
    Some(Complex::new(re, l.im))
}

/// `v` divided by its largest entry (which becomes 1), or `v` if it is
/// zero.
fn scaled(v: DVector<Complex<f64>>) -> DVector<Complex<f64>> {
    let pivot = v.iter().fold(Complex::new(0.0, 0.0), |best, &c| {
        if c.norm() > best.norm() { c } else { best }
    });
    if pivot.norm() > 0.0 { v / pivot } else { v }
}

/// Up to `k` orthonormal vectors of the null space of `m`: its right
/// singular vectors with the smallest singular values, those above `tol`
/// left out when a `tol` is given.
fn null_space(m: &DMatrix<Complex<f64>>, k: usize, tol: Option<f64>) -> Vec<DVector<Complex<f64>>> {
    let svd = m.clone().svd(false, true);
    let Some(v_t) = &svd.v_t else {
        return Vec::new();
    };
    let sv = &svd.singular_values;
    by_singular_value(sv.as_slice())
        .into_iter()
        .take(k)
        .filter(|&i| tol.is_none_or(|t| sv[i] <= t))
        .map(|i| v_t.row(i).adjoint())
        .collect()
}

/// `count` orthonormal directions of the span of `candidates` that are
/// orthogonal to the orthonormal `basis`: the candidates' parts outside
/// the basis, and of those the strongest directions (a singular value
/// decomposition).
fn independent_of(
    basis: &[DVector<Complex<f64>>],
    candidates: &[DVector<Complex<f64>>],
    count: usize,
) -> Vec<DVector<Complex<f64>>> {
    let Some(n) = candidates.first().map(|c| c.len()) else {
        return Vec::new();
    };
    let parts: Vec<DVector<Complex<f64>>> = candidates
        .iter()
        .map(|c| {
            let mut c = c.clone();
            for b in basis {
                let along = b.dotc(&c);
                c -= b * along;
            }
            c
        })
        .collect();
    let outside = DMatrix::from_fn(n, parts.len(), |i, j| parts[j][i]);
    let svd = outside.svd(true, false);
    let Some(u) = &svd.u else {
        return Vec::new();
    };
    by_singular_value(svd.singular_values.as_slice())
        .into_iter()
        .rev()
        .take(count)
        .map(|j| u.column(j).into_owned())
        .collect()
}

/// The indices of the singular values `sv`, smallest first.
fn by_singular_value(sv: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..sv.len()).collect();
    order.sort_by(|&a, &b| sv[a].total_cmp(&sv[b]));
    order
}

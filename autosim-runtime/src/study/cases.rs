//! The table of cases: named columns of values, built from grids, lists of
//! rows and random draws, and computed case by case from the case's index
//! (nothing is held whole, and a case's values never depend on which
//! other cases ran or on how many threads ran them).

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use std::fmt::Write as _;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use super::StudyError;

/// A distribution to draw a column's values from (see [`Cases::random`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Distribution {
    /// Uniform on `[low, high)`.
    Uniform {
        /// Lower bound (included).
        low: f64,
        /// Upper bound (excluded).
        high: f64,
    },
    /// Normal (Gaussian) with the given mean and standard deviation.
    Normal {
        /// Mean.
        mean: f64,
        /// Standard deviation (≥ 0).
        std_dev: f64,
    },
}

impl Distribution {
    /// [`Distribution::Uniform`] on `[low, high)`.
    pub fn uniform(low: f64, high: f64) -> Distribution {
        Distribution::Uniform { low, high }
    }

    /// [`Distribution::Normal`] with this mean and standard deviation.
    pub fn normal(mean: f64, std_dev: f64) -> Distribution {
        Distribution::Normal { mean, std_dev }
    }

    fn check(&self, name: &str) -> Result<(), StudyError> {
        let ok = match *self {
            Distribution::Uniform { low, high } => {
                low.is_finite() && high.is_finite() && low < high
            }
            Distribution::Normal { mean, std_dev } => {
                mean.is_finite() && std_dev.is_finite() && std_dev >= 0.0
            }
        };
        if ok {
            Ok(())
        } else {
            Err(StudyError::InvalidCases(format!(
                "column `{name}`: {self:?} is not a distribution (finite bounds with low < high, or a finite mean and a standard deviation ≥ 0)"
            )))
        }
    }

    fn draw(&self, rng: &mut ChaCha8Rng) -> f64 {
        match *self {
            Distribution::Uniform { low, high } => low + (high - low) * rng.random::<f64>(),
            Distribution::Normal { mean, std_dev } => {
                let z: f64 = rng.sample(rand_distr::StandardNormal);
                mean + std_dev * z
            }
        }
    }
}

/// One factor of the table: its columns vary together.
#[derive(Clone, Debug, PartialEq)]
enum Factor {
    /// One column over a list of values.
    Axis(Vec<f64>),
    /// Several columns over rows given one by one (row-major).
    Rows { width: usize, values: Vec<f64> },
    /// Several columns drawn at random, `count` rows.
    Random {
        count: u64,
        seed: u64,
        distributions: Vec<Distribution>,
    },
}

impl Factor {
    fn len(&self) -> u64 {
        match self {
            Factor::Axis(values) => values.len() as u64,
            Factor::Rows { width, values } => (values.len() / (*width).max(1)) as u64,
            Factor::Random { count, .. } => *count,
        }
    }

    fn width(&self) -> usize {
        match self {
            Factor::Axis(_) => 1,
            Factor::Rows { width, .. } => *width,
            Factor::Random { distributions, .. } => distributions.len(),
        }
    }

    /// Writes row `row` of this factor into `out` (its width).
    fn write(&self, row: u64, out: &mut [f64]) {
        match self {
            Factor::Axis(values) => out[0] = values[row as usize],
            Factor::Rows { width, values } => {
                let start = row as usize * width;
                out.copy_from_slice(&values[start..start + width]);
            }
            Factor::Random {
                seed,
                distributions,
                ..
            } => {
                // One ChaCha stream per row: the row's draws depend on the
                // seed and the row alone.
                let mut rng = ChaCha8Rng::seed_from_u64(*seed);
                rng.set_stream(row);
                for (o, d) in out.iter_mut().zip(distributions) {
                    *o = d.draw(&mut rng);
                }
            }
        }
    }

    /// A line for the study's manifest (what a resumed study must match).
    fn describe(&self, out: &mut String) {
        let _ = match self {
            Factor::Axis(values) => {
                writeln!(out, "axis {:016x} ({} values)", hash(values), values.len())
            }
            Factor::Rows { width, values } => writeln!(
                out,
                "rows {:016x} ({} rows of {width})",
                hash(values),
                values.len() / (*width).max(1)
            ),
            Factor::Random {
                count,
                seed,
                distributions,
            } => writeln!(out, "random {count} draws, seed {seed}, {distributions:?}"),
        };
    }
}

/// FNV-1a over the bits of `values` (a fingerprint for the manifest).
pub(super) fn hash(values: &[f64]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for v in values {
        for b in v.to_bits().to_le_bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// The table of cases of a study: named columns (a model's parameters,
/// inputs or initial states, or columns a setup function reads), built as
/// the product of factors.
///
/// [`Cases::new`] is one case with no columns; each [`grid`](Cases::grid),
/// [`rows`](Cases::rows) or [`random`](Cases::random) multiplies the table
/// by a factor, like a nested loop with the first factor outermost: case
/// `i` is decoded from its index in mixed radix (the last factor varies
/// fastest). A case's values are computed from its index when it runs,
/// so a table of 10⁹ cases costs nothing to hold, and the values never
/// depend on the order or the threads the cases ran on.
///
/// ```
/// use autosim_runtime::study::{Cases, Distribution};
/// let cases = Cases::new()
///     .grid("v", &[1.0, 2.0, 3.0])
///     .unwrap()
///     .random(100, 7, &[("m", Distribution::normal(80.0, 5.0))])
///     .unwrap();
/// assert_eq!(cases.len(), 300);
/// assert_eq!(cases.names(), ["v", "m"]);
/// let mut row = [0.0; 2];
/// cases.case(101, &mut row); // v = 2 (the second grid value), draw 1
/// assert_eq!(row[0], 2.0);
/// let mut again = [0.0; 2];
/// cases.case(1, &mut again); // v = 1, the same draw 1
/// assert_eq!(row[1], again[1]);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Cases {
    names: Vec<String>,
    factors: Vec<Factor>,
}

impl Default for Cases {
    fn default() -> Self {
        Self::new()
    }
}

impl Cases {
    /// One case and no columns (every model value at its default).
    pub fn new() -> Cases {
        Cases {
            names: Vec::new(),
            factors: Vec::new(),
        }
    }

    /// The table times a grid axis: column `name` takes each of `values`.
    ///
    /// # Errors
    /// [`StudyError::InvalidCases`] for a repeated name, no values, or a
    /// value that is not finite.
    pub fn grid(self, name: &str, values: &[f64]) -> Result<Cases, StudyError> {
        self.with(&[name], Factor::Axis(values.to_vec()))
    }

    /// The table times a list of rows: columns `names` take the values of
    /// each row in turn (`rows` is row-major, `names.len()` values a row):
    /// a table from a file or from Python.
    ///
    /// # Errors
    /// [`StudyError::InvalidCases`] for a repeated name, a length that is
    /// not a whole number of rows, no rows, or a value that is not finite.
    pub fn rows(self, names: &[&str], rows: &[f64]) -> Result<Cases, StudyError> {
        let width = names.len();
        if width == 0 || !rows.len().is_multiple_of(width) {
            return Err(StudyError::InvalidCases(format!(
                "{} values are not whole rows of {width} columns",
                rows.len()
            )));
        }
        self.with(
            names,
            Factor::Rows {
                width,
                values: rows.to_vec(),
            },
        )
    }

    /// The table times `count` random draws: each column `name` drawn from
    /// its distribution. Draw `k` comes from its own ChaCha8 stream (seed
    /// `seed`, stream `k`), so it is the same whatever else the table
    /// holds: at every point of a grid the same `count` draws (common
    /// random numbers), and the same on any number of threads or
    /// machines.
    ///
    /// # Errors
    /// [`StudyError::InvalidCases`] for a repeated name, zero draws, or a
    /// distribution with bad parameters.
    pub fn random(
        self,
        count: u64,
        seed: u64,
        columns: &[(&str, Distribution)],
    ) -> Result<Cases, StudyError> {
        for (name, d) in columns {
            d.check(name)?;
        }
        let names: Vec<&str> = columns.iter().map(|c| c.0).collect();
        let distributions = columns.iter().map(|c| c.1).collect();
        self.with(
            &names,
            Factor::Random {
                count,
                seed,
                distributions,
            },
        )
    }

    fn with(mut self, names: &[&str], factor: Factor) -> Result<Cases, StudyError> {
        let invalid = |why: String| Err(StudyError::InvalidCases(why));
        for (k, name) in names.iter().enumerate() {
            if self.names.iter().any(|n| n == name) || names[..k].contains(name) {
                return invalid(format!("column `{name}` is given twice"));
            }
        }
        if factor.len() == 0 {
            return invalid(format!("columns {names:?} have no values"));
        }
        let values = match &factor {
            Factor::Axis(v) | Factor::Rows { values: v, .. } => v.as_slice(),
            Factor::Random { .. } => &[],
        };
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            return invalid(format!("columns {names:?} hold the value {v}"));
        }
        if self.len().checked_mul(factor.len()).is_none() {
            return invalid("more than 2^64 cases".to_string());
        }
        self.names.extend(names.iter().map(|n| n.to_string()));
        self.factors.push(factor);
        Ok(self)
    }

    /// The number of cases (the product of the factors' lengths).
    pub fn len(&self) -> u64 {
        self.factors.iter().map(Factor::len).product()
    }

    /// Always `false`: a table has at least one case.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The column names, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Writes the values of case `index` (`< len()`) into `out` (one per
    /// column).
    ///
    /// # Panics
    /// If `index` is out of range or `out` is not one value per column.
    pub fn case(&self, index: u64, out: &mut [f64]) {
        assert!(index < self.len(), "case {index} of {}", self.len());
        assert_eq!(out.len(), self.names.len(), "one value per column");
        let mut rest = index;
        let mut end = out.len();
        for factor in self.factors.iter().rev() {
            let n = factor.len();
            let start = end - factor.width();
            factor.write(rest % n, &mut out[start..end]);
            rest /= n;
            end = start;
        }
    }

    /// The table's fingerprint: its names and a line per factor.
    pub(super) fn describe(&self) -> String {
        let mut out = format!("cases {} {:?}\n", self.len(), self.names);
        for f in &self.factors {
            f.describe(&mut out);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;

    #[test]
    fn grid_cases_run_like_nested_loops_with_the_last_factor_fastest() {
        let cases = Cases::new()
            .grid("a", &[1.0, 2.0])
            .unwrap()
            .rows(&["b", "c"], &[10.0, 11.0, 20.0, 21.0, 30.0, 31.0])
            .unwrap();
        assert_eq!(cases.len(), 6);
        let mut all = vec![];
        for i in 0..6 {
            let mut row = [0.0; 3];
            cases.case(i, &mut row);
            all.push(row);
        }
        assert_eq!(
            all,
            [
                [1.0, 10.0, 11.0],
                [1.0, 20.0, 21.0],
                [1.0, 30.0, 31.0],
                [2.0, 10.0, 11.0],
                [2.0, 20.0, 21.0],
                [2.0, 30.0, 31.0]
            ]
        );
    }

    #[test]
    fn random_draws_depend_on_seed_and_draw_only() {
        let d = [
            ("u", Distribution::uniform(2.0, 3.0)),
            ("n", Distribution::normal(0.0, 1.0)),
        ];
        let alone = Cases::new().random(1000, 42, &d).unwrap();
        let gridded = Cases::new()
            .grid("g", &[0.0, 1.0])
            .unwrap()
            .random(1000, 42, &d)
            .unwrap();
        let (mut sum, mut sq) = (0.0, 0.0);
        for k in 0..1000 {
            let (mut a, mut b) = ([0.0; 2], [0.0; 3]);
            alone.case(k, &mut a);
            gridded.case(1000 + k, &mut b);
            assert_eq!(a, [b[1], b[2]]);
            assert!((2.0..3.0).contains(&a[0]));
            sum += a[1];
            sq += a[1] * a[1];
        }
        // A standard normal sample of 1000: mean within 4 standard errors.
        assert!(
            (sum / 1000.0).abs() < 4.0 / 1000f64.sqrt(),
            "mean {}",
            sum / 1000.0
        );
        assert!((sq / 1000.0 - 1.0).abs() < 0.2, "variance {}", sq / 1000.0);
        let other = Cases::new().random(1000, 43, &d).unwrap();
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        alone.case(0, &mut a);
        other.case(0, &mut b);
        assert_ne!(a, b);
    }

    #[test]
    fn bad_tables_are_refused_with_the_column_named() {
        let twice = Cases::new().grid("a", &[1.0]).unwrap().grid("a", &[2.0]);
        assert!(
            twice
                .unwrap_err()
                .to_string()
                .contains("`a` is given twice")
        );
        assert!(Cases::new().grid("a", &[]).is_err());
        assert!(Cases::new().grid("a", &[f64::NAN]).is_err());
        assert!(Cases::new().rows(&["a", "b"], &[1.0, 2.0, 3.0]).is_err());
        let bad = Distribution::uniform(1.0, 1.0);
        assert!(Cases::new().random(3, 0, &[("a", bad)]).is_err());
    }
}

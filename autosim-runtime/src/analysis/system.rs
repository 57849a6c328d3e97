//! The linear model with its names: [`LinearSystem`], from a model's
//! symbolic linearization or from matrices, and its eigenvalues.

use super::{Complex, DMatrix};
use crate::{Float, Linearize, ModelError};
use std::format;
use std::string::{String, ToString};
use std::vec;
use std::vec::Vec;

/// A name with its unit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Named {
    /// Name.
    pub name: String,
    /// Unit (may be empty).
    pub unit: String,
}

impl Named {
    fn list(names: &[&str], units: &[&str]) -> Vec<Named> {
        names
            .iter()
            .enumerate()
            .map(|(k, n)| Named {
                name: (*n).to_string(),
                unit: units.get(k).copied().unwrap_or("").to_string(),
            })
            .collect()
    }
}

/// A linear model `dx/dt = A x + B w`, `y = C x + D w` with the names and
/// units of its states, inputs and outputs.
#[derive(Clone, Debug, PartialEq)]
pub struct LinearSystem {
    /// `∂(dx/dt)/∂x`.
    pub a: DMatrix<f64>,
    /// `∂(dx/dt)/∂w`.
    pub b: DMatrix<f64>,
    /// `∂y/∂x`.
    pub c: DMatrix<f64>,
    /// `∂y/∂w`.
    pub d: DMatrix<f64>,
    /// The states.
    pub states: Vec<Named>,
    /// The inputs.
    pub inputs: Vec<Named>,
    /// The outputs.
    pub outputs: Vec<Named>,
}

impl LinearSystem {
    /// The linear model of `model` about `(t, x)` with its current inputs,
    /// in its linear states ([`Linearize::LINEAR_STATES`]).
    ///
    /// # Errors
    /// The model's error at this state.
    pub fn of<M: Linearize>(model: &mut M, t: M::Float, x: &M::State) -> Result<Self, ModelError> {
        let states = M::LINEAR_STATES;
        let (nx, nu, ny) = (states.len(), M::INPUT_NAMES.len(), M::OUTPUT_NAMES.len());
        let zero = M::Float::ZERO;
        let (mut a, mut b, mut c, mut d) = (
            vec![zero; nx * nx],
            vec![zero; nx * nu],
            vec![zero; ny * nx],
            vec![zero; ny * nu],
        );
        model.linearize_into(t, x, &mut a, &mut b, &mut c, &mut d)?;
        let matrix = |rows, cols, v: &[M::Float]| {
            DMatrix::from_row_iterator(rows, cols, v.iter().map(|x| x.to_f64()))
        };
        let state_names: Vec<&str> = states.iter().map(|k| M::STATE_NAMES[*k]).collect();
        let state_units: Vec<&str> = states
            .iter()
            .map(|k| M::STATE_UNITS.get(*k).copied().unwrap_or(""))
            .collect();
        Ok(LinearSystem {
            a: matrix(nx, nx, &a),
            b: matrix(nx, nu, &b),
            c: matrix(ny, nx, &c),
            d: matrix(ny, nu, &d),
            states: Named::list(&state_names, &state_units),
            inputs: Named::list(M::INPUT_NAMES, M::INPUT_UNITS),
            outputs: Named::list(M::OUTPUT_NAMES, M::OUTPUT_UNITS),
        })
    }

    /// A system with only `A` (no inputs or outputs), states named `names`.
    pub fn from_matrices(a: DMatrix<f64>, names: &[&str]) -> Self {
        let n = a.nrows();
        LinearSystem {
            a,
            b: DMatrix::zeros(n, 0),
            c: DMatrix::zeros(0, n),
            d: DMatrix::zeros(0, 0),
            states: Named::list(names, &[]),
            inputs: Vec::new(),
            outputs: Vec::new(),
        }
    }

    /// The system restricted to some of its states (by name, in the order
    /// given): rows and columns of `A`, rows of `B`, columns of `C`. Use it
    /// to drop ignorable coordinates (position, heading, wheel angles) whose
    /// zero eigenvalues say nothing.
    ///
    /// # Errors
    /// The first name that is not a state.
    pub fn restricted(&self, names: &[&str]) -> Result<LinearSystem, String> {
        let mut index = Vec::with_capacity(names.len());
        for n in names {
            match self.states.iter().position(|s| s.name == *n) {
                Some(k) => index.push(k),
                None => return Err(format!("`{n}` is not a state of the linear model")),
            }
        }
        Ok(LinearSystem {
            a: self.a.select_rows(&index).select_columns(&index),
            b: self.b.select_rows(&index),
            c: self.c.select_columns(&index),
            d: self.d.clone(),
            states: index.iter().map(|k| self.states[*k].clone()).collect(),
            inputs: self.inputs.clone(),
            outputs: self.outputs.clone(),
        })
    }

    /// The eigenvalues of `A`, sorted by real part, then imaginary part:
    /// faer's Hessenberg QR iteration (LAPACK's algorithm: multishift
    /// with aggressive early deflation and exceptional shifts).
    /// nalgebra's Schur iteration, used before, loops forever on some
    /// matrices, a sleeping top's among them (dimforge/nalgebra issues
    /// 611, 764, 1528).
    ///
    /// Should faer's iteration not converge (LAPACK's algorithm is not
    /// known to fail on a finite matrix), nalgebra's is tried with a
    /// bounded number of iterations; should that fail too, or `A` have an
    /// entry that is not finite, every eigenvalue is NaN.
    pub fn eigenvalues(&self) -> Vec<Complex<f64>> {
        let n = self.a.nrows();
        let unknown = || vec![Complex::new(f64::NAN, f64::NAN); n];
        if self.a.iter().any(|v| !v.is_finite()) {
            return unknown();
        }
        let a = faer::Mat::from_fn(n, n, |i, j| self.a[(i, j)]);
        let mut ev = a.eigenvalues().unwrap_or_else(|_| {
            let schur = self.a.clone().try_schur(f64::EPSILON, 100 * n.max(1));
            schur.map_or_else(unknown, |s| {
                s.complex_eigenvalues().iter().copied().collect()
            })
        });
        ev.sort_by(|x, y| x.re.total_cmp(&y.re).then(x.im.total_cmp(&y.im)));
        ev
    }
}

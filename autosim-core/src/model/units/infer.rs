//! Dimensions with unknowns: a quantity declared without a unit (a
//! parameter, input, added state or subroutine output) gets a variable,
//! and every use adds a linear equation over the exponents (a product adds
//! exponents, a power multiplies them, a sum equates them). [`Solver`]
//! eliminates the variables as the equations arrive, so the first equation
//! that cannot hold is the one reported, where it was written.

use super::dim::{Dim, Ratio};
use std::fmt;

/// An unknown dimension: the index of a quantity declared without a unit.
pub type Var = usize;

/// A dimension as a known part times powers of unknowns:
/// `dim * Π var^exponent`.
#[derive(Clone, Debug, PartialEq)]
pub struct Affine {
    /// The known part.
    pub dim: Dim,
    /// The unknowns with their (non-zero) exponents, sorted by variable.
    pub vars: Vec<(Var, Ratio)>,
}

impl Affine {
    /// A known dimension.
    pub fn known(dim: Dim) -> Affine {
        Affine {
            dim,
            vars: Vec::new(),
        }
    }

    /// The unknown `v`.
    pub fn var(v: Var) -> Affine {
        Affine {
            dim: Dim::ONE,
            vars: vec![(v, Ratio::ONE)],
        }
    }

    /// `self * other`.
    pub fn times(&self, other: &Affine) -> Option<Affine> {
        let mut vars = self.vars.clone();
        for &(v, e) in &other.vars {
            match vars.binary_search_by_key(&v, |&(w, _)| w) {
                Ok(k) => vars[k].1 = vars[k].1.plus(e)?,
                Err(k) => vars.insert(k, (v, e)),
            }
        }
        vars.retain(|(_, e)| !e.is_zero());
        Some(Affine {
            dim: self.dim.times(other.dim)?,
            vars,
        })
    }

    /// `self^p`.
    pub fn pow(&self, p: Ratio) -> Option<Affine> {
        if p.is_zero() {
            return Some(Affine::known(Dim::ONE));
        }
        let mut vars = Vec::with_capacity(self.vars.len());
        for &(v, e) in &self.vars {
            vars.push((v, e.times(p)?));
        }
        Some(Affine {
            dim: self.dim.pow(p)?,
            vars,
        })
    }

    /// `self / other`.
    pub fn over(&self, other: &Affine) -> Option<Affine> {
        self.times(&other.pow(Ratio::int(-1))?)
    }
}

/// A mismatch: the two sides, with what is known substituted.
#[derive(Clone, Debug)]
pub struct Mismatch {
    /// The left side (or the value found).
    pub left: Affine,
    /// The right side (or the dimension needed).
    pub right: Affine,
}

/// The unknowns and what is known of them.
#[derive(Clone, Debug, Default)]
pub struct Solver {
    /// Each unknown's name (for messages) and its solution, once found.
    vars: Vec<(String, Option<Affine>)>,
}

impl Solver {
    /// A new unknown, the dimension of `name`.
    pub fn fresh(&mut self, name: &str) -> Var {
        self.vars.push((name.to_string(), None));
        self.vars.len() - 1
    }

    /// The name of unknown `v`.
    pub fn name(&self, v: Var) -> &str {
        &self.vars[v].0
    }

    /// `a` with every solved unknown replaced by its solution.
    pub fn resolve(&self, a: &Affine) -> Option<Affine> {
        let mut out = Affine::known(a.dim);
        for &(v, e) in &a.vars {
            let part = match &self.vars[v].1 {
                Some(solution) => self.resolve(solution)?.pow(e)?,
                None => Affine {
                    dim: Dim::ONE,
                    vars: vec![(v, e)],
                },
            };
            out = out.times(&part)?;
        }
        Some(out)
    }

    /// The dimension of `a` if no unknown remains in it.
    pub fn known(&self, a: &Affine) -> Option<Dim> {
        let r = self.resolve(a)?;
        r.vars.is_empty().then_some(r.dim)
    }

    /// Requires `a` and `b` to be the same dimension (the radian aside):
    /// solves an unknown when one remains, else compares.
    pub fn unify(&mut self, a: &Affine, b: &Affine) -> Result<(), Box<Mismatch>> {
        let (Some(ra), Some(rb)) = (self.resolve(a), self.resolve(b)) else {
            return Ok(()); // exponents out of range: not tracked
        };
        let Some(d) = ra.over(&rb) else {
            return Ok(());
        };
        // Solve for the newest unknown: `v^e * rest = 1`.
        let Some(&(v, e)) = d.vars.last() else {
            return match d.dim.is_dimensionless() {
                true => Ok(()),
                false => Err(Box::new(Mismatch {
                    left: ra,
                    right: rb,
                })),
            };
        };
        let rest = Affine {
            dim: d.dim,
            vars: d.vars[..d.vars.len() - 1].to_vec(),
        };
        let solution = e.recip().and_then(|r| rest.pow(r.negated()));
        if let Some(s) = solution {
            self.vars[v].1 = Some(s);
        }
        Ok(())
    }
}

/// Prints `a` with each unknown as `unit(name)`.
pub struct Shown<'a>(pub &'a Affine, pub &'a Solver);

impl fmt::Display for Shown<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Shown(a, solver) = self;
        let mut parts = Vec::new();
        if !a.dim.is_one() || a.vars.is_empty() {
            parts.push(a.dim.to_string());
        }
        for &(v, e) in &a.vars {
            let name = solver.name(v);
            parts.push(match e == Ratio::ONE {
                true => format!("the unit of `{name}`"),
                false => format!("(the unit of `{name}`)^{e}"),
            });
        }
        f.write_str(&parts.join(" times "))
    }
}

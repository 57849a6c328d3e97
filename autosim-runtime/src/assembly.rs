//! Assembly of constrained models: Newton's method on the position
//! constraints `g(q, t) = 0` for the dependent coordinates, the others
//! held. Generated models with position constraints call it from
//! [`Model::assemble`](crate::Model::assemble) (from any guess) and
//! [`Model::project`](crate::Model::project) (after an integration step,
//! where the correction is small and a large one means the mechanism
//! jumped to another branch of its closure).
//!
//! Why projection: the generated derivatives integrate every coordinate,
//! the dependent ones included, with the dependent speeds solved exactly
//! from the constraints, so the constraints hold at the speed level at
//! every state and the positions drift only by the integrator's error.
//! Projecting after each accepted step costs one Newton step (one
//! evaluation of the residuals and their Jacobian) when the drift is below
//! the tolerance, and keeps the residual at rounding level without
//! changing the independent coordinates the integrator controls.

use crate::{Float, ModelError, StateArray};

/// Newton iterations before assembly gives up.
pub const MAX_ITERATIONS: usize = 50;

/// How far a projection may move a dependent coordinate, relative to
/// `1 + |q|`, before it is taken as a lost branch rather than drift.
pub const BRANCH_LIMIT: f64 = 0.1;

/// Solves the position constraints for the dependent coordinates by
/// Newton's method, changing only `x[dependent[i]]`.
///
/// `step(x, s)` writes one Newton step at `x`: `s[..k]` the corrections of
/// the `k` dependent coordinates, `s[k..]` the residuals of the position
/// constraints (`M = 2k`). A state whose first correction is within
/// `tolerance · (1 + |q|)` is left as it is; otherwise Newton's method runs
/// to rounding level. With `branch_limit`, a coordinate that moves more
/// than `branch_limit · (1 + |q|)` from where it started is a lost branch.
/// Returns whether `x` changed.
///
/// # Errors
/// [`ModelError::NotAssembled`] naming the constraint with the largest
/// residual when Newton's method does not converge in
/// [`MAX_ITERATIONS`] (or the residuals are not finite);
/// [`ModelError::LostBranch`] naming the coordinate that jumped; any error
/// of `step` (a singular Jacobian). `x` is unchanged on error.
pub fn solve_positions<F, S, const M: usize>(
    x: &mut S,
    dependent: &[usize],
    constraint_names: &[&'static str],
    coordinate_names: &[&'static str],
    tolerance: F,
    branch_limit: Option<f64>,
    mut step: impl FnMut(&S, &mut [F; M]) -> Result<(), ModelError>,
) -> Result<bool, ModelError>
where
    F: Float,
    S: StateArray<F>,
{
    let k = M / 2;
    let start = *x;
    let mut trial = *x;
    let mut previous = F::from_f64(f64::INFINITY);
    for iteration in 0..MAX_ITERATIONS {
        let mut s = [F::ZERO; M];
        step(&trial, &mut s)?;
        let (correction, scale) = sizes(&trial, dependent, &s[..k]);
        let worst = largest(&s[k..]);
        if !s.iter().all(|v| v.is_finite()) {
            return Err(not_assembled(constraint_names, worst));
        }
        let converged = correction <= F::from_f64(64.0) * F::EPSILON * scale;
        let stalled = iteration > 0
            && correction >= F::from_f64(0.5) * previous
            && correction <= F::EPSILON.sqrt() * scale;
        let within = iteration == 0 && correction <= tolerance * scale;
        if converged || stalled || within {
            if iteration == 0 {
                return Ok(false);
            }
            *x = trial;
            return Ok(true);
        }
        for (i, &slot) in dependent.iter().enumerate() {
            let q = &mut trial.as_mut()[slot];
            *q += s[i];
            let q0 = start.as_ref()[slot];
            let limit = branch_limit.map(|l| F::from_f64(l) * (F::ONE + q0.abs()));
            if limit.is_some_and(|l| (*q - q0).abs() > l) {
                let name = coordinate_names.get(slot).copied().unwrap_or("?");
                return Err(ModelError::LostBranch { coordinate: name });
            }
        }
        previous = correction;
    }
    let mut s = [F::ZERO; M];
    step(&trial, &mut s)?;
    Err(not_assembled(constraint_names, largest(&s[k..])))
}

/// The largest correction and the size of the coordinates it corrects
/// (`1 + max |q|`).
fn sizes<F: Float, S: StateArray<F>>(x: &S, dependent: &[usize], s: &[F]) -> (F, F) {
    let mut correction = F::ZERO;
    let mut scale = F::ONE;
    for (i, &slot) in dependent.iter().enumerate() {
        let c = s[i].abs();
        // A non-finite correction counts as the largest.
        if !c.is_finite() || c > correction {
            correction = c;
        }
        scale = scale.max(F::ONE + x.as_ref()[slot].abs());
    }
    (correction, scale)
}

/// Index of the entry of largest magnitude (the first non-finite one if
/// any).
fn largest<F: Float>(values: &[F]) -> usize {
    let mut best = 0;
    for (i, v) in values.iter().enumerate() {
        if !v.is_finite() {
            return i;
        }
        if v.abs() > values[best].abs() {
            best = i;
        }
    }
    best
}

fn not_assembled(names: &[&'static str], worst: usize) -> ModelError {
    ModelError::NotAssembled {
        name: names.get(worst).copied().unwrap_or("?"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit circle `x² + y² = 1` solved for `y`.
    fn circle(x: &[f64; 2], s: &mut [f64; 2]) -> Result<(), ModelError> {
        let g = x[0] * x[0] + x[1] * x[1] - 1.0;
        s[0] = -g / (2.0 * x[1]);
        s[1] = g;
        Ok(())
    }

    #[test]
    fn newton_closes_a_circle_from_a_guess() {
        let mut x = [0.6, 0.5];
        let changed = solve_positions(&mut x, &[1], &["circle"], &["x", "y"], 0.0, None, circle);
        assert_eq!(changed, Ok(true));
        assert!((x[1] - 0.8).abs() < 1e-15, "{x:?}");
        assert_eq!(x[0], 0.6);
        let again = solve_positions(&mut x, &[1], &["circle"], &["x", "y"], 0.0, None, circle);
        assert_eq!(again, Ok(false));
    }

    #[test]
    fn drift_within_the_tolerance_is_left_alone() {
        let mut x = [0.6, 0.8 + 1e-9];
        let r = solve_positions(&mut x, &[1], &["circle"], &["x", "y"], 1e-8, None, circle);
        assert_eq!((r, x), (Ok(false), [0.6, 0.8 + 1e-9]));
        let r = solve_positions(&mut x, &[1], &["circle"], &["x", "y"], 1e-10, None, circle);
        assert_eq!(r, Ok(true));
        assert!((x[1] - 0.8).abs() < 1e-15);
    }

    #[test]
    fn a_jump_to_the_other_branch_is_reported() {
        // From y = -0.05 Newton lands on y = -0.8, far from the start.
        let mut x = [0.6, -0.05];
        let r = solve_positions(
            &mut x,
            &[1],
            &["circle"],
            &["x", "y"],
            0.0,
            Some(0.1),
            circle,
        );
        assert_eq!(r, Err(ModelError::LostBranch { coordinate: "y" }));
        assert_eq!(x, [0.6, -0.05]);
    }

    #[test]
    fn no_solution_is_not_assembled() {
        // x = 2 leaves no real y.
        let mut x = [2.0, 0.5];
        let r = solve_positions(&mut x, &[1], &["circle"], &["x", "y"], 0.0, None, circle);
        assert_eq!(r, Err(ModelError::NotAssembled { name: "circle" }));
        assert_eq!(x, [2.0, 0.5]);
    }
}

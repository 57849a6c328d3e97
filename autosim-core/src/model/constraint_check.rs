//! Whether a load read from a constraint's expression
//! ([`super::constraint_load::read`]) is the load the constraint carries:
//! its generalized force per unit multiplier, `Σ f·∂v_P/∂u_k` over its
//! forces `f` at points `P` (`v_P` the velocity of the material point of
//! `P`'s body at `P`: a force acts on the body) plus `Σ m·∂ω_B/∂u_k` over
//! its moments on bodies `B`, must be the constraint's row `A_k` (the
//! coefficient of speed `k` in the constraint at the speed level) for
//! every speed. Then the load does what `Aᵀ λ` does in Kane's equations.
//!
//! The two sides are compared symbolically, and where the simplifier
//! leaves a difference (trigonometric identities, square roots), at
//! sampled states: coordinates around the initial ones, speeds and time
//! spread over `[-1, 1]`, parameters and inputs at their defaults. A
//! point that moves in its body counts only by its material velocity, so
//! a constraint written with the position of a point sliding in its body
//! holds only where the sliding does no work (a contact point, the lowest
//! point of a wheel, qualifies: the rim's motion there is along the
//! ground).

use super::scope::Resolver;
use crate::expr::{Bindings, ExprId, NoUserFunctions};
use crate::mech::{Constraint, ConstraintKind, ConstraintLoad, Vector};

/// States sampled when the symbolic difference does not vanish.
const SAMPLES: usize = 8;
/// How many of them must evaluate to finite numbers.
const USABLE: usize = 4;
/// Agreement needed, relative to the row's largest entry.
const TOLERANCE: f64 = 1e-8;

/// Whether `load` is what `c` carries (see the module's description).
pub(super) fn holds(r: &mut Resolver<'_>, c: &Constraint, load: &ConstraintLoad) -> bool {
    let Some((row, from_load)) = rows(r, c, load) else {
        return false;
    };
    let sys = &mut r.sys;
    let same = row.iter().zip(&from_load).all(|(&a, &b)| {
        let d = sys.arena.sub(a, b);
        sys.arena.is_zero(d)
    });
    same || agree_at_samples(r, &row, &from_load)
}

/// The constraint's row `A_k` and the load's generalized forces, per speed.
fn rows(
    r: &mut Resolver<'_>,
    c: &Constraint,
    load: &ConstraintLoad,
) -> Option<(Vec<ExprId>, Vec<ExprId>)> {
    let sys = &mut r.sys;
    let rate = match c.kind {
        ConstraintKind::Position => sys.arena.dxdt(c.value).ok()?,
        ConstraintKind::Speed => c.value,
    };
    let mut velocities: Vec<(Vector, Vector)> = Vec::new();
    for (p, f) in &load.forces {
        velocities.push((f.clone(), sys.material_velocity(*p)));
    }
    for (b, m) in &load.moments {
        velocities.push((m.clone(), sys.rot(*b)));
    }
    let mut row = Vec::with_capacity(sys.coordinates.len());
    let mut from_load = Vec::with_capacity(sys.coordinates.len());
    for k in 0..sys.coordinates.len() {
        let u = sys.coordinates[k].u;
        row.push(sys.arena.partial(rate, u).ok()?);
        let mut terms = Vec::with_capacity(velocities.len());
        for (f, v) in &velocities {
            let dv = sys.partial_vector(v, u).ok()?;
            terms.push(sys.frames.dot_vec(&mut sys.arena, f, &dv));
        }
        from_load.push(sys.arena.sum(&terms));
    }
    Some((row, from_load))
}

/// Whether `a` and `b` agree at [`USABLE`] or more of [`SAMPLES`] states
/// where both evaluate to finite numbers, and differ at none.
fn agree_at_samples(r: &Resolver<'_>, a: &[ExprId], b: &[ExprId]) -> bool {
    let sys = &r.sys;
    let roots: Vec<ExprId> = a.iter().chain(b).copied().collect();
    let mut random = Xorshift(0x9e37_79b9_7f4a_7c15);
    let mut usable = 0;
    for _ in 0..SAMPLES {
        let mut at = Bindings::with_defaults(&sys.arena);
        at.set(sys.time(), random.next());
        for c in &sys.coordinates {
            let q0 = sys.arena.eval(c.initial_q, &at, &mut NoUserFunctions);
            let q0 = if q0.is_finite() { q0 } else { 0.0 };
            at.set(c.q, q0 + 0.5 * random.next());
            at.set(c.u, random.next());
        }
        let values = sys.arena.eval_many(&roots, &at, &mut NoUserFunctions);
        if values.iter().any(|v| !v.is_finite()) {
            continue;
        }
        let (va, vb) = values.split_at(a.len());
        let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if va
            .iter()
            .zip(vb)
            .any(|(x, y)| (x - y).abs() > TOLERANCE * scale)
        {
            return false;
        }
        usable += 1;
    }
    usable >= USABLE
}

/// A fixed sequence of numbers in `[-1, 1]` (Marsaglia's xorshift: the
/// samples need spread, not statistical quality, and the same states on
/// every build keep the compiler deterministic).
struct Xorshift(u64);

impl Xorshift {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

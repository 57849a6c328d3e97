//! The dimensions of the operations of the paper's Tables 6 and 12:
//! positions are in m, velocities in m/s, angular velocities in rad/s,
//! products multiply, `dir` is dimensionless, `angle` is in rad; and of
//! the model's quantities: reactions in N and N m, energies in J, momenta
//! in kg m/s and kg m²/s, power in W, a constraint's force in W per the
//! unit of its speed-level expression.

use super::check::{Checker, Measure, unit_dim};
use super::dim::{Dim, Ratio};
use super::infer::Affine;
use crate::model::scope::Named;
use crate::syntax::ast::Expr;

/// The dimension of `name(args)` for an operation (not a function).
pub(super) fn operation(c: &mut Checker<'_, '_>, name: &str, args: &[Expr]) -> Measure {
    let each =
        |c: &mut Checker<'_, '_>| -> Vec<Measure> { args.iter().map(|a| c.expr(a)).collect() };
    match name {
        "pos" => fixed(c, args, "m"),
        "vel" => fixed(c, args, "m/s"),
        "rot" => fixed(c, args, "rad/s"),
        "angle" => fixed(c, args, "rad"),
        "reaction_force" => fixed(c, args, "N"),
        "reaction_moment" => fixed(c, args, "N m"),
        "kinetic_energy" | "potential_energy" => fixed(c, args, "J"),
        "momentum" => fixed(c, args, "kg m/s"),
        "angular_momentum" => fixed(c, args, "kg m^2/s"),
        // Its argument names a load: not a value with a unit.
        "power" => Measure::known(unit_dim("W")),
        "constraint_force" => constraint_force(c, args),
        "dir" => {
            each(c);
            Measure::known(Dim::ONE)
        }
        "sqrt" => match each(c).pop() {
            Some(q) => power(q, Ratio::new(1, 2)),
            None => Measure::Untracked,
        },
        "mag" | "nominal" | "constant_part" => each(c).pop().unwrap_or(Measure::Untracked),
        "dot" | "cross" | "dot_plane" => {
            let qs = each(c);
            match &qs[..] {
                [a, b] => times(a.clone(), b.clone(), Affine::times),
                _ => Measure::Untracked,
            }
        }
        "dxdt" => match each(c).pop() {
            Some(q) => times(q, Measure::known(unit_dim("s")), Affine::over),
            None => Measure::Untracked,
        },
        "partial" => {
            let qs = each(c);
            match &qs[..] {
                [y, x] => times(y.clone(), x.clone(), Affine::over),
                _ => Measure::Untracked,
            }
        }
        "q" | "u" => generalized(c, name, args),
        _ => Measure::Untracked,
    }
}

/// The multiplier of a constraint: its power `λ ċ` is in W, so it is in
/// W per the unit of the speed-level constraint (`J` per the unit of a
/// position constraint's `g`, `W` per the unit of a speed constraint's
/// `c`); unknown for a constraint declared without a unit.
fn constraint_force(c: &mut Checker<'_, '_>, args: &[Expr]) -> Measure {
    let Some(Expr::Name(n)) = args.first() else {
        return Measure::Untracked;
    };
    let Some(k) = c.r.sys.constraints.iter().find(|k| k.name == n.text) else {
        return Measure::Untracked;
    };
    let Some(unit) = k.unit.as_deref() else {
        return Measure::Untracked;
    };
    let work = match k.kind {
        crate::mech::ConstraintKind::Position => "J",
        crate::mech::ConstraintKind::Speed => "W",
    };
    unit_dim(work)
        .over(unit_dim(unit))
        .map_or(Measure::Untracked, Measure::known)
}

/// An operation whose value has one dimension whatever its arguments.
fn fixed(c: &mut Checker<'_, '_>, args: &[Expr], unit: &str) -> Measure {
    for a in args {
        c.expr(a);
    }
    Measure::known(unit_dim(unit))
}

fn power(q: Measure, p: Option<Ratio>) -> Measure {
    match (q, p) {
        (Measure::Dim(a), Some(p)) => a.pow(p).map_or(Measure::Untracked, Measure::Dim),
        (Measure::Free, _) => Measure::Free,
        _ => Measure::Untracked,
    }
}

/// `a * b` or `a / b` of two values (a number is a plain factor).
fn times(a: Measure, b: Measure, op: fn(&Affine, &Affine) -> Option<Affine>) -> Measure {
    let dim = |q: Measure| match q {
        Measure::Dim(a) => Some(a),
        Measure::Free => Some(Affine::known(Dim::ONE)),
        _ => None,
    };
    let free = matches!((&a, &b), (Measure::Free, Measure::Free));
    match (dim(a), dim(b)) {
        _ if free => Measure::Free,
        (Some(x), Some(y)) => op(&x, &y).map_or(Measure::Untracked, Measure::Dim),
        _ => Measure::Untracked,
    }
}

/// `q(B)`, `q(B, k)`, `u(B)`, `u(B, k)`: the unit of that coordinate or
/// speed (m or rad, m/s or rad/s).
fn generalized(c: &mut Checker<'_, '_>, name: &str, args: &[Expr]) -> Measure {
    let Some(Expr::Name(body)) = args.first() else {
        return Measure::Untracked;
    };
    let Some((Named::Body(Some(b)), _)) = c.r.names.get(&body.text) else {
        return Measure::Untracked;
    };
    let k = match args.get(1) {
        Some(Expr::Number(n)) => match n.text.parse::<usize>() {
            Ok(k) if k >= 1 => k - 1,
            _ => return Measure::Untracked,
        },
        Some(_) => return Measure::Untracked,
        None => 0,
    };
    let Some(&(q, u)) = c.r.sys.body(*b).dofs.get(k) else {
        return Measure::Untracked;
    };
    let arena = &c.r.sys.arena;
    match (arena.as_symbol(q), arena.as_symbol(u)) {
        (Some(q), _) if name == "q" => c.symbol(q),
        (_, Some(u)) => c.symbol(u),
        // The speed of a locked degree of freedom (0): its coordinate's
        // unit per second.
        (Some(q), None) => match c.symbol(q) {
            Measure::Dim(a) => a
                .over(&Affine::known(unit_dim("s")))
                .map_or(Measure::Untracked, Measure::Dim),
            other => other,
        },
        (None, None) => Measure::Untracked,
    }
}

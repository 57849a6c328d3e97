//! Where a position constraint's load acts, read from how its expression
//! is written: `dot(pos(P, Q), d)` or `dot(d, pos(P, Q))` (`pos(P)`: from
//! N's origin), plus or minus a term `c`, with `d` fixed in N and `c`
//! free of coordinates, is held by the force `λ d` on `P` and `−λ d` on
//! `Q`, `λ` its multiplier (their power, `λ d·(v_P − v_Q)`, is `λ ġ`).
//! Joint reactions need it; other forms leave it unknown.

use super::scope::Resolver;
use crate::mech::{ConstraintLoad, FrameId};
use crate::syntax::ast::{BinOp, Expr};

/// The points and direction of the position constraint `g` when it is
/// written `dot(pos(P, Q), d)`; whether `d` is fixed in N is asked only
/// when a reaction needs it ([`fixed_in_n`]: it builds expressions, which
/// models without reactions do not).
pub(super) fn where_load_acts(r: &mut Resolver<'_>, g: &Expr) -> Option<ConstraintLoad> {
    // `dot(...) ± c` and `c + dot(...)`: `c` must not depend on the
    // coordinates (checked with `d`).
    if let Expr::Binary { op, lhs, rhs, .. } = g {
        let (form, offset) = match op {
            BinOp::Add | BinOp::Sub if is_dot(lhs) => (lhs, rhs),
            BinOp::Add if is_dot(rhs) => (rhs, lhs),
            _ => return None,
        };
        let offset = r.scalar(offset, "a position constraint")?;
        let mut load = where_load_acts(r, form)?;
        load.offset = offset;
        return Some(load);
    }
    let Expr::Call { func, args, .. } = g else {
        return None;
    };
    if func.text != "dot" || args.len() != 2 {
        return None;
    }
    for (p, d) in [(&args[0], &args[1]), (&args[1], &args[0])] {
        let Expr::Call { func, args: at, .. } = p else {
            continue;
        };
        if func.text != "pos" || at.is_empty() || at.len() > 2 {
            continue;
        }
        // The expression resolved already: these names resolve again,
        // without diagnostics.
        let on = r.point(&at[0], "`pos`")?;
        let reaction = match at.get(1) {
            Some(q) => Some(r.point(q, "`pos`")?),
            None => None,
        };
        let direction = r.vector(d, "`dot`")?;
        let offset = r.sys.arena.zero();
        return Some(ConstraintLoad {
            on,
            reaction,
            direction,
            offset,
        });
    }
    None
}

fn is_dot(e: &Expr) -> bool {
    matches!(e, Expr::Call { func, args, .. } if func.text == "dot" && args.len() == 2)
}

/// Whether the load's direction `d` (its components in N) and its offset
/// depend on no coordinate: then `ġ` is `d·(v_P − v_Q)` plus terms without
/// speeds.
pub(super) fn fixed_in_n(r: &mut Resolver<'_>, load: &ConstraintLoad) -> bool {
    let mut components = r
        .sys
        .frames
        .express_in(&mut r.sys.arena, &load.direction, FrameId::N)
        .to_vec();
    components.push(load.offset);
    let coordinates: Vec<_> = r.sys.coordinates.iter().map(|c| c.q).collect();
    components.iter().all(|&c| {
        r.sys
            .arena
            .free_symbols(c)
            .iter()
            .all(|s| !coordinates.contains(s))
    })
}

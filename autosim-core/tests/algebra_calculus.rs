//! Property tests of the expression algebra's calculus and substitutions:
//! `partial` against central differences, `dxdt` against the chain rule,
//! `substitute` against the tree with the trees substituted, and `nominal`
//! against the value at zero coordinates. The trees and the direct
//! evaluation they are checked against are in `algebra/`.

mod algebra;

use algebra::direct::{close, direct};
use algebra::{EPS, K, NAMES, Q, T, X, build, config, ctx, eval, subst_tree, tree, value_strategy};
use autosim_core::expr::{Bindings, NoUserFunctions, SymbolKind};
use proptest::prelude::*;
use rustc_hash::FxHashMap;

// ----- numeric derivatives of the direct tree -----

/// Central differences along `dir` with one Richardson step; `None` where
/// two step sizes disagree (a kink, a branch cut, or ill-conditioning).
fn directional_derivative(t: &T, vals: &[f64], dir: &[f64]) -> Option<(f64, f64)> {
    let f = |h: f64| {
        let moved: Vec<f64> = vals.iter().zip(dir).map(|(v, d)| v + h * d).collect();
        direct(t, &moved, &[])
    };
    let scale_x = vals
        .iter()
        .zip(dir)
        .filter(|(_, d)| **d != 0.0)
        .fold(1.0f64, |a, (v, _)| a.max(v.abs()));
    let h = 1e-4 * scale_x;
    let c = |h: f64| (f(h).v - f(-h).v) / (2.0 * h);
    let (d1, d2) = (c(h), c(h / 2.0));
    let r = (4.0 * d2 - d1) / 3.0;
    let f0 = f(0.0);
    if !r.is_finite() || !f0.e.is_finite() {
        return None;
    }
    // The steps must stay well inside the region where f is smooth: near a
    // pole or a kink f changes by a large fraction of itself across them.
    let spread = [h, -h, h / 2.0, -h / 2.0]
        .iter()
        .map(|s| (f(*s).v - f0.v).abs())
        .fold(
            0.0f64,
            |a, x| if x.is_nan() { f64::INFINITY } else { a.max(x) },
        );
    if spread > 0.01 * f0.v.abs().max(1.0) {
        return None;
    }
    let scale = r.abs().max(1.0);
    let noise = 1e3 * EPS * f0.e / h;
    if (d1 - d2).abs() > 1e-3 * scale + noise {
        return None;
    }
    Some((r, 1e-6 * scale + noise))
}

proptest! {
    #![proptest_config(config())]

    /// nominal sets the coordinates to zero.
    #[test]
    fn nominal_is_value_at_zero_coordinates(t in tree(), vals in value_strategy()) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        let n = c.arena.nominal(e);
        prop_assert!(!c.arena.depends_on(n, c.syms[Q]));
        let mut at_zero = vals;
        at_zero[Q] = 0.0;
        close(eval(&c, n, &vals), direct(&t, &at_zero, &[]))?;
    }

    /// Substitution gives the value of the tree with the trees substituted.
    #[test]
    fn substitute_preserves_value(t in tree(), sx in tree(), sq in tree(), vals in value_strategy()) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        let (ex, eq) = (build(&mut c, &sx), build(&mut c, &sq));
        let mut map = FxHashMap::default();
        map.insert(c.syms[X], ex);
        map.insert(c.syms[Q], eq);
        let r = c.arena.substitute(e, &map);
        let mut tmap = FxHashMap::default();
        tmap.insert(X, sx);
        tmap.insert(Q, sq);
        let composite = subst_tree(&t, &tmap);
        close(eval(&c, r, &vals), direct(&composite, &vals, &[]))?;
    }

    /// partial agrees with central differences, for every symbol.
    #[test]
    fn partial_matches_finite_differences(t in tree(), vals in value_strategy()) {
        let mut c = ctx();
        let e = build(&mut c, &t);
        for i in 0..NAMES.len() {
            let d = c.arena.partial(e, c.syms[i]).unwrap();
            let mut dir = [0.0; 5];
            dir[i] = 1.0;
            if let Some((want, tol)) = directional_derivative(&t, &vals, &dir) {
                let got = eval(&c, d, &vals);
                prop_assert!((got - want).abs() <= tol,
                    "d/d{} of {}: {} = {got}, differences {want}", NAMES[i],
                    c.arena.to_text(e), c.arena.to_text(d));
            }
        }
    }

    /// dxdt is the chain rule: sum of partials times the declared rates.
    #[test]
    fn dxdt_matches_chain_rule(t in tree(), vals in value_strategy(), rates in value_strategy()) {
        let mut c = ctx();
        let mut rate_syms = Vec::new();
        for (i, n) in NAMES.iter().enumerate().take(K) {
            let r = c.arena.add_symbol(&format!("{n}_rate"), SymbolKind::Free).unwrap();
            let re = c.arena.sym(r);
            c.arena.set_dxdt(c.syms[i], re);
            rate_syms.push(r);
        }
        let e = build(&mut c, &t);
        let d = c.arena.dxdt(e).unwrap();
        // k is a parameter: its rate is zero.
        let mut dir = rates;
        dir[K] = 0.0;
        if let Some((want, tol)) = directional_derivative(&t, &vals, &dir) {
            let mut b = Bindings::with_defaults(&c.arena);
            for (s, v) in c.syms.iter().zip(vals) {
                b.set(*s, v);
            }
            for (i, r) in rate_syms.iter().enumerate() {
                b.set(*r, rates[i]);
            }
            let got = c.arena.eval(d, &b, &mut NoUserFunctions);
            prop_assert!((got - want).abs() <= tol,
                "dxdt of {}: {} = {got}, chain rule {want}", c.arena.to_text(e), c.arena.to_text(d));
        }
    }
}

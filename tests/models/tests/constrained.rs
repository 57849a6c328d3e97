//! Every constrained example model (both paths) against a second
//! evaluation of its equations outside the generated code: the symbolic
//! constraint rows, mass matrix and forcing evaluated at a state, the
//! dependent speeds and the reduced equations `Pᵀ M P u̇ = Pᵀ (f − M w)`
//! solved with nalgebra's LU. A differential test of the unrolled,
//! statically pivoted constraint solve and of the reduction.

mod common;
use autosim::runtime::Model;
use autosim_core::expr::{Bindings, ExprId, NoUserFunctions};
use autosim_core::pipeline::Compiled;
use autosim_models_check::{via_build, via_macro};
use autosim_test_support::*;
use common::compile;
use nalgebra::{DMatrix, DVector};

/// dq/dt of the state's coordinates and du/dt of the independent speeds,
/// by nalgebra (no motions in these models: every coordinate is a state).
fn reference(c: &Compiled, params: &[f64], x: &[f64]) -> Option<Vec<f64>> {
    let sys = &c.model.system;
    let eqs = &c.equations;
    let cons = &eqs.constraints;
    let (n, m) = (eqs.coordinates.len(), cons.rows.len());
    let free: Vec<usize> = (0..n)
        .filter(|k| !cons.dependent_speeds.contains(k))
        .collect();
    let mut b = Bindings::with_defaults(&sys.arena);
    for (s, v) in sys.parameters().iter().zip(params) {
        b.set(*s, *v);
    }
    b.set(sys.time(), 0.0);
    for (k, q) in eqs.coordinates.iter().enumerate() {
        b.set(*q, x[k]);
    }
    for (i, &k) in free.iter().enumerate() {
        b.set(eqs.speeds[k], x[n + i]);
    }
    let eval = |b: &Bindings, es: &[ExprId]| sys.arena.eval_many(es, b, &mut NoUserFunctions);
    // A u + offset = 0 for the dependent speeds.
    let coefficients: Vec<ExprId> = cons
        .rows
        .iter()
        .flat_map(|r| r.coefficients.clone())
        .collect();
    let a = DMatrix::from_row_slice(m, n, &eval(&b, &coefficients));
    let offsets: Vec<ExprId> = cons.rows.iter().map(|r| r.offset).collect();
    let mut rhs = -DVector::from_vec(eval(&b, &offsets));
    for (i, &k) in free.iter().enumerate() {
        rhs -= a.column(k) * x[n + i];
    }
    let a_d = a.select_columns(&cons.dependent_speeds);
    let lu = a_d.clone().lu();
    let u_d = lu.solve(&rhs)?;
    for (r, &k) in cons.dependent_speeds.iter().enumerate() {
        b.set(eqs.speeds[k], u_d[r]);
    }
    let (mut out, mass, forcing) = api::evaluated(sys, eqs, &b);
    let biases: Vec<ExprId> = cons.rows.iter().map(|r| r.bias).collect();
    let bias = DVector::from_vec(eval(&b, &biases));
    // u = P u_f, u̇ = P u̇_f + w.
    let mut p = DMatrix::zeros(n, free.len());
    for (i, &k) in free.iter().enumerate() {
        p[(k, i)] = 1.0;
        let dep = lu.solve(&(-a.column(k)))?;
        for (r, &d) in cons.dependent_speeds.iter().enumerate() {
            p[(d, i)] = dep[r];
        }
    }
    let mut w = DVector::zeros(n);
    let w_d = lu.solve(&(-bias))?;
    for (r, &d) in cons.dependent_speeds.iter().enumerate() {
        w[d] = w_d[r];
    }
    let reduced = p.transpose() * &mass * &p;
    let du = reduced
        .lu()
        .solve(&(p.transpose() * (forcing - &mass * w)))?;
    out.extend(du.iter());
    Some(out)
}

macro_rules! differential {
    ($test:ident, $file:literal, $($path:ident)::+) => {
        #[test]
        fn $test() {
            type M = $($path)::+;
            let c = compile($file);
            let mut rng = Rng::new(0x2545_f491_4f6c_dd1d);
            let mut model = M::new();
            let mut params = vec![0.0; <M as Model>::PARAMETER_NAMES.len()];
            model.parameter_values(&mut params);
            let n = c.equations.coordinates.len();
            let (mut worst, mut compared) = (0.0f64, 0);
            for _ in 0..40 {
                let mut x = [0.0; <M as Model>::STATE_NAMES.len()];
                for (i, v) in x.iter_mut().enumerate() {
                    *v = if i < n { rng.uniform(-1.5, 1.5) } else { rng.uniform(-2.0, 2.0) };
                }
                let mut dx = x;
                if model.derivatives(0.0, &x, &mut dx).is_err() {
                    continue;
                }
                let Some(want) = reference(&c, &params, &x) else { continue };
                let e = rel_err(&dx, &want);
                worst = worst_of(worst, e);
                compared += 1;
                assert!(e < 1e-9, "{}: generated vs nalgebra {e:e}", $file);
            }
            eprintln!("{}: {compared} states, worst relative difference {worst:.2e}", $file);
            assert!(compared >= 20, "{}: only {compared} regular states", $file);
        }
    };
}

differential!(four_bar_macro, "four_bar.sim", via_macro::four_bar::FourBar);
differential!(four_bar_build, "four_bar.sim", via_build::four_bar::FourBar);
differential!(
    rolling_disc_macro,
    "rolling_disc.sim",
    via_macro::rolling_disc::RollingDisc
);
differential!(
    rolling_disc_build,
    "rolling_disc.sim",
    via_build::rolling_disc::RollingDisc
);
differential!(andrews_macro, "andrews.sim", via_macro::andrews::Andrews);
differential!(andrews_build, "andrews.sim", via_build::andrews::Andrews);
differential!(bicycle_macro, "bicycle.sim", via_macro::bicycle::Bicycle);
differential!(bicycle_build, "bicycle.sim", via_build::bicycle::Bicycle);

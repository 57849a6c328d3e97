//! Euler parameters: a body oriented by a quaternion has the same cosine
//! matrix as the 1-2-3 angles it converts from, and the satellite with a
//! quaternion bus reproduces the reference data after converting states.

use autosim_core::expr::Bindings;
use autosim_core::mech::BodyId;
use autosim_test_support::api::*;
use autosim_test_support::quaternion::{from_123, rates_123};
use autosim_test_support::*;

#[test]
fn satellite_with_quaternion_bus_matches_reference() {
    let data = load("satellite");
    let params = &data["parameters"];
    let mut euler = satellite(params, false);
    let mut quat = satellite_with(params, false, true);
    let eqs = quat.equations().unwrap();
    let _ = euler.equations().unwrap();
    // 10 speeds, 10 paired coordinates (q1..q3, e1..e3, q7..q10) and e0.
    assert_eq!(eqs.speeds.len(), 10);
    assert_eq!(eqs.states.len(), 1);
    let b = quat.body_named("B").unwrap();
    let cq = quat.cosine_matrix(b, BodyId::N);
    let be = euler.body_named("B").unwrap();
    let ce = euler.cosine_matrix(be, BodyId::N);
    let mut worst: f64 = 0.0;
    for s in data["samples"].as_array().unwrap() {
        let q = floats(&s["q"]);
        let u = floats(&s["u"]);
        let e = from_123(q[3], q[4], q[5]);
        // Same orientation.
        let mut bq = Bindings::with_defaults(&quat.arena);
        let mut be_ = Bindings::with_defaults(&euler.arena);
        for (name, v) in [("e0", e[0]), ("e1", e[1]), ("e2", e[2]), ("e3", e[3])] {
            bq.set(quat.arena.symbol_named(name).unwrap(), v);
        }
        for k in 4..7 {
            be_.set(
                euler.arena.symbol_named(&format!("q{k}")).unwrap(),
                q[k - 1],
            );
        }
        for i in 0..3 {
            for j in 0..3 {
                let a = quat
                    .arena
                    .eval(cq[i][j], &bq, &mut autosim_core::expr::NoUserFunctions);
                let b = euler
                    .arena
                    .eval(ce[i][j], &be_, &mut autosim_core::expr::NoUserFunctions);
                assert!(
                    (a - b).abs() < 1e-12,
                    "C[{i}][{j}]: quaternion {a} vs angles {b}"
                );
            }
        }
        // Same dynamics: bind the converted state and solve.
        let mut sample = s.clone();
        let mut qv: Vec<f64> = q.clone();
        qv[3] = e[1];
        qv[4] = e[2];
        qv[5] = e[3];
        sample["q"] = serde_json::json!(qv);
        let mut bind_q = bind(&quat, &eqs, &sample, params);
        bind_q.set(quat.arena.symbol_named("e0").unwrap(), e[0]);
        let (dq, du) = derivatives(&quat, &eqs, &bind_q);
        let err = rel_err(&du, &floats(&s["du"]));
        worst = worst_of(worst, err);
        assert!(err < 1e-9, "du differs by {err:e}");
        // Quaternion rates equal the derivative of the converted angles.
        let r = rates_123([q[3], q[4], q[5]], [u[3], u[4], u[5]]);
        let h = 1e-6;
        let ep = from_123(q[3] + h * r[0], q[4] + h * r[1], q[5] + h * r[2]);
        let em = from_123(q[3] - h * r[0], q[4] - h * r[1], q[5] - h * r[2]);
        for k in 1..4 {
            let fd = (ep[k] - em[k]) / (2.0 * h);
            assert!(
                (dq[2 + k] - fd).abs() < 1e-7,
                "de{k}/dt = {} vs {fd}",
                dq[2 + k]
            );
        }
        let e0dot = quat.arena.eval(
            eqs.state_derivatives[0],
            &bind_q,
            &mut autosim_core::expr::NoUserFunctions,
        );
        assert!((e0dot - (ep[0] - em[0]) / (2.0 * h)).abs() < 1e-7);
    }
    eprintln!("quaternion satellite: worst relative error {worst:.2e}");
}

/// Locking the boom angles (q9, q10) at zero gives the full model with
/// those speeds constrained: the locked model's accelerations are the
/// solution of the full mass matrix and forcing with the boom rows and
/// columns removed, at q9 = q10 = u9 = u10 = 0.
#[test]
fn locked_boom_is_the_constrained_full_model() {
    let data = load("satellite");
    let params = &data["parameters"];
    let mut full = satellite(params, false);
    let mut locked = satellite_locked_boom(params);
    let ef = full.equations().unwrap();
    let el = locked.equations().unwrap();
    assert_eq!(el.speeds.len(), 8);
    for name in ["q9", "q10"] {
        let s = locked
            .arena
            .symbol_named(name)
            .expect("locked coordinate is a parameter");
        assert!(locked.arena.symbol(s).is_constant());
    }
    for s in data["samples"].as_array().unwrap() {
        let mut sample = s.clone();
        let mut q = floats(&s["q"]);
        let mut u = floats(&s["u"]);
        q[8] = 0.0;
        q[9] = 0.0;
        u[8] = 0.0;
        u[9] = 0.0;
        sample["q"] = serde_json::json!(q);
        sample["u"] = serde_json::json!(u);
        let bf = bind(&full, &ef, &sample, params);
        let (_, m, f) = evaluated(&full, &ef, &bf);
        let keep: Vec<usize> = (0..8).collect();
        let mr = m.select_rows(&keep).select_columns(&keep);
        let fr = f.select_rows(&keep);
        let want: Vec<f64> = mr.lu().solve(&fr).unwrap().iter().copied().collect();
        let mut ls = sample.clone();
        ls["q"] = serde_json::json!(q[..8].to_vec());
        ls["u"] = serde_json::json!(u[..8].to_vec());
        let bl = bind(&locked, &el, &ls, params);
        let (_, du) = derivatives(&locked, &el, &bl);
        let err = rel_err(&du, &want);
        assert!(
            err < 1e-10,
            "locked boom differs from the constrained model by {err:e}"
        );
    }
}

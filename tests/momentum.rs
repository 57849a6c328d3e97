//! A free-floating spacecraft-like model (a bus with a sprung boom and a
//! sprung reaction wheel, no gravity, no external load) integrated with
//! Dormand–Prince at 1e-12 conserves the built-ins' linear momentum, angular
//! momentum about a point fixed in N, and energy (`kinetic_energy()` plus
//! the two springs' potentials). Their values are checked against an
//! independent Newton–Euler computation on the satellite in
//! `autosim-core/tests/quantities/satellite.rs`.

use autosim::runtime::Model;
use autosim_test_support::tight_run;

autosim::model! {
    /// A bus B tumbling freely, a boom F hinged on it with a torsional
    /// spring, and a wheel W turning on it against a torsional spring: every
    /// load is internal.
    model Floating;
    parameters {
        mb = 50 [kg], mf = 5 [kg], mw = 2 [kg], L = 2 [m],
        kf = 40 [N m/rad], kw = 3 [N m/rad],
    }
    body B {
        translate: [1, 2, 3], rotate: [1, 2, 3], mass: mb,
        inertia: [[10, 1, -0.5], [1, 12, 0.3], [-0.5, 0.3, 15]],
        initial: [0.1, 0.2, -0.3, 0.1, -0.2, 0.3],
        initial_speeds: [0.1, -0.2, 0.05, 0.3, -0.1, 0.2],
    }
    body F {
        parent: B, joint: [0, 0.8, 0], rotate: 3, mass: mf, cm: [0, L/2, 0],
        inertia: diag(mf*L^2/12, 0.01, mf*L^2/12), initial: [0.2], initial_speeds: [1.5],
    }
    body W {
        parent: B, joint: [0.3, 0, 0.2], rotate: 2, mass: mw, cm: [0.05, 0, 0],
        inertia: diag(0.02, 0.04, 0.02), initial_speeds: [8],
    }
    moment boom { on: F, reaction: B, about: b3, magnitude: -kf*q(F) }
    moment wheel { on: W, reaction: B, about: b2, magnitude: -kw*q(W) }
    point O in N at [1, -2, 0.5];
    output p1 [kg m/s] = dot(momentum(), n1);
    output p2 [kg m/s] = dot(momentum(), n2);
    output p3 [kg m/s] = dot(momentum(), n3);
    output h1 [kg m^2/s] = dot(angular_momentum(O), n1);
    output h2 [kg m^2/s] = dot(angular_momentum(O), n2);
    output h3 [kg m^2/s] = dot(angular_momentum(O), n3);
    output energy [J] = kinetic_energy() + potential_energy() + kf*q(F)^2/2 + kw*q(W)^2/2;
}
use floating::Floating;

#[test]
fn a_free_body_conserves_momentum_angular_momentum_and_energy() {
    let mut model = Floating::new();
    let mut x = model.initial_state();
    let (summary, out) = tight_run(&mut model, &mut x, 5.0, 0.01);
    let y0 = out[0].2;
    // Nothing is trivially zero.
    let p0 = (y0[0] * y0[0] + y0[1] * y0[1] + y0[2] * y0[2]).sqrt();
    let h0 = (y0[3] * y0[3] + y0[4] * y0[4] + y0[5] * y0[5]).sqrt();
    assert!(p0 > 1.0 && h0 > 1.0 && y0[6] > 1.0, "{y0:?}");
    let mut drift = [0.0f64; 3];
    for (_, _, y) in &out {
        for k in 0..3 {
            drift[0] = drift[0].max((y[k] - y0[k]).abs() / p0);
            drift[1] = drift[1].max((y[3 + k] - y0[3 + k]).abs() / h0);
        }
        drift[2] = drift[2].max((y[6] - y0[6]).abs() / y0[6]);
    }
    eprintln!(
        "free-floating model over 5 s ({} steps, Dormand–Prince at 1e-12): relative drift of momentum {:.2e}, angular momentum {:.2e}, energy {:.2e}",
        summary.steps, drift[0], drift[1], drift[2]
    );
    assert!(drift[0] < 1e-10, "momentum drift {:e}", drift[0]);
    assert!(drift[1] < 1e-10, "angular momentum drift {:e}", drift[1]);
    assert!(drift[2] < 1e-10, "energy drift {:e}", drift[2]);
    // The motion is not trivial: the boom swings and the bus turns.
    let last = out.last().expect("outputs").1;
    assert!((last[6] - 0.2).abs() > 0.01 && (last[3] - 0.1).abs() > 0.01);
}

//! The reference models built through the API match the independent
//! reference data in ../shared/reference to 1e-9.

use autosim_core::expr::ExprId;
use autosim_core::mech::{Equations, System};
use autosim_test_support::api::*;
use autosim_test_support::*;
use serde_json::Value;

fn check_chain(n: usize, spatial: bool) {
    let name = format!("chain-{}-{n}", if spatial { "spatial" } else { "planar" });
    let data = load(&name);
    let params = &data["parameters"];
    let mut sys = chain(n, spatial, params);
    let eqs = sys.equations().unwrap();
    // Energy: kinetic + gravity + springs.
    let ke = sys.kinetic_energy();
    let mut pe_terms = Vec::new();
    for i in 1..=n {
        let b = sys.body_named(&format!("B{i}")).unwrap();
        let cm = sys.body(b).cm_point;
        let r = sys.pos(cm, None);
        let z = vector_dot_n3(&mut sys, &r);
        let m = sys.body(b).mass;
        let g = sys.arena.parse_text("g").unwrap();
        pe_terms.push(sys.arena.product(&[m, g, z]));
        let q = sys.arena.sym(sys.coordinates()[i - 1].q);
        let k = sys.arena.parse_text("k/2").unwrap();
        let q2 = sys.arena.powi(q, 2);
        pe_terms.push(sys.arena.mul(k, q2));
    }
    let pe = sys.arena.sum(&pe_terms);
    let energy = sys.arena.add(ke, pe);
    check_samples(&name, &sys, &eqs, &data, energy, "energy");
}

/// Every sample of the reference `data`: dq and du to 1e-9 (normwise
/// relative), and `energy` evaluated at the sample against the sample's
/// field `energy_key` to 1e-9 (relative above 1).
fn check_samples(
    name: &str,
    sys: &System,
    eqs: &Equations,
    data: &Value,
    energy: ExprId,
    energy_key: &str,
) {
    let params = &data["parameters"];
    let mut worst: f64 = 0.0;
    for sample in data["samples"].as_array().unwrap() {
        let b = bind(sys, eqs, sample, params);
        let (dq, du) = derivatives(sys, eqs, &b);
        let want_dq = floats(&sample["dq"]);
        let want_du = floats(&sample["du"]);
        let e_dq = rel_err(&dq, &want_dq);
        let e_du = rel_err(&du, &want_du);
        worst = worst_of(worst_of(worst, e_dq), e_du);
        assert!(
            e_dq < 1e-9 && e_du < 1e-9,
            "{name}: dq err {e_dq:e}, du err {e_du:e}\n got {du:?}\nwant {want_du:?}"
        );
        let e = sys
            .arena
            .eval(energy, &b, &mut autosim_core::expr::NoUserFunctions);
        let want_e = sample[energy_key].as_f64().unwrap();
        assert!(
            (e - want_e).abs() <= 1e-9 * want_e.abs().max(1.0),
            "{name}: {energy_key} {e} vs {want_e}"
        );
    }
    eprintln!("{name}: worst relative error {worst:.2e}");
}

#[test]
fn chain_planar_matches_reference() {
    for n in [1, 2, 3, 5, 10] {
        check_chain(n, false);
    }
}

#[test]
fn chain_spatial_matches_reference() {
    for n in [1, 2, 3, 5, 10] {
        check_chain(n, true);
    }
}

#[test]
fn satellite_matches_reference() {
    let data = load("satellite");
    let params = &data["parameters"];
    let mut sys = satellite(params, false);
    let eqs = sys.equations().unwrap();
    let ke = sys.kinetic_energy();
    check_samples("satellite", &sys, &eqs, &data, ke, "kinetic_energy");
}

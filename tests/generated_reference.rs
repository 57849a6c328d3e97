//! Every reference model, written in the language and compiled through the
//! macro, matches the independent reference data in ../shared/reference.

use autosim::runtime::Model;
use autosim_test_support::*;

macro_rules! chain_test {
    ($test:ident, $module:ident, $ty:ident, $file:literal, $reference:literal) => {
        mod $test {
            autosim::model!(file = $file);
        }
        #[test]
        fn $test() {
            use $test::$module::{Parameters, $ty};
            let data = load($reference);
            let mut model = $ty::new();
            // The model's defaults are the reference parameters (to rounding:
            // the files write the definitions' values, the reference JSON
            // what its program computed); run with the reference's own.
            let mut values = vec![0.0; <$ty as Model>::PARAMETER_NAMES.len()];
            model.parameter_values(&mut values);
            for (name, v) in <$ty as Model>::PARAMETER_NAMES
                .iter()
                .zip(values.iter_mut())
            {
                let want = data["parameters"][*name].as_f64().unwrap();
                assert!(
                    (*v - want).abs() <= 1e-15 * want.abs(),
                    "parameter {name}: {v} vs {want}"
                );
                *v = want;
            }
            model.set_parameter_values(&values);
            let _ = Parameters::default();
            let n = <$ty as Model>::STATE_NAMES.len() / 2;
            let mut worst: f64 = 0.0;
            for s in data["samples"].as_array().unwrap() {
                let mut x = [0.0; <$ty as Model>::STATE_NAMES.len()];
                x[..n].copy_from_slice(&floats(&s["q"]));
                x[n..].copy_from_slice(&floats(&s["u"]));
                let mut dx = x;
                model
                    .derivatives(s["t"].as_f64().unwrap(), &x, &mut dx)
                    .unwrap();
                let e_dq = rel_err(&dx[..n], &floats(&s["dq"]));
                let e_du = rel_err(&dx[n..], &floats(&s["du"]));
                worst = worst_of(worst_of(worst, e_dq), e_du);
                assert!(
                    e_dq < REFERENCE_AGREEMENT && e_du < REFERENCE_AGREEMENT,
                    "{}: dq {e_dq:e}, du {e_du:e}",
                    $reference
                );
            }
            eprintln!("{}: worst relative error {worst:.2e}", $reference);
        }
    };
}

chain_test!(
    chain_planar_1,
    chain_planar1,
    ChainPlanar1,
    "examples/models/chain_planar_1.sim",
    "chain-planar-1"
);
chain_test!(
    chain_planar_2,
    chain_planar2,
    ChainPlanar2,
    "examples/models/chain_planar_2.sim",
    "chain-planar-2"
);
chain_test!(
    chain_planar_3,
    chain_planar3,
    ChainPlanar3,
    "examples/models/chain_planar_3.sim",
    "chain-planar-3"
);
chain_test!(
    chain_planar_5,
    chain_planar5,
    ChainPlanar5,
    "examples/models/chain_planar_5.sim",
    "chain-planar-5"
);
chain_test!(
    chain_planar_10,
    chain_planar10,
    ChainPlanar10,
    "examples/models/chain_planar_10.sim",
    "chain-planar-10"
);
chain_test!(
    chain_spatial_1,
    chain_spatial1,
    ChainSpatial1,
    "examples/models/chain_spatial_1.sim",
    "chain-spatial-1"
);
chain_test!(
    chain_spatial_2,
    chain_spatial2,
    ChainSpatial2,
    "examples/models/chain_spatial_2.sim",
    "chain-spatial-2"
);
chain_test!(
    chain_spatial_3,
    chain_spatial3,
    ChainSpatial3,
    "examples/models/chain_spatial_3.sim",
    "chain-spatial-3"
);
chain_test!(
    chain_spatial_5,
    chain_spatial5,
    ChainSpatial5,
    "examples/models/chain_spatial_5.sim",
    "chain-spatial-5"
);
chain_test!(
    chain_spatial_10,
    chain_spatial10,
    ChainSpatial10,
    "examples/models/chain_spatial_10.sim",
    "chain-spatial-10"
);

mod satellite_model {
    autosim::model!(file = "examples/models/satellite.sim");
}

/// User code that returns a reference sample's recorded inputs.
struct Recorded {
    cmd: [f64; 2],
    thrust: [f64; 3],
    calls: Vec<usize>,
}

impl satellite_model::satellite::Externs for Recorded {
    fn thrust(&mut self, _t: f64, axis: f64, _error: f64) -> f64 {
        self.calls.push(axis as usize);
        self.thrust[axis as usize - 1]
    }
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        self.cmd
    }
}

#[test]
fn satellite() {
    use satellite_model::satellite::Satellite;
    let mut model = Satellite::new(Recorded {
        cmd: [0.0; 2],
        thrust: [0.0; 3],
        calls: Vec::new(),
    });
    let mut worst: f64 = 0.0;
    for s in satellite_samples() {
        model.externs.cmd = s.cmd;
        model.externs.thrust = s.thrust;
        model.externs.calls.clear();
        let x = s.state();
        let mut dx = x;
        model.derivatives(s.t, &x, &mut dx).unwrap();
        // The thrusters are called once per evaluation, axes 1, 2, 3.
        assert_eq!(model.externs.calls, [1, 2, 3]);
        let e_dq = rel_err(&dx[..10], &s.dq);
        let e_du = rel_err(&dx[10..], &s.du);
        worst = worst_of(worst_of(worst, e_dq), e_du);
        assert!(
            e_dq < REFERENCE_AGREEMENT && e_du < REFERENCE_AGREEMENT,
            "satellite: dq {e_dq:e}, du {e_du:e}"
        );
    }
    eprintln!("satellite: worst relative error {worst:.2e}");
}

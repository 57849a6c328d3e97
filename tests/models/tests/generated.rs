//! The build-script path matches the reference data, and every generated
//! model (both paths) matches the core's evaluation of its unoptimized
//! equations at random states (a differential test of the optimizer).

mod common;
use autosim::runtime::Model;
use autosim_core::expr::Bindings;
use autosim_core::pipeline::Compiled;
use autosim_models_check::{scenes, via_build, via_macro};
use autosim_test_support::*;
use common::compile;

/// du/dt from the symbolic equations: evaluate M and f, solve with nalgebra.
fn reference_derivatives(
    c: &Compiled,
    params: &[f64],
    t: f64,
    x: &[f64],
    inputs: &[f64],
) -> Vec<f64> {
    let sys = &c.model.system;
    let eqs = &c.equations;
    let mut b = Bindings::with_defaults(&sys.arena);
    for (s, v) in sys.parameters().iter().zip(params) {
        b.set(*s, *v);
    }
    for (s, v) in sys.inputs().iter().zip(inputs) {
        b.set(*s, *v);
    }
    for (s, v) in eqs
        .coordinates
        .iter()
        .chain(&eqs.speeds)
        .chain(&eqs.states)
        .zip(x)
    {
        b.set(*s, *v);
    }
    b.set(sys.time(), t);
    let (mut out, m, f) = api::evaluated(sys, eqs, &b);
    let du = m.lu().solve(&f).expect("regular mass matrix");
    out.extend(du.iter());
    out
}

macro_rules! differential {
    ($test:ident, $file:literal, $($path:ident)::+) => {
        #[test]
        fn $test() {
            let c = compile($file);
            let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
            let mut worst: f64 = 0.0;
            let mut model = $($path)::+::new();
            let mut params = vec![0.0; <$($path)::+ as Model>::PARAMETER_NAMES.len()];
            model.parameter_values(&mut params);
            let n = c.program.n();
            for _ in 0..25 {
                let mut x = [0.0; <$($path)::+ as Model>::STATE_NAMES.len()];
                for (i, v) in x.iter_mut().enumerate() {
                    *v = if i < n { rng.uniform(-3.0, 3.0) } else { rng.uniform(-2.0, 2.0) };
                }
                let t = rng.uniform(0.0, 10.0);
                let mut dx = x;
                if model.derivatives(t, &x, &mut dx).is_err() {
                    continue;
                }
                let want = reference_derivatives(&c, &params, t, &x, &[]);
                let e = rel_err(&dx[..2 * n], &want);
                worst = worst_of(worst, e);
                assert!(e < 1e-12, "{}: optimized vs unoptimized {e:e}", $file);
            }
            eprintln!("{}: worst relative difference {worst:.2e}", $file);
        }
    };
}

differential!(
    chain_planar_10_macro,
    "chain_planar_10.sim",
    via_macro::chain_planar10::ChainPlanar10
);
differential!(
    chain_planar_10_build,
    "chain_planar_10.sim",
    via_build::chain_planar10::ChainPlanar10
);
differential!(
    chain_spatial_7_macro,
    "chain_spatial_7.sim",
    via_macro::chain_spatial7::ChainSpatial7
);
differential!(
    chain_spatial_10_build,
    "chain_spatial_10.sim",
    via_build::chain_spatial10::ChainSpatial10
);
differential!(
    chain_spatial_20_build,
    "chain_spatial_20.sim",
    via_build::chain_spatial20::ChainSpatial20
);
differential!(
    chain_spatial_3_stiff_build,
    "chain_spatial_3_stiff.sim",
    via_build::chain_spatial3_stiff::ChainSpatial3Stiff
);

macro_rules! reference {
    ($test:ident, $reference:literal, $($path:ident)::+) => {
        #[test]
        fn $test() {
            let data = load($reference);
            let mut model = $($path)::+::new();
            let mut values = vec![0.0; <$($path)::+ as Model>::PARAMETER_NAMES.len()];
            for (name, v) in <$($path)::+ as Model>::PARAMETER_NAMES.iter().zip(values.iter_mut()) {
                *v = data["parameters"][*name].as_f64().expect("parameter in reference");
            }
            model.set_parameter_values(&values);
            let n = <$($path)::+ as Model>::STATE_NAMES.len() / 2;
            for s in data["samples"].as_array().unwrap() {
                let mut x = [0.0; <$($path)::+ as Model>::STATE_NAMES.len()];
                x[..n].copy_from_slice(&floats(&s["q"]));
                x[n..].copy_from_slice(&floats(&s["u"]));
                let mut dx = x;
                model.derivatives(s["t"].as_f64().unwrap(), &x, &mut dx).unwrap();
                let e_dq = rel_err(&dx[..n], &floats(&s["dq"]));
                let e_du = rel_err(&dx[n..], &floats(&s["du"]));
                assert!(e_dq < REFERENCE_AGREEMENT && e_du < REFERENCE_AGREEMENT, "{}: dq {e_dq:e} du {e_du:e}", $reference);
            }
        }
    };
}

reference!(
    build_chain_planar_1,
    "chain-planar-1",
    via_build::chain_planar1::ChainPlanar1
);
reference!(
    build_chain_planar_2,
    "chain-planar-2",
    via_build::chain_planar2::ChainPlanar2
);
reference!(
    build_chain_planar_3,
    "chain-planar-3",
    via_build::chain_planar3::ChainPlanar3
);
reference!(
    build_chain_planar_5,
    "chain-planar-5",
    via_build::chain_planar5::ChainPlanar5
);
reference!(
    build_chain_planar_10,
    "chain-planar-10",
    via_build::chain_planar10::ChainPlanar10
);
reference!(
    build_chain_spatial_1,
    "chain-spatial-1",
    via_build::chain_spatial1::ChainSpatial1
);
reference!(
    build_chain_spatial_2,
    "chain-spatial-2",
    via_build::chain_spatial2::ChainSpatial2
);
reference!(
    build_chain_spatial_3,
    "chain-spatial-3",
    via_build::chain_spatial3::ChainSpatial3
);
reference!(
    build_chain_spatial_5,
    "chain-spatial-5",
    via_build::chain_spatial5::ChainSpatial5
);
reference!(
    build_chain_spatial_10,
    "chain-spatial-10",
    via_build::chain_spatial10::ChainSpatial10
);

/// The satellite through build.rs, with the sample's recorded user values.
struct Recorded {
    cmd: [f64; 2],
    thrust: [f64; 3],
}

impl via_build::satellite::Externs for Recorded {
    fn thrust(&mut self, _t: f64, axis: f64, _error: f64) -> f64 {
        self.thrust[(axis as usize).clamp(1, 3) - 1]
    }
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        self.cmd
    }
}

#[test]
fn build_satellite() {
    let mut model = via_build::satellite::Satellite::new(Recorded {
        cmd: [0.0; 2],
        thrust: [0.0; 3],
    });
    for s in satellite_samples() {
        model.externs.cmd = s.cmd;
        model.externs.thrust = s.thrust;
        let x = s.state();
        let mut dx = x;
        model.derivatives(s.t, &x, &mut dx).unwrap();
        let e = rel_err(&dx[10..], &s.du);
        assert!(e < REFERENCE_AGREEMENT, "satellite via build.rs: du {e:e}");
    }
}

#[test]
fn markdown_documentation_is_written() {
    let md = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/satellite.md"))
        .expect("satellite.md in OUT_DIR");
    for needle in [
        "# Satellite",
        "| `KB` | 2000 | N m/rad |",
        "## Outputs",
        "`roll`",
        "## Equations",
        "thrust(",
    ] {
        assert!(md.contains(needle), "satellite.md lacks {needle:?}");
    }
}

/// The f32 model agrees with the f64 model to single precision.
#[test]
fn f32_model_matches_f64_model() {
    let mut m64 = via_macro::chain_planar2::ChainPlanar2::new();
    let mut m32 = via_build::chain_planar2_f32::ChainPlanar2F32::new();
    let mut rng = Rng::new(7);
    let mut worst: f64 = 0.0;
    for _ in 0..100 {
        let mut x = [0.0f64; 4];
        for v in x.iter_mut() {
            *v = rng.uniform(-2.0, 2.0);
        }
        let x32 = x.map(|v| v as f32);
        let (mut d64, mut d32) = ([0.0f64; 4], [0.0f32; 4]);
        m64.derivatives(0.0, &x, &mut d64).unwrap();
        m32.derivatives(0.0, &x32, &mut d32).unwrap();
        let got: Vec<f64> = d32.iter().map(|v| f64::from(*v)).collect();
        worst = worst_of(worst, rel_err(&got, &d64));
    }
    eprintln!("f32 vs f64: worst relative difference {worst:.2e}");
    assert!(worst < 1e-4, "f32 model differs by {worst:e}");
}

struct Fixed;

impl scenes::satellite_small_scene::Externs for Fixed {
    fn thrust(&mut self, _t: f64, axis: f64, _e: f64) -> f64 {
        0.3 * axis - 0.5
    }
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        [0.8, -0.45]
    }
}

impl via_macro::satellite_small::Externs for Fixed {
    fn thrust(&mut self, _t: f64, axis: f64, _e: f64) -> f64 {
        0.3 * axis - 0.5
    }
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        [0.8, -0.45]
    }
}

impl scenes::rigid_boom::Externs for Fixed {
    fn thrust(&mut self, _t: f64, axis: f64, _e: f64) -> f64 {
        0.3 * axis - 0.5
    }
    fn cmd(&mut self, _t: f64) -> [f64; 2] {
        [0.8, -0.45]
    }
}

/// `small = [B, E, F]` at the use site gives the paper's small-variable
/// model: the same program as satellite_small.sim.
#[test]
fn scene_small_equals_small_model_file() {
    use scenes::satellite_small_scene::SatelliteSmallScene as Scene;
    use via_macro::satellite_small::SatelliteSmall as File;
    assert_eq!(
        Scene::<Fixed>::DERIVATIVE_OPS,
        File::<Fixed>::DERIVATIVE_OPS
    );
    let (mut a, mut b) = (Scene::new(Fixed), File::new(Fixed));
    let mut rng = Rng::new(3);
    for _ in 0..20 {
        let mut x = [0.0; 20];
        for v in x.iter_mut() {
            *v = rng.uniform(-0.01, 0.01);
        }
        let (mut da, mut db) = ([0.0; 20], [0.0; 20]);
        a.derivatives(0.0, &x, &mut da).unwrap();
        b.derivatives(0.0, &x, &mut db).unwrap();
        assert_eq!(da, db);
    }
}

/// `lock = [q9, q10], outputs = [roll, pitch, yaw]`: eight speeds, three
/// outputs, and less work than the full model.
#[test]
fn scene_lock_and_outputs() {
    use scenes::rigid_boom::{N_OUTPUTS, N_SPEEDS, RigidBoom};
    assert_eq!(N_SPEEDS, 8);
    assert_eq!(N_OUTPUTS, 3);
    assert_eq!(
        <RigidBoom<Fixed> as Model>::OUTPUT_NAMES,
        ["roll", "pitch", "yaw"]
    );
    assert!(<RigidBoom<Fixed> as Model>::PARAMETER_NAMES.contains(&"q9"));
    let full = via_build::satellite::Satellite::<Recorded>::DERIVATIVE_OPS.total();
    let rigid = RigidBoom::<Fixed>::DERIVATIVE_OPS.total();
    eprintln!("satellite derivatives: {full} ops; with the boom locked: {rigid} ops");
    assert!(rigid < full);
}

/// A model's fingerprint is its generated code's: the macro and the build
/// script give the same one, `Model::FINGERPRINT` is the module's, and
/// another model (or the same file compiled as a scene, or in `f32`) has
/// another.
#[test]
fn fingerprints_follow_the_generated_code() {
    macro_rules! both_paths {
        ($($model:ident),*) => {
            (
                [$(via_macro::$model::FINGERPRINT),*],
                [$(via_build::$model::FINGERPRINT),*],
            )
        };
    }
    let (by_macro, by_build) = both_paths!(
        andrews,
        bicycle,
        four_bar,
        satellite,
        chain_spatial10,
        chain_planar2,
        chain_planar2_f32
    );
    assert_eq!(by_macro, by_build);
    let mut all = by_macro.to_vec();
    all.push(scenes::rigid_boom::FINGERPRINT);
    all.push(scenes::four_bar_f32::FINGERPRINT);
    all.sort_unstable();
    all.dedup();
    assert_eq!(all.len(), by_macro.len() + 2, "{all:x?}");
    assert_eq!(
        <via_build::bicycle::Bicycle as Model>::FINGERPRINT,
        via_build::bicycle::FINGERPRINT
    );
}

//! The undamped 3-link chains (c = 0), integrated for 5 s with
//! Dormand–Prince at a tight tolerance, reproduce the independent reference
//! trajectories `chain-{planar,spatial}-3-trajectory.json` (SciPy DOP853 at
//! 1e-12 on SymPy's equations) to 1e-7, and conserve energy.
//!
//! The energy is the reference's definition: kinetic (½ uᵀ M(q) u, with the
//! generated mass matrix) + gravitational (Σ m_i g z_i of the mass centers,
//! computed here from the chain's geometry) + Σ ½ k q_i².

use autosim::runtime::Model;
use autosim_test_support::{floats, kinetic_energy, load, tight_run, worst_of};
use serde_json::Value;

mod planar {
    autosim::model!(file = "examples/models/chain_planar_3.sim");
}
mod spatial {
    autosim::model!(file = "examples/models/chain_spatial_3.sim");
}

/// The model's parameters set from the reference file, by name.
fn set_parameters<M: Model<Float = f64>>(model: &mut M, data: &Value) {
    let values: Vec<f64> = M::PARAMETER_NAMES
        .iter()
        .map(|name| {
            data["parameters"][*name]
                .as_f64()
                .unwrap_or_else(|| panic!("parameter {name} missing from the reference"))
        })
        .collect();
    assert_eq!(data["parameters"]["c"].as_f64(), Some(0.0), "undamped");
    model.set_parameter_values(&values);
}

/// Rotation by `q` about axis `axis` (1, 2, 3): child components to parent components.
fn rotation(axis: usize, q: f64) -> [[f64; 3]; 3] {
    let (s, c) = q.sin_cos();
    match axis {
        1 => [[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]],
        2 => [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]],
        3 => [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]],
        _ => unreachable!(),
    }
}

fn matmul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

/// Heights (n3 components) of the mass centers of a chain whose link `i`
/// turns about its parent's axis `axes[i]` (reference-models.md).
fn mass_center_heights(axes: &[usize; 3], lengths: &[f64; 3], q: &[f64]) -> [f64; 3] {
    let mut frame = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut joint_z = 0.0;
    let mut z = [0.0; 3];
    for i in 0..3 {
        frame = matmul(&frame, &rotation(axes[i], q[i]));
        // The n3 component of C·(0, 0, -l) is -l C[2][2].
        z[i] = joint_z - 0.5 * lengths[i] * frame[2][2];
        joint_z -= lengths[i] * frame[2][2];
    }
    z
}

macro_rules! trajectory_test {
    ($test:ident, $ty:ty, $reference:literal, $axes:expr) => {
        #[test]
        fn $test() {
            type M = $ty;
            let data = load($reference);
            let mut model = <M>::new();
            set_parameters(&mut model, &data);
            let p = |name: &str| data["parameters"][name].as_f64().unwrap();
            let masses = [p("m1"), p("m2"), p("m3")];
            let lengths = [p("L1"), p("L2"), p("L3")];
            let (k, g) = (p("k"), p("g"));

            let energy = |model: &mut M, x: &[f64; 6], tip_height: f64| {
                let mut m = [[0.0; 3]; 3];
                model.mass_matrix(0.0, x, &mut m);
                let kinetic = kinetic_energy(&m, &x[3..]);
                let z = mass_center_heights(&$axes, &lengths, &x[..3]);
                // The model's output is the last mass center's height.
                assert!((z[2] - tip_height).abs() < 1e-12, "tip_height {tip_height} vs {}", z[2]);
                let gravity: f64 = (0..3).map(|i| masses[i] * g * z[i]).sum();
                let springs: f64 = x[..3].iter().map(|q| 0.5 * k * q * q).sum();
                kinetic + gravity + springs
            };

            let records = data["records"].as_array().unwrap();
            let mut x = [0.0; 6];
            x[..3].copy_from_slice(&floats(&records[0]["q"]));
            x[3..].copy_from_slice(&floats(&records[0]["u"]));

            let (summary, outputs) = tight_run(&mut model, &mut x, 5.0, 0.01);
            let outputs: Vec<(f64, [f64; 6], f64)> = outputs.into_iter().map(|(t, x, y)| (t, x, y[0])).collect();

            // States at the reference's records.
            let mut worst_state = 0.0f64;
            let mut worst_energy_vs_ref = 0.0f64;
            for record in records {
                let t = record["t"].as_f64().unwrap();
                let (_, got, tip) = *outputs
                    .iter()
                    .find(|o| (o.0 - t).abs() < 1e-9)
                    .unwrap_or_else(|| panic!("no output at t = {t}"));
                let want: Vec<f64> = floats(&record["q"]).into_iter().chain(floats(&record["u"])).collect();
                for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                    let err = (g - w).abs();
                    assert!(err < 1e-7, "{}: state {i} at t = {t}: {g} vs reference {w}", $reference);
                    worst_state = worst_state.max(err);
                }
                let e = energy(&mut model, &got, tip);
                let e_ref = record["energy"].as_f64().unwrap();
                worst_energy_vs_ref = worst_energy_vs_ref.max((e - e_ref).abs());
            }
            // Our energy definition is the reference's (checked at every record).
            assert!(worst_energy_vs_ref < 1e-7, "energy vs reference {worst_energy_vs_ref:e}");

            // Energy drift over every output (every 10 ms).
            let e0 = energy(&mut model, &outputs[0].1, outputs[0].2);
            let drift = outputs
                .iter()
                .map(|(_, x, tip)| (energy(&mut model, x, *tip) - e0).abs())
                .fold(0.0f64, worst_of);
            assert!(drift < 1e-8 * e0.abs(), "energy drift {drift:e} of {e0}");

            eprintln!(
                "{}: max |state error| {worst_state:.2e} at {} records; energy drift {drift:.2e} J (relative {:.2e}) over {} outputs; |E - E_ref| {worst_energy_vs_ref:.2e} J; {} steps ({} rejected), {} evaluations",
                $reference,
                records.len(),
                drift / e0.abs(),
                outputs.len(),
                summary.steps,
                summary.rejected_steps,
                summary.evaluations,
            );
        }
    };
}

trajectory_test!(
    chain_planar_3_trajectory,
    planar::chain_planar3::ChainPlanar3,
    "chain-planar-3-trajectory",
    [1, 1, 1]
);
trajectory_test!(
    chain_spatial_3_trajectory,
    spatial::chain_spatial3::ChainSpatial3,
    "chain-spatial-3-trajectory",
    [1, 2, 3]
);

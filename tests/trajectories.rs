//! The undamped 3-link chains (c = 0), integrated for 5 s with
//! Dormand–Prince at a tight tolerance, reproduce the independent reference
//! trajectories `chain-{planar,spatial}-3-trajectory.json` (SciPy DOP853 at
//! 1e-12 on SymPy's equations) to 1e-7, and conserve energy.
//!
//! The energy is the reference's definition, kinetic + gravitational +
//! Σ ½ k q_i², computed by the model language's built-ins
//! (`kinetic_energy() + potential_energy()`) in an output added to the
//! example's text and read through the compiler's interpreter: the
//! example files keep one output, since another one would change their
//! generated derivatives (the parameter constants they share with the
//! outputs are renumbered).

use autosim::runtime::Model;
use autosim_core::diag::SourceFile;
use autosim_core::opt::{At, Interpreter, UserCalls};
use autosim_core::pipeline::{Compiled, compile_source};
use autosim_test_support::{floats, load, program_parameters, tight_run, worst_of};
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

/// The chain of `file` with the output `energy` from the built-ins,
/// compiled for the interpreter, and its parameters from the reference.
fn energy_model(file: &str, data: &Value) -> (Compiled, Vec<f64>) {
    let text = std::fs::read_to_string(file).expect("model file")
        + "output energy [J] = kinetic_energy() + potential_energy() + k*(q1^2 + q2^2 + q3^2)/2;\n";
    let source = SourceFile::new(file, text);
    let compiled = compile_source(&source).unwrap_or_else(|d| panic!("{}", d.render(&source)));
    let params = program_parameters(&compiled.program, data);
    (compiled, params)
}

/// The `energy` output of [`energy_model`] at state `x`.
fn energy_at(model: &(Compiled, Vec<f64>), x: &[f64]) -> f64 {
    let (compiled, params) = model;
    let index = compiled
        .program
        .interface
        .model
        .outputs
        .iter()
        .position(|o| o.name == "energy")
        .expect("energy output");
    let mut function = |_f: usize, _a: &[f64]| 0.0;
    let mut subroutine = |_s: usize, _a: &[f64]| Vec::new();
    let mut user = UserCalls {
        function: &mut function,
        subroutine: &mut subroutine,
    };
    let it = Interpreter::new(&compiled.program, params);
    it.outputs(
        At {
            t: 0.0,
            x,
            inputs: &[],
            discrete: &[],
        },
        &mut user,
    )
    .expect("outputs")[index]
}

macro_rules! trajectory_test {
    ($test:ident, $ty:ty, $reference:literal, $file:literal) => {
        #[test]
        fn $test() {
            type M = $ty;
            let data = load($reference);
            let mut model = <M>::new();
            set_parameters(&mut model, &data);
            let built_ins = energy_model($file, &data);
            let energy = |x: &[f64; 6]| energy_at(&built_ins, x);

            let records = data["records"].as_array().unwrap();
            let mut x = [0.0; 6];
            x[..3].copy_from_slice(&floats(&records[0]["q"]));
            x[3..].copy_from_slice(&floats(&records[0]["u"]));

            let (summary, outputs) = tight_run(&mut model, &mut x, 5.0, 0.01);
            let outputs: Vec<(f64, [f64; 6])> = outputs.into_iter().map(|(t, x, _)| (t, x)).collect();

            // States at the reference's records.
            let mut worst_state = 0.0f64;
            let mut worst_energy_vs_ref = 0.0f64;
            for record in records {
                let t = record["t"].as_f64().unwrap();
                let (_, got) = *outputs
                    .iter()
                    .find(|o| (o.0 - t).abs() < 1e-9)
                    .unwrap_or_else(|| panic!("no output at t = {t}"));
                let want: Vec<f64> = floats(&record["q"]).into_iter().chain(floats(&record["u"])).collect();
                for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                    let err = (g - w).abs();
                    assert!(err < 1e-7, "{}: state {i} at t = {t}: {g} vs reference {w}", $reference);
                    worst_state = worst_state.max(err);
                }
                let e = energy(&got);
                let e_ref = record["energy"].as_f64().unwrap();
                worst_energy_vs_ref = worst_energy_vs_ref.max((e - e_ref).abs());
            }
            // Our energy definition is the reference's (checked at every record).
            assert!(worst_energy_vs_ref < 1e-7, "energy vs reference {worst_energy_vs_ref:e}");

            // Energy drift over every output (every 10 ms).
            let e0 = energy(&outputs[0].1);
            let drift = outputs
                .iter()
                .map(|(_, x)| (energy(x) - e0).abs())
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
    "examples/models/chain_planar_3.sim"
);
trajectory_test!(
    chain_spatial_3_trajectory,
    spatial::chain_spatial3::ChainSpatial3,
    "chain-spatial-3-trajectory",
    "examples/models/chain_spatial_3.sim"
);

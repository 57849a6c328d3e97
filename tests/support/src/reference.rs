//! The reference data of `tests/reference` (see its README for where each
//! file comes from).

use serde_json::Value;
use std::path::PathBuf;

/// The folder `tests/reference` of this repository.
pub fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../reference")
}

/// A reference file by model name (`satellite`, `chain-planar-3`, ...).
pub fn load(name: &str) -> Value {
    let path = dir().join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The largest difference of a run's states from a reference file's
/// `samples` (each `{"t": ..., "state": [...]}`): `time` the recorded times
/// (each sample's found among them to 1e-12), `state(i, k)` state `i` at
/// recorded time `k`.
pub fn sample_error(samples: &Value, time: &[f64], state: impl Fn(usize, usize) -> f64) -> f64 {
    let mut worst: f64 = 0.0;
    for sample in samples.as_array().expect("a JSON array of samples") {
        let t = sample["t"].as_f64().expect("a sample's time");
        let k = time
            .iter()
            .position(|&r| (r - t).abs() < 1e-12)
            .unwrap_or_else(|| panic!("no recorded time {t}"));
        for (i, expected) in floats(&sample["state"]).iter().enumerate() {
            worst = worst.max((state(i, k) - expected).abs());
        }
    }
    worst
}

/// A JSON array of numbers.
pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("a JSON array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// The values of a compiled program's parameters, in its order, from a
/// reference file's `parameters` (each must be there).
pub fn program_parameters(program: &autosim_core::opt::Program, data: &Value) -> Vec<f64> {
    program
        .interface
        .model
        .parameters
        .iter()
        .map(|p| {
            data["parameters"][&p.name]
                .as_f64()
                .unwrap_or_else(|| panic!("parameter {} missing from the reference", p.name))
        })
        .collect()
}

/// One sample of the satellite's reference file (`satellite.json`): the
/// time and state, the values its user code returned there, and the rates.
#[derive(Clone, Debug)]
pub struct SatelliteSample {
    /// Time, in s.
    pub t: f64,
    /// Coordinates `q1 … q10`.
    pub q: Vec<f64>,
    /// Speeds `u1 … u10`.
    pub u: Vec<f64>,
    /// What the subroutine `cmd` returned: `[clkcmd, camcmd]`.
    pub cmd: [f64; 2],
    /// What `thrust` returned for axes 1, 2, 3.
    pub thrust: [f64; 3],
    /// Expected `dq/dt`.
    pub dq: Vec<f64>,
    /// Expected `du/dt`.
    pub du: Vec<f64>,
}

impl SatelliteSample {
    /// The state vector, coordinates then speeds.
    pub fn state(&self) -> [f64; 20] {
        let mut x = [0.0; 20];
        x[..10].copy_from_slice(&self.q);
        x[10..].copy_from_slice(&self.u);
        x
    }
}

/// Every sample of the satellite's reference file.
pub fn satellite_samples() -> Vec<SatelliteSample> {
    let data = load("satellite");
    let samples = data["samples"].as_array().expect("samples");
    samples
        .iter()
        .map(|s| {
            let input = |k: &str| s["inputs"][k].as_f64().expect("a recorded input");
            SatelliteSample {
                t: s["t"].as_f64().expect("t"),
                q: floats(&s["q"]),
                u: floats(&s["u"]),
                cmd: [input("clkcmd"), input("camcmd")],
                thrust: [input("thr1"), input("thr2"), input("thr3")],
                dq: floats(&s["dq"]),
                du: floats(&s["du"]),
            }
        })
        .collect()
}

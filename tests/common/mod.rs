//! Shared helpers of the workspace tests: the reference data in
//! `../shared/reference` and comparisons.

#![allow(dead_code)]

use serde_json::Value;
use std::path::PathBuf;

/// `$AUTOSIM_SHARED/reference`, or `../shared/reference` beside the repository.
pub fn reference_dir() -> PathBuf {
    if let Ok(dir) = std::env::var("AUTOSIM_SHARED") {
        return PathBuf::from(dir).join("reference");
    }
    // The first ancestor of this crate that has `shared/reference` beside it.
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest
        .ancestors()
        .map(|dir| dir.join("../shared/reference"))
        .find(|dir| dir.is_dir())
        .unwrap_or_else(|| manifest.join("../shared/reference"))
}

/// A reference file by model name (`satellite`, `chain-planar-3`, ...).
pub fn load(name: &str) -> Value {
    let path = reference_dir().join(format!("{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "{}: {e} (set AUTOSIM_SHARED to the shared folder)",
            path.display()
        )
    });
    serde_json::from_str(&text).expect("valid JSON")
}

/// A JSON array of numbers.
pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("array")
        .iter()
        .map(|x| x.as_f64().expect("number"))
        .collect()
}

/// Largest absolute difference relative to the largest |want|.
pub fn rel_err(got: &[f64], want: &[f64]) -> f64 {
    assert_eq!(got.len(), want.len());
    let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs())).max(1e-300);
    got.iter()
        .zip(want)
        .fold(0.0f64, |a, (g, w)| a.max((g - w).abs()))
        / scale
}

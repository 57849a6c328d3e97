//! Compiles the three constrained example models and this folder's variant
//! of the rolling disc.

fn main() {
    let mut models: Vec<std::path::PathBuf> = ["four_bar", "rolling_disc", "bicycle"]
        .iter()
        .map(|m| format!("../../examples/models/{m}.sim").into())
        .collect();
    models.push("models/rolling_disc_lean.sim".into());
    for m in &models {
        println!("cargo::rerun-if-changed={}", m.display());
    }
    if let Err(e) = autosim::build::Config::new().compile(&models) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

//! Compiles the three constrained example models.

fn main() {
    let models: Vec<std::path::PathBuf> = ["four_bar", "rolling_disc", "bicycle"]
        .iter()
        .map(|m| format!("../../examples/models/{m}.sim").into())
        .collect();
    for m in &models {
        println!("cargo::rerun-if-changed={}", m.display());
    }
    if let Err(e) = autosim::build::Config::new().compile(&models) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

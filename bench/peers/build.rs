//! Compiles every model `run.sh` put into `models/` (the chains and the
//! satellite).

fn main() {
    let mut models: Vec<std::path::PathBuf> = std::fs::read_dir("models")
        .map(|dir| dir.filter_map(|e| e.ok().map(|e| e.path())).collect())
        .unwrap_or_default();
    models.retain(|p| p.extension().is_some_and(|x| x == "sim"));
    models.sort();
    println!("cargo::rerun-if-changed=models");
    if let Err(e) = autosim::build::Config::new().compile(&models) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

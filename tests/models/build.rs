//! Compiles every example model with the build-script API (and its
//! Markdown documentation).

fn main() {
    let models = std::fs::read_dir("../../examples/models")
        .map(|dir| {
            let mut v: Vec<std::path::PathBuf> = dir
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "sim"))
                .collect();
            v.sort();
            v
        })
        .unwrap_or_default();
    println!("cargo::rerun-if-changed=../../examples/models");
    if let Err(e) = autosim::build::Config::new()
        .markdown(true)
        .compile(&models)
    {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

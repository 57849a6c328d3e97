//! Compiles `examples/models/features.sim` as an FMU compiles it.

fn main() {
    if let Err(e) = autosim_fmu::generate("../../../../examples/models/features.sim", None) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

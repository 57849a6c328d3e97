//! Compiles `examples/models/satellite_small.sim` as an FMU compiles it.

fn main() {
    if let Err(e) = autosim_fmu::generate("../../../../examples/models/satellite_small.sim", None) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

//! Compiles `examples/models/satellite_sampled.sim` as an FMU compiles it.

fn main() {
    if let Err(e) = autosim_fmu::generate("../../../../examples/models/satellite_sampled.sim", None) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

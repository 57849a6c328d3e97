//! Compiles `examples/models/satellite_events.sim` as an FMU compiles it.

fn main() {
    if let Err(e) = autosim_fmu::generate("../../../../examples/models/satellite_events.sim", None) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

//! Compiles the satellite model as an FMU compiles it: `satellite.rs` and
//! `satellite_fmu.rs` (its GUID and dependent coordinates) in `OUT_DIR`.

fn main() {
    if let Err(e) = autosim_fmu::generate("../models/satellite.sim", None) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

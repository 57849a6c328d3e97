//! Compiles the falling ball as an FMU compiles it: `ball.rs` and
//! `ball_fmu.rs` (its GUID) in `OUT_DIR`.

fn main() {
    if let Err(e) = autosim_fmu::generate("../ball.sim", None) {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

//! Prints the embedded check's final state on the host (compare with the
//! Cortex-M4F run in QEMU, `tests/embedded`): one line, `state:` then six
//! `f32` values.

fn main() {
    match autosim_no_std_check::swing_f32() {
        Ok(x) => {
            let values: Vec<String> = x.iter().map(|v| format!("{v:e}")).collect();
            println!("state: {}", values.join(" "));
        }
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}

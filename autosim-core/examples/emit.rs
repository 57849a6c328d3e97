//! Prints the Rust generated for a model file: `cargo run -p autosim-core
//! --example emit -- path/to/model.sim`.

use autosim_core::diag::SourceFile;
use autosim_core::emit::{EmitOptions, format_tokens, model_tokens};
use autosim_core::pipeline::compile_source;

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: emit <model.sim>");
        std::process::exit(2);
    };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{path}: {e}");
            std::process::exit(1);
        }
    };
    let file = SourceFile::new(&path, text);
    match compile_source(&file) {
        Ok(c) => {
            let code = format_tokens(&model_tokens(&c.program, &EmitOptions::default()));
            // A closed pipe (`| head`) ends the output quietly, not in a panic.
            let _ = std::io::Write::write_all(&mut std::io::stdout(), code.as_bytes());
        }
        Err(d) => {
            eprint!("{}", d.render(&file));
            std::process::exit(1);
        }
    }
}

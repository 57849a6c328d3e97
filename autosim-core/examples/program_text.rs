//! Prints the program of a model file in its text form (every block):
//! `cargo run -p autosim-core --example program_text -- file.sim`.

use autosim_core::diag::SourceFile;
use autosim_core::pipeline::compile_source;

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: program_text <model.sim>");
        std::process::exit(2);
    };
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        eprintln!("{path}: {e}");
        std::process::exit(1)
    });
    let file = SourceFile::new(&path, text);
    match compile_source(&file) {
        Ok(c) => {
            // A closed pipe (`| head`) ends the output quietly, not in a panic.
            let text = c.program.to_string();
            let _ = std::io::Write::write_all(&mut std::io::stdout(), text.as_bytes());
        }
        Err(d) => {
            eprint!("{}", d.render(&file));
            std::process::exit(1);
        }
    }
}

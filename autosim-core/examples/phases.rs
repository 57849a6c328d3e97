//! Time of each compiler phase on a model file:
//! `cargo run --release -p autosim-core --example phases -- file.sim`.

use autosim_core::diag::SourceFile;
use std::time::Instant;

fn main() {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: phases <model.sim>");
        std::process::exit(2);
    };
    let Ok(text) = std::fs::read_to_string(&path) else {
        eprintln!("cannot read {path}");
        std::process::exit(1);
    };
    let file = SourceFile::new(&path, text);
    let t = Instant::now();
    let Ok(ast) = autosim_core::syntax::parse_source(&file) else {
        eprintln!("syntax errors");
        std::process::exit(1);
    };
    let t_parse = t.elapsed();
    let t = Instant::now();
    let Ok(mut model) = autosim_core::model::resolve(&ast) else {
        eprintln!("model errors");
        std::process::exit(1);
    };
    let t_resolve = t.elapsed();
    let t = Instant::now();
    let Ok(eqs) = model.system.equations() else {
        eprintln!("equation errors");
        std::process::exit(1);
    };
    let t_eqs = t.elapsed();
    let t = Instant::now();
    let input = autosim_core::pipeline::opt_input(&model, &eqs);
    let Ok(program) = autosim_core::opt::build(input) else {
        eprintln!("program errors");
        std::process::exit(1);
    };
    let t_prog = t.elapsed();
    let c = autosim_core::pipeline::Compiled {
        model,
        equations: eqs,
        program,
    };
    let t = Instant::now();
    let tokens =
        autosim_core::emit::model_tokens(&c.program, &autosim_core::emit::EmitOptions::default());
    let t_emit = t.elapsed();
    let t = Instant::now();
    let text = autosim_core::emit::format_tokens(&tokens);
    let t_fmt = t.elapsed();
    println!(
        "parse {t_parse:?}, resolve {t_resolve:?}, equations {t_eqs:?}, program {t_prog:?}, emit {t_emit:?}, format {t_fmt:?} ({} lines, {} arena nodes, {} IR nodes)",
        text.lines().count(),
        c.model.system.arena.len(),
        c.program.ir.len()
    );
}

//! Writes the code generated for every model in a source tree into a
//! folder, one file per model: each `.sim` file (its Rust and its
//! Markdown) and each `model!` invocation in a `.rs` file (its expansion,
//! errors and placeholder included; the models of the list macros
//! `models_from!` and `from_file!` too). Run it before and after a refactor
//! and compare the folders: a refactor proves itself by byte-identical
//! output.
//!
//! `cargo run -p autosim-core --example emit_all -- . /tmp/before`

use autosim_core::diag::SourceFile;
use autosim_core::emit::{EmitOptions, format_tokens, markdown, model_tokens};
use autosim_core::expand::expand_model;
use autosim_core::pipeline::compile_source;
use proc_macro2::{TokenStream, TokenTree};
use std::path::{Path, PathBuf};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [root, out] = args.as_slice() else {
        eprintln!("usage: emit_all <source tree> <output folder>");
        std::process::exit(2);
    };
    let (root, out) = (PathBuf::from(root), PathBuf::from(out));
    if let Err(e) = std::fs::create_dir_all(&out) {
        eprintln!("{}: {e}", out.display());
        std::process::exit(1);
    }
    let mut files = Vec::new();
    walk(&root, &mut files);
    let mut count = 0;
    for f in files {
        let name = f
            .strip_prefix(&root)
            .unwrap_or(&f)
            .to_string_lossy()
            .replace('/', "__");
        let Ok(text) = std::fs::read_to_string(&f) else {
            continue;
        };
        let outputs = match f.extension().and_then(|e| e.to_str()) {
            Some("sim") => vec![sim_file(&f, text)],
            Some("rs") => macro_calls(&f, &text),
            _ => Vec::new(),
        };
        for (k, text) in outputs.iter().enumerate() {
            let path = out.join(format!("{name}.{k}.out"));
            if let Err(e) = std::fs::write(&path, text) {
                eprintln!("{}: {e}", path.display());
                std::process::exit(1);
            }
            count += 1;
        }
    }
    eprintln!("{count} models written to {}", out.display());
}

/// The files below `dir`, sorted, without `target` and hidden folders.
fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for p in paths {
        let hidden = p
            .file_name()
            .is_some_and(|n| n == "target" || n.to_string_lossy().starts_with('.'));
        match (hidden, p.is_dir()) {
            (true, _) => {}
            (false, true) => walk(&p, out),
            (false, false) => out.push(p),
        }
    }
}

/// A model file's Rust and Markdown, or its diagnostics.
fn sim_file(path: &Path, text: String) -> String {
    let file = SourceFile::new(path, text);
    match compile_source(&file) {
        Ok(c) => format!(
            "{}\n===== markdown =====\n{}",
            format_tokens(&model_tokens(&c.program, &EmitOptions::default())),
            markdown(&c.program, &path.to_string_lossy())
        ),
        Err(d) => d.render(&file),
    }
}

/// The expansion of every `model!` call in a Rust file, as the macro
/// expands it there (file paths relative to the file's crate).
fn macro_calls(path: &Path, text: &str) -> Vec<String> {
    let Ok(tokens) = text.parse::<TokenStream>() else {
        return Vec::new();
    };
    let mut calls = Vec::new();
    find_calls(tokens, &mut calls);
    let root = crate_root(path);
    calls
        .into_iter()
        .map(|call| {
            let t = expand_model(call, &root);
            format!("{}\n===== tokens =====\n{t}", format_tokens(&t))
        })
        .collect()
}

/// The arguments of every `model!` call in `tokens`, and of every model a
/// list macro declares (`models_from!` of the test support crate, the
/// tradeoff example's `from_file!`: `"file": Name, option = value; ...`).
/// Calls inside `macro_rules!` templates (with `$` fragments) are skipped.
fn find_calls(tokens: TokenStream, calls: &mut Vec<TokenStream>) {
    let tokens: Vec<TokenTree> = tokens.into_iter().collect();
    for (i, t) in tokens.iter().enumerate() {
        if let TokenTree::Group(g) = t {
            find_calls(g.stream(), calls);
        }
        let (TokenTree::Ident(id), Some(TokenTree::Punct(p)), Some(TokenTree::Group(g))) =
            (t, tokens.get(i + 1), tokens.get(i + 2))
        else {
            continue;
        };
        if p.as_char() != '!' || g.stream().to_string().contains('$') {
            continue;
        }
        if id == "model" {
            calls.push(g.stream());
        } else if id == "models_from" || id == "from_file" {
            list_calls(g.stream(), calls);
        }
    }
}

/// `"file": Name, option = value; Name2; ...` as one `model!` argument
/// list per entry.
fn list_calls(tokens: TokenStream, calls: &mut Vec<TokenStream>) {
    let tokens: Vec<TokenTree> = tokens.into_iter().collect();
    let Some(file) = tokens.first() else { return };
    let mut entry: Vec<TokenTree> = Vec::new();
    for t in tokens.iter().skip(2) {
        if matches!(t, TokenTree::Punct(p) if p.as_char() == ';') {
            let head: TokenStream = format!("file = {file}, name = ")
                .parse()
                .expect("valid tokens");
            calls.push(head.into_iter().chain(entry.drain(..)).collect());
        } else {
            entry.push(t.clone());
        }
    }
}

/// The nearest folder above `path` with a `Cargo.toml`.
fn crate_root(path: &Path) -> PathBuf {
    path.ancestors()
        .skip(1)
        .find(|d| d.join("Cargo.toml").exists())
        .map_or_else(PathBuf::new, Path::to_path_buf)
}

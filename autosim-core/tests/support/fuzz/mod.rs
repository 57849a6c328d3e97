//! Seeded generators of model texts for the pipeline fuzzer, and the run of
//! one text through the whole compiler with panics caught.
//!
//! Shared by `examples/fuzz.rs` (long runs) and `tests/fuzz_pipeline.rs`
//! (a few hundred cases in CI) through `#[path]`. Four kinds of input:
//!
//! - [`Kind::Grammar`]: random models written with the grammar in mind —
//!   bodies with random parents (cycles, unknown ones), random options
//!   (quaternions, `small`, `lock`) with valid and invalid values,
//!   expressions over declared and undeclared names calling every operation
//!   with random arity and argument kinds, and every other item. A `chaos`
//!   percentage per model decides how many choices go wrong, so some models
//!   compile and reach the back end; chaotic ones sometimes get mutated too;
//! - [`Kind::Mutation`]: the example models with tokens or lines deleted,
//!   duplicated or swapped, numbers made huge, tiny, zero or negative, and
//!   identifiers renamed;
//! - [`Kind::Soup`]: raw bytes, random characters and keyword/punctuation soups;
//! - [`Kind::Deep`] (3%): one pathological shape — thousands of chained
//!   `let`s or points, nesting past the parser's limit, long flat sums,
//!   chains of up to 24 bodies, thousands of states.
//!
//! One case in five also gets use-site options (a [`Scene`]: name, float,
//! threshold, outputs, small, lock) naming things in the model or not.
//! Sizes stay small: a case takes milliseconds in a release build.

#![allow(dead_code)]
// Index loops over names and matrix entries read like what they build.
#![allow(clippy::needless_range_loop)]

use std::panic::{AssertUnwindSafe, catch_unwind};

use autosim_core::diag::SourceFile;
use autosim_core::emit::{EmitOptions, format_tokens, markdown, model_tokens};
use autosim_core::model::{FloatType, Scene};
use autosim_core::pipeline::{compile_source, compile_source_scene, compile_tokens};

mod grammar;
mod mutate;
mod shapes;
mod vocab;

use grammar::Grammar;
pub use mutate::mutate;
use mutate::{pieces, soup};
use shapes::deep;
use vocab::ODD_NAMES;

pub use autosim_test_support::Rng;

/// What a generated input is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A random model following the grammar (maybe mutated a little).
    Grammar,
    /// A mutated example model.
    Mutation,
    /// Bytes, characters or tokens at random.
    Soup,
    /// A model of one pathological shape: long chains of `let`s or points,
    /// deep nesting, long sums, many bodies.
    Deep,
}

/// The example models, mutated by [`Kind::Mutation`] (the large chains are
/// left out: their bodies are already in the smaller ones).
pub const EXAMPLES: &[(&str, &str)] = &[
    (
        "features",
        include_str!("../../../../examples/models/features.sim"),
    ),
    (
        "satellite",
        include_str!("../../../../examples/models/satellite.sim"),
    ),
    (
        "satellite_small",
        include_str!("../../../../examples/models/satellite_small.sim"),
    ),
    (
        "chain_planar_1",
        include_str!("../../../../examples/models/chain_planar_1.sim"),
    ),
    (
        "chain_planar_2",
        include_str!("../../../../examples/models/chain_planar_2.sim"),
    ),
    (
        "chain_planar_2_f32",
        include_str!("../../../../examples/models/chain_planar_2_f32.sim"),
    ),
    (
        "chain_planar_3",
        include_str!("../../../../examples/models/chain_planar_3.sim"),
    ),
    (
        "chain_spatial_1",
        include_str!("../../../../examples/models/chain_spatial_1.sim"),
    ),
    (
        "chain_spatial_2",
        include_str!("../../../../examples/models/chain_spatial_2.sim"),
    ),
    (
        "chain_spatial_3",
        include_str!("../../../../examples/models/chain_spatial_3.sim"),
    ),
    (
        "chain_spatial_3_stiff",
        include_str!("../../../../examples/models/chain_spatial_3_stiff.sim"),
    ),
];

/// Case `case` of the run seeded with `seed`: its kind and text.
/// One generated input.
#[derive(Clone, Debug)]
pub struct Case {
    /// How it was made.
    pub kind: Kind,
    /// The model text.
    pub text: String,
    /// Options of a use site (as the macro or a build script gives them),
    /// for one case in five.
    pub scene: Option<Scene>,
}

/// Case `case` of the run seeded with `seed`.
pub fn generate(seed: u64, case: u64) -> Case {
    let mut rng = Rng::for_case(seed, case);
    let (kind, text) = generate_text(&mut rng);
    let scene = rng.chance(20).then(|| scene(&mut rng, &text));
    Case { kind, text, scene }
}

fn generate_text(rng: &mut Rng) -> (Kind, String) {
    if rng.chance(3) {
        return (Kind::Deep, deep(rng));
    }
    match rng.below(10) {
        0..=4 => {
            let grammar = Grammar::new(rng);
            let chaotic = grammar.chaos > 0;
            let mut text = grammar.model();
            if chaotic && rng.chance(20) {
                text = mutate(rng, &text);
            }
            (Kind::Grammar, text)
        }
        5..=7 => {
            let base = rng.pick(EXAMPLES).1;
            (Kind::Mutation, mutate(rng, base))
        }
        _ => (Kind::Soup, soup(rng)),
    }
}

/// Scene options naming things of the model (bodies, coordinates,
/// outputs) or not, with thresholds in and out of range.
fn scene(rng: &mut Rng, text: &str) -> Scene {
    let mut idents: Vec<&str> = pieces(text)
        .into_iter()
        .filter(|p| p.starts_with(|c: char| c.is_alphabetic() || c == '_'))
        .collect();
    idents.extend(ODD_NAMES);
    let names = |rng: &mut Rng| -> Vec<_> {
        (0..rng.range(0, 3))
            .map(|_| Scene::name(rng.pick::<&str>(&idents)))
            .collect()
    };
    let mut scene = Scene::default();
    if rng.chance(20) {
        scene.name =
            Some(Scene::name(rng.pick::<&str>(&[
                "Renamed", "M2", "fn", "N", "é", "Model", "a_b",
            ])));
    }
    if rng.chance(30) {
        scene.float = Some(*rng.pick(&[FloatType::F32, FloatType::F64]));
    }
    if rng.chance(20) {
        scene.threshold = Some(*rng.pick(&[-5, 0, 1, 2, 3, 20, 21, 1000, i16::MAX, i16::MIN]));
    }
    if rng.chance(20) {
        scene.outputs = Some(names(rng));
    }
    if rng.chance(40) {
        scene.small = names(rng);
    }
    if rng.chance(40) {
        scene.lock = names(rng);
    }
    scene
}

// ---------------------------------------------------------------------------
// Running a case.

/// How the compiler answered one input.
#[derive(Debug)]
pub enum Outcome {
    /// Compiled, emitted and formatted.
    Ok,
    /// Rejected with this many diagnostics (rendered without panicking).
    Diagnostics(usize),
    /// Generated tokens that do not parse as a Rust file.
    BadEmit(String),
    /// A panic, with its message and location.
    Panic(String),
}

thread_local! {
    static LAST_PANIC: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Replaces the panic hook with one that records the message and location
/// for [`run`] instead of printing it (`std::panic::take_hook` restores
/// the default).
pub fn silence_panics() {
    std::panic::set_hook(Box::new(|info| {
        let message = info.to_string();
        LAST_PANIC.with(|p| *p.borrow_mut() = Some(message));
    }));
}

/// Runs `text` through the whole pipeline (parse, resolve, equations,
/// program, tokens, formatting, Markdown; with `tokens_too`, also the
/// macro's Rust-token front end when the text lexes), catching panics.
pub fn run(case: &Case, tokens_too: bool) -> Outcome {
    LAST_PANIC.with(|p| p.borrow_mut().take());
    // The compiler keeps no span past a compile; without this, the lexer's
    // per-thread source map grows with every case (about 15 kB each).
    proc_macro2::extra::invalidate_current_thread_spans();
    match catch_unwind(AssertUnwindSafe(|| run_unguarded(case, tokens_too))) {
        Ok(outcome) => outcome,
        Err(payload) => {
            let message = LAST_PANIC
                .with(|p| p.borrow_mut().take())
                .unwrap_or_else(|| {
                    payload
                        .downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| payload.downcast_ref::<String>().cloned())
                        .unwrap_or_else(|| "panic".to_string())
                });
            Outcome::Panic(message)
        }
    }
}

/// The formatted Rust of a case that compiles (for checking generated code
/// with rustc), or `None`.
pub fn generated_code(case: &Case) -> Option<String> {
    let file = SourceFile::new("fuzz.sim", case.text.as_str());
    let compiled = match &case.scene {
        Some(scene) => compile_source_scene(&file, scene),
        None => compile_source(&file),
    };
    let compiled = compiled.ok()?;
    Some(format_tokens(&model_tokens(
        &compiled.program,
        &EmitOptions::default(),
    )))
}

fn run_unguarded(case: &Case, tokens_too: bool) -> Outcome {
    let text = case.text.as_str();
    let file = SourceFile::new("fuzz.sim", text);
    let compiled = match &case.scene {
        Some(scene) => compile_source_scene(&file, scene),
        None => compile_source(&file),
    };
    let outcome = match compiled {
        Ok(compiled) => {
            let tokens = model_tokens(&compiled.program, &EmitOptions::default());
            let formatted = format_tokens(&tokens);
            let _ = markdown(&compiled.program, "fuzz.sim");
            match syn::parse2::<syn::File>(tokens) {
                Ok(_) => Outcome::Ok,
                Err(e) => Outcome::BadEmit(format!(
                    "{e}: {}",
                    formatted.chars().take(2000).collect::<String>()
                )),
            }
        }
        Err(diags) => {
            let rendered = diags.render(&file);
            assert!(!diags.is_empty(), "an error without diagnostics");
            assert!(!rendered.is_empty(), "diagnostics rendered as nothing");
            Outcome::Diagnostics(diags.len())
        }
    };
    // The token front end (the macro's) on the same text, when it lexes.
    if let Some(Ok(tokens)) = tokens_too.then(|| text.parse::<proc_macro2::TokenStream>()) {
        match compile_tokens(tokens) {
            Ok(compiled) => {
                let _ = model_tokens(&compiled.program, &EmitOptions::default());
            }
            Err(diags) => {
                let _ = diags.to_syn_error();
            }
        }
    }
    outcome
}

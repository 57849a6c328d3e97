//! Compiling a model's text and reading its outputs through the
//! interpreter.

use autosim_core::diag::SourceFile;
use autosim_core::opt::{At, Interpreter, Quantity, UserCalls};
use autosim_core::pipeline::{Compiled, compile_source};

/// The compiled program of `text` (panics with the rendered diagnostics).
pub fn compile_text(name: &str, text: &str) -> Compiled {
    let file = SourceFile::new(name, text.to_string());
    match compile_source(&file) {
        Ok(c) => c,
        Err(d) => panic!("{}", d.render(&file)),
    }
}

/// The text of `examples/models/<file>`.
pub fn model_text(file: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/models")
        .join(file);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The names of `c`'s outputs, in order.
pub fn output_names(c: &Compiled) -> Vec<String> {
    c.program
        .interface
        .model
        .outputs
        .iter()
        .map(|o| o.name.clone())
        .collect()
}

/// The outputs of `c` at state `x` (default parameters, no user code).
pub fn outputs_at(c: &Compiled, x: &[f64], t: f64) -> Vec<f64> {
    outputs_with(c, &parameter_values(c, |p| p.default), x, t)
}

/// The value `value` gives each of `c`'s parameters, in declaration order.
pub fn parameter_values(c: &Compiled, value: impl Fn(&Quantity) -> f64) -> Vec<f64> {
    let parameters = &c.program.interface.model.parameters;
    parameters.iter().map(value).collect()
}

/// The outputs of `c` at state `x` with these parameters (user functions
/// return 0, subroutines nothing).
pub fn outputs_with(c: &Compiled, params: &[f64], x: &[f64], t: f64) -> Vec<f64> {
    let mut function = |_f: usize, _a: &[f64]| 0.0;
    let mut subroutine = |_s: usize, _a: &[f64]| Vec::new();
    let mut user = UserCalls {
        function: &mut function,
        subroutine: &mut subroutine,
    };
    outputs_calling(c, params, x, t, &mut user)
}

/// The outputs of `c` at state `x` with these parameters and user code.
pub fn outputs_calling(
    c: &Compiled,
    params: &[f64],
    x: &[f64],
    t: f64,
    user: &mut UserCalls<'_>,
) -> Vec<f64> {
    let it = Interpreter::new(&c.program, params);
    let at = At {
        t,
        x,
        inputs: &[],
        discrete: &[],
    };
    it.outputs(at, user).expect("outputs")
}

/// `|a − b| ≤ tol (1 + |b|)`.
pub fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

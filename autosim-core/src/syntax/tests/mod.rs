//! Data-driven tests of the front end.

mod errors;
mod errors_lex;
mod events;
mod expr;
mod fuzz;
mod satellite;

use super::{ast, parse_source};
use crate::diag::SourceFile;

/// Parses `text` as the file `test.sim`: the model, or the rendered diagnostics.
pub(super) fn parse_file(text: &str) -> Result<ast::Model, String> {
    parse_source(&SourceFile::new("test.sim", text))
        .map_err(|diags| diags.render(&SourceFile::new("test.sim", text)))
}

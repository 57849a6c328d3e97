//! What the model checks share: compiling an example model through the
//! core, for the symbolic side of a differential test.

use autosim_core::diag::SourceFile;
use autosim_core::pipeline::{Compiled, compile_source};

/// The example model `file` (in `examples/models`), compiled.
pub fn compile(file: &str) -> Compiled {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/models")
        .join(file);
    let text = std::fs::read_to_string(&path).expect("model file");
    let src = SourceFile::new(file, text);
    compile_source(&src).unwrap_or_else(|d| panic!("{}", d.render(&src)))
}

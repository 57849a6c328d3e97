//! The `model!` procedural macro of autosim. A thin shell: all the work is in
//! `autosim-core`.

use proc_macro::TokenStream;

/// Compiles a model description into Rust (see the `autosim` crate docs).
#[proc_macro]
pub fn model(input: TokenStream) -> TokenStream {
    let _ = input;
    TokenStream::new()
}

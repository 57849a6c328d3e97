//! What the macro emits beside the errors of a model that does not
//! compile: a module with the model's item names, so one mistake does not
//! bury the user in follow-on errors at their own correct code.
//!
//! The module's items are written in terms of an *error type*: the first
//! of the model's errors is a `compile_error!` in an array length, and a
//! projection from that array is a type the compiler knows is in error.
//! rustc reports nothing further about code that uses such a type (a call
//! of `new`, a field, a struct literal, a trait bound, a method signature
//! that differs), so the user sees the model's errors and only those.

use super::expr::ident;
use super::model::snake_case;
use crate::syntax::{Parsed, ast};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// What the placeholder needs of a model that did not compile: the name
/// its module and type take, and the user code it declares (the methods
/// of its `Externs` trait), as far as the model could be read.
#[derive(Clone, Debug, PartialEq)]
pub struct Outline {
    /// The model's name (the scene's `name` if it renames it).
    pub name: String,
    /// Each `extern fn` and `extern sub`: its name and its arity.
    pub user_code: Vec<(String, usize)>,
}

impl Outline {
    /// The outline of what could be parsed, named `name` (`None` without
    /// a name, when no placeholder can be made).
    pub fn of(parsed: &Parsed, name: Option<&str>) -> Option<Outline> {
        let name = name?.to_string();
        let items = parsed.model.iter().flat_map(|m| &m.items);
        let user_code = items
            .filter_map(|item| match item {
                ast::Item::ExternFn(f) => Some((f.name.text.clone(), f.params.len())),
                ast::Item::ExternSub(s) => Some((s.name.text.clone(), s.args.len())),
                _ => None,
            })
            .collect();
        Some(Outline { name, user_code })
    }
}

/// The hidden name of the error type inside the placeholder module.
const ERROR_TYPE: &str = "__AutosimModelHasErrors";

/// The placeholder module of a model, with `first_error` (one
/// `compile_error!` invocation, the model's first error) inside it. The
/// module is named as the generated code names it (a keyword module name
/// such as `mod` gets a `_`).
pub fn placeholder(outline: &Outline, first_error: TokenStream) -> TokenStream {
    let name = outline.name.as_str();
    let module = ident(&snake_case(name));
    let ty = ident(name);
    let error = format_ident!("{ERROR_TYPE}");
    // A model named like one of the other items (an error the resolver
    // reports) must not make them clash.
    let named = |item: &str| (name != item).then_some(ident(item));
    let parameters = named("Parameters").map(|p| quote!(pub type #p = #error;));
    let inputs = named("Inputs").map(|i| quote!(pub type #i = #error;));
    let externs = named("Externs").map(|trait_name| {
        let methods = outline.user_code.iter().map(|(method, arity)| {
            let method = ident(method);
            let args = (0..*arity).map(|k| format_ident!("a{k}"));
            quote!(fn #method(&mut self, #(#args: #error),*) -> #error;)
        });
        quote!(pub trait #trait_name { #(#methods)* })
    });
    let counts = ["N_STATES", "N_SPEEDS", "N_INPUTS", "N_OUTPUTS"].map(|c| format_ident!("{c}"));
    quote! {
        #[allow(dead_code, non_snake_case, non_camel_case_types, clippy::all)]
        pub mod #module {
            type #error = <[(); #first_error] as ::core::ops::Deref>::Target;
            /// Placeholder: the model has errors.
            pub type #ty<E = ()> = (#error, ::core::marker::PhantomData<E>);
            #parameters
            #inputs
            #externs
            #(pub const #counts: usize = <#error>::VALUE;)*
            pub const FINGERPRINT: u64 = <#error>::VALUE;
        }
    }
}

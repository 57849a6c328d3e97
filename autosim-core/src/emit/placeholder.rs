//! What the macro emits beside the errors of a model that does not
//! compile: a module with the model's type names, so one mistake does not
//! bury the user in follow-on errors about missing items.

use super::expr::ident;
use super::model::snake_case;
use proc_macro2::TokenStream;
use quote::quote;

/// The placeholder module of a model named `name` (as the generated code
/// names it: a keyword module name such as `mod` gets a `_`).
pub fn placeholder(name: &str) -> TokenStream {
    let module = ident(&snake_case(name));
    let ty = ident(name);
    // A model named like one of the other items (an error the resolver
    // reports) must not make them clash.
    let parameters = (name != "Parameters").then(|| {
        quote! {
            /// Placeholder: the model has errors.
            #[derive(Default)]
            pub struct Parameters;
        }
    });
    let inputs = (name != "Inputs").then(|| {
        quote! {
            /// Placeholder: the model has errors.
            #[derive(Default)]
            pub struct Inputs;
        }
    });
    let externs = (name != "Externs").then(|| {
        quote! {
            /// Placeholder: the model has errors.
            pub trait Externs {}
        }
    });
    quote! {
        #[allow(dead_code, non_snake_case)]
        pub mod #module {
            /// Placeholder: the model has errors.
            pub struct #ty<E = ()>(pub E);
            #parameters
            #inputs
            #externs
        }
    }
}

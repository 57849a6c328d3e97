//! The generated module's data types: `Parameters` and `Inputs` (fields
//! with docs, units and defaults) and the `Externs` trait of user code.

use super::{doc, docs};
use crate::emit::expr::{float_type, ident, literal};
use crate::opt::FloatType;
use crate::opt::{Interface, Quantity};
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// A struct of values with their defaults (`Parameters`, `Inputs`): one
/// documented field per quantity, and `Default` (derived when every
/// default is zero, which clippy prefers).
pub(super) fn values_struct(
    name: &str,
    struct_doc: TokenStream,
    quantities: &[Quantity],
    float: FloatType,
) -> TokenStream {
    let ty = float_type(float);
    let mut fields = Vec::with_capacity(quantities.len());
    let mut defaults = Vec::with_capacity(quantities.len());
    for q in quantities {
        let id = ident(&q.name);
        let mut d =
            docs(&q.docs.clone().unwrap_or_else(|| {
                vec![format!("{} (default mass or inertia of a body).", q.name)]
            }));
        let unit = match (q.unit.as_str(), q.inferred_unit.as_str()) {
            ("", "") => String::new(),
            ("", inferred) => format!(" \\[{inferred}, inferred\\]"),
            (unit, _) => format!(" \\[{unit}\\]"),
        };
        d.extend(doc(&format!("Default: `{:?}`{unit}.", q.default)));
        let lit = literal(q.default, float);
        fields.push(quote!(#d pub #id: #ty));
        defaults.push(quote!(#id: #lit));
    }
    let ty_name = ident(name);
    let (derive_default, default_impl) = if quantities.iter().all(|q| q.default == 0.0) {
        (quote!(, Default), quote!())
    } else {
        (
            quote!(),
            quote! {
                impl Default for #ty_name {
                    fn default() -> Self {
                        #ty_name { #(#defaults,)* }
                    }
                }
            },
        )
    };
    quote! {
        #struct_doc
        #[derive(Clone, Copy, Debug, PartialEq #derive_default)]
        pub struct #ty_name {
            #(#fields,)*
        }

        #default_impl
    }
}

/// `Parameters` and its `Default`.
pub(super) fn parameters(i: &Interface) -> TokenStream {
    let doc = quote!(#[doc = r" Parameters of the model, with their defaults."]);
    values_struct("Parameters", doc, &i.model.parameters, i.float)
}

/// `Inputs` and its `Default`.
pub(super) fn inputs(i: &Interface) -> TokenStream {
    let doc = quote!(#[doc = r" Inputs of the model, supplied by the caller at run time."]);
    values_struct("Inputs", doc, &i.model.inputs, i.float)
}

/// The `Externs` trait: one method per user function and subroutine
/// (nothing if the model calls no user code).
pub(super) fn externs_trait(i: &Interface) -> TokenStream {
    if !i.has_externs() {
        return quote!();
    }
    let ty = float_type(i.float);
    let params = |names: &[String]| -> Vec<TokenStream> {
        names
            .iter()
            .map(|p| {
                let p = ident(p);
                quote!(#p: #ty)
            })
            .collect()
    };
    let mut methods = Vec::new();
    for f in &i.model.extern_fns {
        let id = ident(&f.name);
        let ps = params(&f.params);
        let d = docs(&f.docs);
        methods.push(quote!(#d fn #id(&mut self, #(#ps),*) -> #ty;));
    }
    for s in &i.model.subroutines {
        let id = ident(&s.name);
        let ps = params(&s.params);
        let mut d = docs(&s.docs);
        d.extend(doc(&format!("Returns `[{}]`.", s.outputs.join(", "))));
        let k_out = Literal::usize_unsuffixed(s.outputs.len());
        methods.push(quote!(#d fn #id(&mut self, #(#ps),*) -> [#ty; #k_out];));
    }
    quote! {
        /// The user code this model calls: implement it and pass it to
        /// the model's `new`. Called with static dispatch.
        pub trait Externs {
            #(#methods)*
        }
    }
}

//! The generated module's data types: `Parameters` and `Inputs` (fields
//! with docs, units and defaults) and the `Externs` trait of user code.

use super::{doc, docs};
use crate::emit::expr::{float_type, ident, literal};
use crate::model::FloatType;
use crate::opt::Interface;
use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// A field of `Parameters` or `Inputs`.
struct Field<'a> {
    name: &'a str,
    unit: &'a str,
    default: f64,
    docs: Vec<String>,
}

/// The fields, the struct's `Default` (derived when every default is zero,
/// which clippy prefers) and the field list of a struct literal.
struct StructParts {
    fields: Vec<TokenStream>,
    derive_default: TokenStream,
    default_impl: TokenStream,
}

fn struct_parts(type_name: &str, fields: &[Field<'_>], float: FloatType) -> StructParts {
    let ty = float_type(float);
    let mut out = Vec::with_capacity(fields.len());
    let mut defaults = Vec::with_capacity(fields.len());
    for f in fields {
        let id = ident(f.name);
        let mut d = docs(&f.docs);
        let unit = if f.unit.is_empty() {
            String::new()
        } else {
            format!(" [{}]", f.unit)
        };
        d.extend(doc(&format!("Default: `{:?}`{unit}.", f.default)));
        let lit = literal(f.default, float);
        out.push(quote!(#d pub #id: #ty));
        defaults.push(quote!(#id: #lit));
    }
    let ty_name = ident(type_name);
    if fields.iter().all(|f| f.default == 0.0) {
        StructParts {
            fields: out,
            derive_default: quote!(, Default),
            default_impl: quote!(),
        }
    } else {
        StructParts {
            fields: out,
            derive_default: quote!(),
            default_impl: quote! {
                impl Default for #ty_name {
                    fn default() -> Self {
                        #ty_name { #(#defaults,)* }
                    }
                }
            },
        }
    }
}

/// `Parameters` and its `Default`.
pub(super) fn parameters(i: &Interface) -> TokenStream {
    let fields: Vec<Field<'_>> = i
        .parameters
        .iter()
        .map(|p| Field {
            name: &p.name,
            unit: &p.unit,
            default: p.default,
            docs: p.docs.clone().unwrap_or_else(|| {
                vec![format!("{} (default mass or inertia of a body).", p.name)]
            }),
        })
        .collect();
    let StructParts {
        fields,
        derive_default,
        default_impl,
    } = struct_parts("Parameters", &fields, i.float);
    quote! {
        /// Parameters of the model, with their defaults.
        #[derive(Clone, Copy, Debug, PartialEq #derive_default)]
        pub struct Parameters {
            #(#fields,)*
        }

        #default_impl
    }
}

/// `Inputs` and its `Default`.
pub(super) fn inputs(i: &Interface) -> TokenStream {
    let fields: Vec<Field<'_>> = i
        .inputs
        .iter()
        .map(|x| Field {
            name: &x.name,
            unit: &x.unit,
            default: x.default,
            docs: x.docs.clone(),
        })
        .collect();
    let StructParts {
        fields,
        derive_default,
        default_impl,
    } = struct_parts("Inputs", &fields, i.float);
    quote! {
        /// Inputs of the model, supplied by the caller at run time.
        #[derive(Clone, Copy, Debug, PartialEq #derive_default)]
        pub struct Inputs {
            #(#fields,)*
        }

        #default_impl
    }
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
    for f in &i.extern_fns {
        let id = ident(&f.name);
        let ps = params(&f.params);
        let d = docs(&f.docs);
        methods.push(quote!(#d fn #id(&mut self, #(#ps),*) -> #ty;));
    }
    for s in &i.subroutines {
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

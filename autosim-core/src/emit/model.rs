//! The generated module of a model: parameters, inputs, the user-code
//! trait, the model type with its `Model` implementation, and the
//! operation counts.

use super::block::{BlockEmitter, Target};
use super::expr::{Locals, float_type, ident, literal};
use crate::model::{FloatType, ItemDoc};
use crate::opt::{Block, Leaf, Ops, Program};
use crate::pipeline::Compiled;
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use rustc_hash::FxHashMap;

/// How generated code is written.
#[derive(Clone, Debug)]
pub struct EmitOptions {
    /// Path of the runtime crate in generated code (default
    /// `::autosim::runtime`).
    pub runtime_path: String,
    /// Name of the generated module (default: the model name in snake case).
    pub module_name: Option<String>,
}

impl Default for EmitOptions {
    fn default() -> Self {
        EmitOptions {
            runtime_path: "::autosim::runtime".to_string(),
            module_name: None,
        }
    }
}

/// `CamelCase` → `snake_case`.
pub fn snake_case(name: &str) -> String {
    let mut out = String::new();
    let chars: Vec<char> = name.chars().collect();
    for (i, c) in chars.iter().enumerate() {
        if c.is_uppercase() {
            let prev_lower =
                i > 0 && (chars[i - 1].is_lowercase() || chars[i - 1].is_ascii_digit());
            let next_lower = chars.get(i + 1).is_some_and(|n| n.is_lowercase());
            if i > 0 && (prev_lower || (next_lower && chars[i - 1].is_uppercase())) {
                out.push('_');
            }
            out.extend(c.to_lowercase());
        } else {
            out.push(*c);
        }
    }
    out
}

fn docs(lines: &[String]) -> TokenStream {
    let mut out = TokenStream::new();
    for l in lines {
        let text = if l.starts_with(' ') {
            l.clone()
        } else {
            format!(" {l}")
        };
        out.extend(quote!(#[doc = #text]));
    }
    out
}

fn doc(text: &str) -> TokenStream {
    let text = format!(" {text}");
    quote!(#[doc = #text])
}

fn ops_tokens(rt: &TokenStream, o: &Ops) -> TokenStream {
    let [a, m, d, f, u] =
        [o.adds, o.muls, o.divs, o.funcs, o.user_calls].map(Literal::usize_unsuffixed);
    quote!(#rt::OpCount { adds: #a, muls: #m, divs: #d, funcs: #f, user_calls: #u })
}

fn unit_of(docs: &[ItemDoc], name: &str) -> String {
    docs.iter()
        .find(|d| d.name == name)
        .and_then(|d| d.unit.clone())
        .unwrap_or_default()
}

/// The whole generated module.
pub fn model_tokens(c: &Compiled, options: &EmitOptions) -> TokenStream {
    let prog = &c.program;
    let model = &c.model;
    let sys = &model.system;
    let float = model.float;
    let ty = float_type(float);
    let rt: TokenStream = options
        .runtime_path
        .parse()
        .unwrap_or_else(|_| quote!(::autosim::runtime));
    let math = quote!(math);
    let name = sys.name().to_string();
    let model_ty = ident(&name);
    let module = ident(
        &options
            .module_name
            .clone()
            .unwrap_or_else(|| snake_case(&name)),
    );
    let n = prog.n;
    let n_states = 2 * n + prog.n_extra;
    let n_out = prog.output_names.len();
    let n_states_lit = Literal::usize_unsuffixed(n_states);
    let n_lit = Literal::usize_unsuffixed(n);
    let n_out_lit = Literal::usize_unsuffixed(n_out);
    let has_externs = !prog.user_fn_names.is_empty() || !prog.subroutines.is_empty();

    let constant_slot: FxHashMap<_, _> = prog
        .hoisted
        .iter()
        .enumerate()
        .map(|(k, n)| (*n, k))
        .collect();
    let locals = Locals::new(prog);
    let be = BlockEmitter {
        prog,
        float,
        constant_slot: &constant_slot,
        math: math.clone(),
        rt: rt.clone(),
        locals: &locals,
    };
    let Locals {
        x: lx,
        dx: ldx,
        y: ly,
        p: lp,
        m: lm,
        f: lf,
        x0: lx0,
        ..
    } = &locals;

    // Parameters.
    let param_syms = sys.parameters();
    let mut p_fields = Vec::new();
    let mut p_defaults = Vec::new();
    let mut p_units = Vec::new();
    let mut p_get = Vec::new();
    let mut p_set = Vec::new();
    for (i, s) in param_syms.iter().enumerate() {
        let sym = sys.arena.symbol(*s);
        let id = ident(&sym.name);
        let default = match sym.kind {
            crate::expr::SymbolKind::Parameter { default } => default,
            _ => 0.0,
        };
        let unit = sym.unit.clone().unwrap_or_default();
        let user_doc = model
            .parameter_docs
            .iter()
            .find(|d| d.name == sym.name)
            .map(|d| d.docs.clone())
            .unwrap_or_else(|| vec![format!("{} (default mass or inertia of a body).", sym.name)]);
        let mut d = docs(&user_doc);
        let unit_text = if unit.is_empty() {
            String::new()
        } else {
            format!(" [{unit}]")
        };
        d.extend(doc(&format!("Default: `{default:?}`{unit_text}.")));
        let lit = literal(default, float);
        p_fields.push(quote!(#d pub #id: #ty));
        p_defaults.push(quote!(#id: #lit));
        p_units.push(unit);
        let k = Literal::usize_unsuffixed(i);
        p_get.push(quote!(#k => #lp.#id,));
        p_set.push(quote!(#k => #lp.#id = *v,));
    }
    let p_names: Vec<&String> = prog.parameter_names.iter().collect();
    let params_zero = param_syms.iter().all(|s| {
        matches!(sys.arena.symbol(*s).kind, crate::expr::SymbolKind::Parameter { default } if default == 0.0)
    });
    let (params_derive_default, params_default_impl) = if params_zero {
        (quote!(, Default), quote!())
    } else {
        (
            quote!(),
            quote! {
                impl Default for Parameters {
                    fn default() -> Self {
                        Parameters { #(#p_defaults,)* }
                    }
                }
            },
        )
    };
    let (p_get_body, p_set_body) = if p_get.is_empty() {
        (quote!(let _ = values;), quote!(let _ = values;))
    } else {
        (
            quote! {
                let #lp = &self.parameters;
                for (k, v) in values.iter_mut().enumerate() {
                    *v = match k {
                        #(#p_get)*
                        _ => *v,
                    };
                }
            },
            quote! {
                let mut #lp = self.parameters;
                for (k, v) in values.iter().enumerate() {
                    match k {
                        #(#p_set)*
                        _ => {}
                    }
                }
                self.set_parameters(#lp);
            },
        )
    };

    // Inputs.
    let mut i_fields = Vec::new();
    let mut i_defaults = Vec::new();
    let mut i_units = Vec::new();
    for s in sys.inputs() {
        let sym = sys.arena.symbol(*s);
        let id = ident(&sym.name);
        let default = match sym.kind {
            crate::expr::SymbolKind::Input { default } => default,
            _ => 0.0,
        };
        let unit = sym.unit.clone().unwrap_or_default();
        let mut d = docs(
            &model
                .input_docs
                .iter()
                .find(|x| x.name == sym.name)
                .map(|x| x.docs.clone())
                .unwrap_or_default(),
        );
        d.extend(doc(&format!(
            "Default: `{default:?}`{}.",
            if unit.is_empty() {
                String::new()
            } else {
                format!(" [{unit}]")
            }
        )));
        let lit = literal(default, float);
        i_fields.push(quote!(#d pub #id: #ty));
        i_defaults.push(quote!(#id: #lit));
        i_units.push(unit);
    }
    let i_names: Vec<&String> = prog.input_names.iter().collect();
    // All-zero defaults are what `derive(Default)` gives (clippy prefers it).
    let inputs_zero = sys.inputs().iter().all(|s| {
        matches!(sys.arena.symbol(*s).kind, crate::expr::SymbolKind::Input { default } if default == 0.0)
    });
    let (inputs_derive_default, inputs_default_impl) = if inputs_zero {
        (quote!(, Default), quote!())
    } else {
        (
            quote!(),
            quote! {
                impl Default for Inputs {
                    fn default() -> Self {
                        Inputs { #(#i_defaults,)* }
                    }
                }
            },
        )
    };

    // User code.
    let mut trait_fns = Vec::new();
    for f in &model.extern_fns {
        let id = ident(&f.name);
        let params: Vec<_> = f
            .params
            .iter()
            .map(|p| {
                let p = ident(p);
                quote!(#p: #ty)
            })
            .collect();
        let d = docs(&f.docs);
        trait_fns.push(quote!(#d fn #id(&mut self, #(#params),*) -> #ty;));
    }
    for (k, (sname, outs)) in prog.subroutines.iter().enumerate() {
        let id = ident(sname);
        let params: Vec<_> = model
            .subroutine_params
            .get(k)
            .cloned()
            .unwrap_or_default()
            .iter()
            .map(|p| {
                let p = ident(p);
                quote!(#p: #ty)
            })
            .collect();
        let mut d = docs(
            model
                .subroutine_docs
                .get(k)
                .map(Vec::as_slice)
                .unwrap_or(&[]),
        );
        d.extend(doc(&format!("Returns `[{}]`.", outs.join(", "))));
        let k_out = Literal::usize_unsuffixed(outs.len());
        trait_fns.push(quote!(#d fn #id(&mut self, #(#params),*) -> [#ty; #k_out];));
    }

    // Constants.
    let c_fields: Vec<_> = (0..prog.hoisted.len())
        .map(|k| {
            let id = format_ident!("p{}", k + 1);
            quote!(#id: #ty)
        })
        .collect();
    let c_body = be.emit(&prog.constants, false, Target::ConstantFields);
    let c_uses_p = prog
        .constants
        .leaves
        .iter()
        .any(|l| matches!(l, Leaf::Param(_)));
    let c_param = if c_uses_p {
        quote!(parameters)
    } else {
        quote!(_parameters)
    };
    let c_body = if c_uses_p {
        let inner = c_body;
        quote!(let #lp = parameters; #inner)
    } else {
        c_body
    };

    // Blocks.
    let deriv = block_fn_body(&be, &prog.derivatives, Target::Array(ldx));
    let mm = block_fn_body(&be, &prog.mass_matrix, Target::Matrix(lm, n.max(1)));
    let fo = block_fn_body(&be, &prog.forcing, Target::Array(lf));
    let outs_body = {
        let body = block_fn_body(&be, &prog.outputs, Target::Array(ly));
        if prog.outputs_need_derivatives {
            quote! {
                let mut #ldx = [0.0; #n_states_lit];
                <Self as #rt::Model>::derivatives(self, t, #lx, &mut #ldx)?;
                #body
            }
        } else {
            body
        }
    };
    let init = {
        let mut nonzero = prog.initial.clone();
        nonzero.stmts.retain(|st| match st {
            crate::opt::Stmt::Store { value, .. } => prog.ir.as_num(*value) != Some(0.0),
            _ => true,
        });
        if nonzero
            .stmts
            .iter()
            .any(|st| matches!(st, crate::opt::Stmt::Store { .. }))
        {
            let body = be.emit(&nonzero, false, Target::Array(lx0));
            quote!(let mut #lx0 = [0.0; #n_states_lit]; #body #lx0)
        } else {
            quote!([0.0; #n_states_lit])
        }
    };
    let t_arg = |b: &Block| if uses_time(b) { quote!(t) } else { quote!(_) };
    let reads_state = |b: &Block| b.leaves.iter().any(|l| matches!(l, Leaf::State(_)));
    let x_arg = |b: &Block| {
        if reads_state(b) {
            quote!(#lx)
        } else {
            quote!(_)
        }
    };
    let (dt, dxx) = (t_arg(&prog.derivatives), x_arg(&prog.derivatives));
    let need = prog.outputs_need_derivatives;
    let out_t = if uses_time(&prog.outputs) || need {
        quote!(t)
    } else {
        quote!(_)
    };
    let out_x = if reads_state(&prog.outputs) || need {
        quote!(#lx)
    } else {
        quote!(_)
    };
    let out_y = if n_out == 0 { quote!(_) } else { quote!(#ly) };
    // A model without states writes no derivative (an unused `dx` warned).
    let d_arg = if n_states == 0 {
        quote!(_)
    } else {
        quote!(#ldx)
    };
    let (mt, mx) = (t_arg(&prog.mass_matrix), x_arg(&prog.mass_matrix));
    let (ft, fx) = (t_arg(&prog.forcing), x_arg(&prog.forcing));
    let m_arg = if n == 0 { quote!(_) } else { quote!(#lm) };
    let f_arg = if n == 0 { quote!(_) } else { quote!(#lf) };

    let state_names = &prog.state_names;
    let state_units = &prog.state_units;
    let out_names = &prog.output_names;
    let out_units: Vec<String> = prog
        .output_names
        .iter()
        .map(|o| unit_of(&model.output_docs, o))
        .collect();

    let d_ops = ops_tokens(&rt, &prog.derivatives.ops);
    let o_ops = ops_tokens(&rt, &prog.outputs.ops);
    let c_ops = ops_tokens(&rt, &prog.constants.ops);
    let m_ops = ops_tokens(&rt, &prog.mass_matrix.ops);
    let f_ops = ops_tokens(&rt, &prog.forcing.ops);

    let model_docs = {
        let mut lines = model.docs.clone();
        if !lines.is_empty() {
            lines.push(String::new());
        }
        lines.push(format!(
            "Generated by autosim from model `{name}`: {n} degree{} of freedom, {n_states} states.",
            if n == 1 { "" } else { "s" }
        ));
        lines.push(String::new());
        lines.push(format!(
            "Cost of one `derivatives` call: {}.",
            prog.derivatives.ops
        ));
        lines.push(format!("Cost of one `outputs` call: {}.", prog.outputs.ops));
        lines.push(format!(
            "Cost of a parameter change (constants): {}.",
            prog.constants.ops
        ));
        lines.push(String::new());
        lines.push("| state | unit |".to_string());
        lines.push("| --- | --- |".to_string());
        for (s, u) in state_names.iter().zip(state_units) {
            lines.push(format!("| `{s}` | {u} |"));
        }
        docs(&lines)
    };

    let (generics, bound, externs_field, new_fn, struct_generics) = if has_externs {
        (
            quote!(<E: Externs>),
            quote!(E: Externs),
            quote!(
                /// The user code the model calls.
                pub externs: E,
            ),
            quote! {
                /// The model with default parameters and inputs, calling `externs`.
                pub fn new(externs: E) -> Self {
                    Self::with_parameters(Parameters::default(), externs)
                }
                /// The model with the given parameters, calling `externs`.
                pub fn with_parameters(parameters: Parameters, externs: E) -> Self {
                    #model_ty { constants: Constants::new(&parameters), parameters, inputs: Inputs::default(), externs }
                }
            },
            quote!(<E>),
        )
    } else {
        (
            quote!(),
            quote!(),
            quote!(),
            quote! {
                /// The model with default parameters and inputs.
                pub fn new() -> Self {
                    Self::with_parameters(Parameters::default())
                }
                /// The model with the given parameters.
                pub fn with_parameters(parameters: Parameters) -> Self {
                    #model_ty { constants: Constants::new(&parameters), parameters, inputs: Inputs::default() }
                }
            },
            quote!(),
        )
    };
    let default_impl = if has_externs {
        quote!()
    } else {
        quote! {
            impl Default for #model_ty {
                fn default() -> Self {
                    Self::new()
                }
            }
        }
    };
    let where_clause = if has_externs {
        quote!(where #bound)
    } else {
        quote!()
    };
    let trait_item = if has_externs {
        quote! {
            /// The user code this model calls: implement it and pass it to
            /// the model's `new`. Called with static dispatch.
            pub trait Externs {
                #(#trait_fns)*
            }
        }
    } else {
        quote!()
    };

    let module_doc = doc(&format!(
        "The `{name}` model generated by autosim: see [`{name}`]."
    ));
    let name_str = name.clone();

    quote! {
        #module_doc
        // Names come from the model (`KB`, `IB11`); literals are the model's
        // values; numerically equal but symbolically distinct terms can
        // print alike (`a - a` after rounding) or as `x * -1.0`.
        #[allow(
            non_snake_case,
            clippy::approx_constant,
            clippy::too_many_arguments,
            clippy::excessive_precision,
            clippy::unreadable_literal,
            clippy::single_match,
            clippy::eq_op,
            clippy::neg_multiply
        )]
        pub mod #module {
            #[allow(unused_imports)]
            use #rt::__private::math;

            /// Parameters of the model, with their defaults.
            #[derive(Clone, Copy, Debug, PartialEq #params_derive_default)]
            pub struct Parameters {
                #(#p_fields,)*
            }

            #params_default_impl

            /// Inputs of the model, supplied by the caller at run time.
            #[derive(Clone, Copy, Debug, PartialEq #inputs_derive_default)]
            pub struct Inputs {
                #(#i_fields,)*
            }

            #inputs_default_impl

            #trait_item

            /// Values computed once per parameter set.
            #[derive(Clone, Copy, Debug, PartialEq)]
            struct Constants {
                #(#c_fields,)*
            }

            impl Constants {
                fn new(#c_param: &Parameters) -> Self {
                    #c_body
                }
            }

            /// Number of states: coordinates, speeds, added states.
            pub const N_STATES: usize = #n_states_lit;
            /// Number of generalized speeds.
            pub const N_SPEEDS: usize = #n_lit;
            /// Number of outputs.
            pub const N_OUTPUTS: usize = #n_out_lit;

            #model_docs
            #[derive(Clone, Debug)]
            pub struct #model_ty #struct_generics {
                parameters: Parameters,
                constants: Constants,
                /// Inputs read by every evaluation.
                pub inputs: Inputs,
                #externs_field
            }

            #default_impl

            impl #generics #model_ty #struct_generics #where_clause {
                #new_fn

                /// The current parameters.
                pub fn parameters(&self) -> &Parameters {
                    &self.parameters
                }

                /// Sets the parameters and recomputes what depends on them.
                pub fn set_parameters(&mut self, parameters: Parameters) {
                    self.constants = Constants::new(&parameters);
                    self.parameters = parameters;
                }

                /// Operations of one `derivatives` call.
                pub const DERIVATIVE_OPS: #rt::OpCount = #d_ops;
                /// Operations of one `outputs` call.
                pub const OUTPUT_OPS: #rt::OpCount = #o_ops;
                /// Operations of a parameter change.
                pub const CONSTANT_OPS: #rt::OpCount = #c_ops;
                /// Operations of one `mass_matrix` call.
                pub const MASS_MATRIX_OPS: #rt::OpCount = #m_ops;
                /// Operations of one `forcing` call.
                pub const FORCING_OPS: #rt::OpCount = #f_ops;

                /// The mass matrix `M(q)` of `M du/dt = f` (symmetric).
                pub fn mass_matrix(&mut self, #mt: #ty, #mx: &[#ty; #n_states_lit], #m_arg: &mut [[#ty; #n_lit]; #n_lit]) {
                    #mm
                }

                /// The forcing vector `f(q, u, t)` of `M du/dt = f`.
                pub fn forcing(&mut self, #ft: #ty, #fx: &[#ty; #n_states_lit], #f_arg: &mut [#ty; #n_lit]) {
                    #fo
                }
            }

            impl #generics #rt::Model for #model_ty #struct_generics #where_clause {
                type Float = #ty;
                type State = [#ty; #n_states_lit];
                type Outputs = [#ty; #n_out_lit];
                const NAME: &'static str = #name_str;
                const STATE_NAMES: &'static [&'static str] = &[#(#state_names),*];
                const STATE_UNITS: &'static [&'static str] = &[#(#state_units),*];
                const PARAMETER_NAMES: &'static [&'static str] = &[#(#p_names),*];
                const PARAMETER_UNITS: &'static [&'static str] = &[#(#p_units),*];
                const INPUT_NAMES: &'static [&'static str] = &[#(#i_names),*];
                const INPUT_UNITS: &'static [&'static str] = &[#(#i_units),*];
                const OUTPUT_NAMES: &'static [&'static str] = &[#(#out_names),*];
                const OUTPUT_UNITS: &'static [&'static str] = &[#(#out_units),*];

                fn derivatives(&mut self, #dt: #ty, #dxx: &[#ty; #n_states_lit], #d_arg: &mut [#ty; #n_states_lit]) -> Result<(), #rt::ModelError> {
                    #deriv
                    Ok(())
                }

                fn outputs(&mut self, #out_t: #ty, #out_x: &[#ty; #n_states_lit], #out_y: &mut [#ty; #n_out_lit]) -> Result<(), #rt::ModelError> {
                    #outs_body
                    Ok(())
                }

                fn parameter_values(&self, values: &mut [#ty]) {
                    #p_get_body
                }

                fn set_parameter_values(&mut self, values: &[#ty]) {
                    #p_set_body
                }

                fn initial_state(&self) -> [#ty; #n_states_lit] {
                    #init
                }
            }
        }
    }
}

fn uses_time(b: &Block) -> bool {
    b.leaves.contains(&Leaf::Time)
}

fn block_fn_body(be: &BlockEmitter<'_>, block: &Block, target: Target<'_>) -> TokenStream {
    be.emit(block, true, target)
}

#[allow(dead_code)]
fn float_name(f: FloatType) -> &'static str {
    match f {
        FloatType::F64 => "f64",
        FloatType::F32 => "f32",
    }
}

/// Operation counts of the main blocks, for reports.
pub fn ops_summary(p: &Program) -> [(String, Ops); 3] {
    [
        ("derivatives".to_string(), p.derivatives.ops),
        ("outputs".to_string(), p.outputs.ops),
        ("constants".to_string(), p.constants.ops),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::SourceFile;
    use crate::pipeline::compile_source;

    #[test]
    fn model_without_states_has_no_unused_dx() {
        let c = compile_source(&SourceFile::new("m.sim", "model M;\nparameter k = 1;")).unwrap();
        let code = crate::emit::format_tokens(&model_tokens(&c, &EmitOptions::default()));
        let code: String = code.split_whitespace().collect();
        assert!(
            code.contains("fnderivatives(&mutself,_:f64,_:&[f64;0],_:&mut[f64;0],)"),
            "{code}"
        );
    }
}

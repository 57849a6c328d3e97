//! A scheduled block as Rust statements: bindings of the values it reads,
//! user calls, named intermediates, pivot checks and stores.

use super::expr::{ExprPrinter, Locals, ident};
use crate::model::FloatType;
use crate::opt::{Block, Guard, Leaf, Nid, Program, Stmt};
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use rustc_hash::FxHashMap;

/// Where a block's stores go.
pub enum Target<'a> {
    /// `<array>[slot] = value;`
    Array(&'a proc_macro2::Ident),
    /// `<array>[slot / n][slot % n] = value;`
    Matrix(&'a proc_macro2::Ident, usize),
    /// Collected into a struct literal `Constants { p1: ..., }` (the
    /// statements end with that expression).
    ConstantFields,
}

/// Emits a block.
pub struct BlockEmitter<'a> {
    /// The program.
    pub prog: &'a Program,
    /// Float type.
    pub float: FloatType,
    /// Slot of each hoisted constant.
    pub constant_slot: &'a FxHashMap<Nid, usize>,
    /// Path of the runtime's math module.
    pub math: TokenStream,
    /// Path of the runtime crate.
    pub rt: TokenStream,
    /// The generated code's own locals.
    pub locals: &'a Locals,
}

impl BlockEmitter<'_> {
    /// The statements of `block` (with `hoisted`: constants read from `c`).
    pub fn emit(&self, block: &Block, hoisted: bool, target: Target<'_>) -> TokenStream {
        let printer = ExprPrinter {
            prog: self.prog,
            names: &block.names,
            hoisted,
            float: self.float,
            constant_slot: self.constant_slot,
            math: self.math.clone(),
            locals: self.locals,
        };
        let mut out = self.reads(block, hoisted, &target);
        let mut fields = Vec::new();
        for st in &block.stmts {
            match st {
                Stmt::Let(n) => {
                    let name = ident(&block.names[n]);
                    let e = printer.definition(*n);
                    out.extend(quote!(let #name = #e;));
                }
                Stmt::SinCos { sin, cos } => {
                    let (s, c) = (ident(&block.names[sin]), ident(&block.names[cos]));
                    let arg = match self.prog.ir.op(*sin) {
                        crate::opt::Op::Call(_, args) => printer.expr(args[0]),
                        _ => printer.definition(*sin),
                    };
                    let m = &self.math;
                    out.extend(quote!(let (#s, #c) = #m::sin_cos(#arg);));
                }
                Stmt::CallSub(k) => out.extend(self.call_subroutine(block, &printer, *k)),
                Stmt::Check { pivot, guard } => {
                    out.extend(self.pivot_check(&printer, *pivot, *guard))
                }
                Stmt::Store { slot, value } => {
                    let e = printer.expr(*value);
                    match target {
                        Target::Array(a) => {
                            let k = Literal::usize_unsuffixed(*slot);
                            out.extend(quote!(#a[#k] = #e;));
                        }
                        Target::Matrix(a, n) => {
                            let i = Literal::usize_unsuffixed(slot / n);
                            let j = Literal::usize_unsuffixed(slot % n);
                            out.extend(quote!(#a[#i][#j] = #e;));
                        }
                        Target::ConstantFields => {
                            let f = ident(&format!("p{}", slot + 1));
                            fields.push(quote!(#f: #e));
                        }
                    }
                }
            }
        }
        if let Target::ConstantFields = target {
            out.extend(quote!(Constants { #(#fields),* }));
        }
        out
    }

    /// Bindings of the values the block reads: parameters, constants,
    /// states, inputs and accelerations.
    fn reads(&self, block: &Block, hoisted: bool, target: &Target<'_>) -> TokenStream {
        let in_constants = matches!(target, Target::ConstantFields);
        let Locals { x, dx, p, c, .. } = self.locals;
        let mut out = TokenStream::new();
        if !in_constants && block.leaves.iter().any(|l| matches!(l, Leaf::Param(_))) {
            out.extend(quote!(let #p = &self.parameters;));
        }
        if hoisted && !block.hoisted.is_empty() {
            out.extend(quote!(let #c = &self.constants;));
        }
        for l in &block.leaves {
            match *l {
                Leaf::State(i) => {
                    let id = ident(&self.prog.states().state(i).name);
                    let k = Literal::usize_unsuffixed(i);
                    out.extend(quote!(let #id = #x[#k];));
                }
                Leaf::Input(i) => {
                    let id = ident(&self.prog.interface.inputs[i].name);
                    out.extend(quote!(let #id = self.inputs.#id;));
                }
                Leaf::Accel(i) => {
                    let id = ident(&self.prog.states().speed_rate_name(i));
                    let k = Literal::usize_unsuffixed(self.prog.states().speed_slot(i));
                    out.extend(quote!(let #id = #dx[#k];));
                }
                Leaf::Param(_) | Leaf::Time | Leaf::SubOut(..) => {}
            }
        }
        out
    }

    /// `let [a, _, b] = self.externs.sub(args);`
    fn call_subroutine(&self, block: &Block, printer: &ExprPrinter<'_>, k: usize) -> TokenStream {
        let sub = &self.prog.interface.subroutines[k];
        let f = ident(&sub.name);
        let pats: Vec<TokenStream> = sub
            .outputs
            .iter()
            .enumerate()
            .map(|(j, o)| {
                if block.leaves.contains(&Leaf::SubOut(k, j)) {
                    let id = ident(o);
                    quote!(#id)
                } else {
                    quote!(_)
                }
            })
            .collect();
        let args: Vec<TokenStream> = self.prog.sub_args[k]
            .iter()
            .map(|a| printer.expr(*a))
            .collect();
        quote!(let [#(#pats),*] = self.externs.#f(#(#args),*);)
    }

    /// A pivot of the mass matrix that must be positive, or the model
    /// returns `SingularMassMatrix` naming the speed; a pivot of a
    /// constraint solve that must not vanish, or `SingularConstraints`
    /// naming the constraint.
    fn pivot_check(&self, printer: &ExprPrinter<'_>, pivot: Nid, guard: Guard) -> TokenStream {
        let e = printer.expr(pivot);
        let m = &self.math;
        let rt = &self.rt;
        match guard {
            Guard::Positive { speed } => {
                let k = Literal::usize_unsuffixed(speed);
                let name = &self.prog.states().speeds[speed].name;
                quote! {
                    if !#m::is_positive(#e) {
                        return Err(#rt::ModelError::SingularMassMatrix { speed: #k, name: #name });
                    }
                }
            }
            Guard::Regular { constraint } => {
                let k = Literal::usize_unsuffixed(constraint);
                let name = &self.prog.interface.constraints[constraint].name;
                quote! {
                    if !#m::is_regular(#e) {
                        return Err(#rt::ModelError::SingularConstraints { constraint: #k, name: #name });
                    }
                }
            }
        }
    }
}

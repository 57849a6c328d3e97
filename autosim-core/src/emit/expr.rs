//! Printing IR nodes as Rust expressions: names for bound values, literals
//! in the model's float type, operators with the parentheses the IR's order
//! of evaluation needs, and calls of the runtime's math functions.

use super::lane_values::LaneValue;
use crate::expr::{Func, Prec};
use crate::opt::FloatType;
use crate::opt::{Ir, Leaf, Nid, Op, Program};
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use rustc_hash::FxHashMap;
mod sum;

/// An identifier from a model name (raw identifiers kept raw; anything that
/// is not an identifier is sanitized, never a panic).
pub fn ident(name: &str) -> Ident {
    if let Some(raw) = name.strip_prefix("r#")
        && is_ident(raw)
    {
        return Ident::new_raw(raw, Span::call_site());
    }
    if is_ident(name) && !is_keyword(name) {
        return Ident::new(name, Span::call_site());
    }
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    if is_keyword(&s) {
        s.push('_');
    }
    Ident::new(&s, Span::call_site())
}

fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    match chars.next() {
        Some(c) if c.is_alphabetic() || c == '_' => {}
        _ => return false,
    }
    s != "_" && chars.all(|c| c.is_alphanumeric() || c == '_')
}

fn is_keyword(s: &str) -> bool {
    matches!(
        s,
        "as" | "break"
            | "const"
            | "continue"
            | "crate"
            | "else"
            | "enum"
            | "extern"
            | "false"
            | "fn"
            | "for"
            | "if"
            | "impl"
            | "in"
            | "let"
            | "loop"
            | "match"
            | "mod"
            | "move"
            | "mut"
            | "pub"
            | "ref"
            | "return"
            | "self"
            | "Self"
            | "static"
            | "struct"
            | "super"
            | "trait"
            | "true"
            | "type"
            | "unsafe"
            | "use"
            | "where"
            | "while"
            | "async"
            | "await"
            | "dyn"
            | "abstract"
            | "become"
            | "box"
            | "do"
            | "final"
            | "macro"
            | "override"
            | "priv"
            | "typeof"
            | "unsized"
            | "virtual"
            | "yield"
            | "try"
            | "gen"
    )
}

/// A float literal in the model's type (non-finite values as constants).
pub fn literal(x: f64, float: FloatType) -> TokenStream {
    let ty = float_type(float);
    // An `f32` model holds the value `x as f32`, infinite beyond its range.
    let x = match float {
        FloatType::F64 => x,
        FloatType::F32 => f64::from(x as f32),
    };
    if x.is_nan() {
        return quote!(#ty::NAN);
    }
    if x.is_infinite() {
        return if x > 0.0 {
            quote!(#ty::INFINITY)
        } else {
            quote!(#ty::NEG_INFINITY)
        };
    }
    match magnitude_literal(x, float, false) {
        Some(lit) if x < 0.0 => quote!(-#lit),
        Some(lit) => quote!(#lit),
        None => quote!(#ty::NAN),
    }
}

/// The literal of `|x|` in the model's float type (`0.5f32` when
/// `suffixed`), or `None` when that is not finite: proc-macro2 panics on a
/// non-finite literal, so every float literal of generated code is made
/// here. (The pipeline rejects models with such constants before emission;
/// this keeps the emitter from panicking if one ever got through.)
pub fn magnitude_literal(x: f64, float: FloatType, suffixed: bool) -> Option<Literal> {
    match float {
        FloatType::F64 if x.is_finite() => Some(match suffixed {
            true => Literal::f64_suffixed(x.abs()),
            false => Literal::f64_unsuffixed(x.abs()),
        }),
        FloatType::F32 if (x as f32).is_finite() => Some(match suffixed {
            true => Literal::f32_suffixed((x as f32).abs()),
            false => Literal::f32_unsuffixed((x as f32).abs()),
        }),
        _ => None,
    }
}

/// The float type's tokens.
pub fn float_type(float: FloatType) -> TokenStream {
    match float {
        FloatType::F64 => quote!(f64),
        FloatType::F32 => quote!(f32),
    }
}

/// Names of the generated code's own locals, chosen so that no model name
/// (a coordinate called `x`, a speed called `p`) shadows them.
#[derive(Clone, Debug)]
pub struct Locals {
    /// The state array.
    pub x: Ident,
    /// The derivative array.
    pub dx: Ident,
    /// The output array.
    pub y: Ident,
    /// The parameters.
    pub p: Ident,
    /// The precomputed constants.
    pub c: Ident,
    /// The mass matrix.
    pub m: Ident,
    /// The forcing vector.
    pub f: Ident,
    /// The initial state.
    pub x0: Ident,
    /// The Newton step of assembly.
    pub step: Ident,
    /// The linear model.
    pub lin: Ident,
    /// The intermediates of a block too big for `let`s.
    pub z: Ident,
    /// The values of the common block.
    pub s: Ident,
    /// The number of lanes of `derivatives_lanes` (a const generic).
    pub lanes: Ident,
    /// The lane values of a lanes function (`lane_values.rs`).
    pub values: Ident,
}

impl Locals {
    /// Locals that avoid every name the program binds.
    pub fn new(prog: &Program) -> Locals {
        let i = &prog.interface;
        let mut taken: rustc_hash::FxHashSet<String> =
            i.states.states().map(|s| s.name.clone()).collect();
        taken.extend(i.model.inputs.iter().map(|x| x.name.clone()));
        taken.extend(i.model.discrete.iter().map(|x| x.name.clone()));
        for sub in &i.model.subroutines {
            taken.extend(sub.outputs.iter().cloned());
        }
        for (_, b) in &prog.blocks {
            taken.extend(b.names.values().cloned());
        }
        for k in 0..prog.n() {
            taken.insert(i.states.speed_rate_name(k));
        }
        let mut pick = |base: &str| {
            let mut name = base.to_string();
            while taken.contains(&name) {
                name.push('_');
            }
            taken.insert(name.clone());
            ident(&name)
        };
        Locals {
            x: pick("x"),
            dx: pick("dx"),
            y: pick("y"),
            p: pick("p"),
            c: pick("c"),
            m: pick("m"),
            f: pick("f"),
            x0: pick("x0"),
            step: pick("step"),
            lin: pick("lin"),
            z: pick("z"),
            s: pick("s"),
            lanes: pick("L"),
            values: pick("v"),
        }
    }
}

/// Prints IR nodes of one block.
pub struct ExprPrinter<'a> {
    /// The program.
    pub prog: &'a Program,
    /// Names of nodes bound in the block.
    pub names: &'a FxHashMap<Nid, String>,
    /// Whether constants are read from `c` (hoisted).
    pub hoisted: bool,
    /// Float type.
    pub float: FloatType,
    /// Slot of each hoisted constant.
    pub constant_slot: &'a FxHashMap<Nid, usize>,
    /// Slot of each value read from the common block (`s[k]`).
    pub common_slot: &'a FxHashMap<Nid, usize>,
    /// How to call the runtime's math functions (`math`).
    pub math: TokenStream,
    /// The generated code's own locals.
    pub locals: &'a Locals,
    /// Bound values kept in the local array `z` instead of `let`s (blocks
    /// too big for one `let` each), by index.
    pub array: &'a FxHashMap<Nid, usize>,
    /// When each value is ready and how each sum is printed (see
    /// [`sum`]).
    pub timing: sum::Timing,
    /// The runtime's path where user functions' results are checked for
    /// NaN and infinity (in functions that return `Result`), else `None`.
    pub user_check: Option<TokenStream>,
    /// The runtime's path in a lanes function (`derivatives_lanes`), where
    /// every value is a `Lanes<L>`: literals are splat into every lane,
    /// parameters and constants read from the lane values, user functions
    /// called lane by lane.
    pub lanes: Option<TokenStream>,
}

impl ExprPrinter<'_> {
    fn ir(&self) -> &Ir {
        &self.prog.ir
    }

    fn prec(&self, n: Nid) -> Prec {
        if self.is_name(n) {
            return Prec::Atom;
        }
        match self.ir().op(n) {
            Op::Num(b) => {
                if f64::from_bits(*b) < 0.0 && self.lanes.is_none() {
                    Prec::Unary
                } else {
                    Prec::Atom
                }
            }
            Op::Leaf(_) | Op::Call(..) | Op::Sqrt(_) | Op::Powf(..) => Prec::Atom,
            Op::Sum { pos, neg } => self.sum_prec(n, pos, neg),
            Op::Mul(..) | Op::Div(..) => Prec::Prod,
            Op::Powi(_, k) => {
                if *k <= 3 {
                    Prec::Prod
                } else {
                    Prec::Atom
                }
            }
            Op::Neg(_) => Prec::Unary,
        }
    }

    /// Whether `n` is read from outside the block (the common block's
    /// values, hoisted constants) rather than computed in it.
    pub fn is_outside(&self, n: Nid) -> bool {
        self.common_slot.contains_key(&n) || (self.hoisted && self.constant_slot.contains_key(&n))
    }

    fn is_name(&self, n: Nid) -> bool {
        self.names.contains_key(&n)
            || self.common_slot.contains_key(&n)
            || (self.hoisted && self.constant_slot.contains_key(&n))
    }

    fn wrap(&self, n: Nid, min: Prec) -> TokenStream {
        let t = self.expr(n);
        if self.prec(n) < min { quote!((#t)) } else { t }
    }

    /// The expression computing node `n`: its name if it is bound.
    pub fn expr(&self, n: Nid) -> TokenStream {
        if let Some(k) = self.array.get(&n) {
            let (z, k) = (&self.locals.z, Literal::usize_unsuffixed(*k));
            return quote!(#z[#k]);
        }
        if let Some(name) = self.names.get(&n) {
            let id = ident(name);
            return quote!(#id);
        }
        if let Some(k) = self.common_slot.get(&n) {
            let (s, k) = (&self.locals.s, Literal::usize_unsuffixed(*k));
            return quote!(#s[#k]);
        }
        if self.hoisted
            && let Some(k) = self.constant_slot.get(&n)
        {
            let slot = LaneValue::Constant(*k);
            let (c, k) = (&self.locals.c, Literal::usize_unsuffixed(*k));
            return self.read(slot, quote!(#c.p[#k]));
        }
        self.definition(n)
    }

    /// The expression of node `n`'s operation (even if `n` is bound).
    pub fn definition(&self, n: Nid) -> TokenStream {
        match self.ir().op(n).clone() {
            Op::Num(b) => self.splat(literal(f64::from_bits(b), self.float)),
            Op::Leaf(l) => self.leaf(l),
            Op::Sum { pos, neg } => self.sum(n, &pos, &neg),
            Op::Mul(a, b) => {
                let x = self.wrap(a, Prec::Prod);
                let y = self.wrap(b, Prec::Unary);
                quote!(#x * #y)
            }
            Op::Div(a, b) => {
                let x = self.wrap(a, Prec::Prod);
                let y = self.wrap(b, Prec::Unary);
                quote!(#x / #y)
            }
            Op::Neg(a) => {
                // `-(x.add_mul(a, b))`, not `-x.add_mul(a, b)` (the same, but
                // read as if the minus came first).
                let x = match self.ir().op(a) {
                    Op::Sum { .. } if !self.is_name(a) => {
                        let e = self.expr(a);
                        quote!((#e))
                    }
                    _ => self.wrap(a, Prec::Unary),
                };
                quote!(-#x)
            }
            Op::Powi(a, k) => {
                let x = self.wrap(a, Prec::Unary);
                match k {
                    2 => quote!(#x * #x),
                    3 => quote!(#x * #x * #x),
                    _ => {
                        let m = &self.math;
                        let x = self.expr(a);
                        let k = Literal::i32_unsuffixed(k);
                        quote!(#m::powi(#x, #k))
                    }
                }
            }
            Op::Sqrt(a) => {
                let m = &self.math;
                let x = self.expr(a);
                quote!(#m::sqrt(#x))
            }
            Op::Powf(a, b) => {
                let m = &self.math;
                let x = self.expr(a);
                let y = self.expr(b);
                quote!(#m::powf(#x, #y))
            }
            Op::Call(f, args) => {
                let xs: Vec<TokenStream> = args.iter().map(|a| self.expr(*a)).collect();
                match f {
                    Func::User(u) => {
                        let declared = &self.prog.interface.model.extern_fns[u.index()].name;
                        let name = ident(declared);
                        if let Some(rt) = &self.lanes {
                            return self.user_call_lanes(rt, &name, declared, &xs);
                        }
                        let call = quote!(self.externs.#name(#(#xs),*));
                        match &self.user_check {
                            Some(rt) => quote!(#rt::check_user_result(#call, #declared)?),
                            None => call,
                        }
                    }
                    other => {
                        let m = &self.math;
                        let name = ident(self.builtin(other));
                        quote!(#m::#name(#(#xs),*))
                    }
                }
            }
        }
    }

    /// The runtime's math function for a builtin: in `f64` models a sine
    /// or cosine needed alone is the runtime's branch-free one
    /// (`sin_inline`, `cos_inline`: faster than libm's at random angles,
    /// timings in `bench/results/compiler-choices.md`), in `f32` ones
    /// libm's (the kernel computes in `f64`).
    fn builtin(&self, f: Func) -> &'static str {
        match (f, self.float) {
            (Func::Sin, FloatType::F64) => "sin_inline",
            (Func::Cos, FloatType::F64) => "cos_inline",
            _ => f.builtin_name().unwrap_or("abs"),
        }
    }

    /// `value` in every lane in a lanes function (`Lanes::<L>::splat`),
    /// else `value`.
    pub fn splat(&self, value: TokenStream) -> TokenStream {
        match self.lanes {
            Some(_) => {
                let l = &self.locals.lanes;
                quote!(Lanes::<#l>::splat(#value))
            }
            None => value,
        }
    }

    /// `scalar`, the value read from the model; in a lanes function,
    /// `v[i]`, its place in the lane values (`lane_values.rs`).
    pub fn read(&self, value: LaneValue, scalar: TokenStream) -> TokenStream {
        match self.lanes {
            Some(_) => {
                let v = &self.locals.values;
                let i = Literal::usize_unsuffixed(value.index(self.prog));
                quote!(#v[#i])
            }
            None => scalar,
        }
    }

    /// A user function called once per lane (its results checked where
    /// the function returns `Result`): the arguments evaluated first, as
    /// one call evaluates them.
    fn user_call_lanes(
        &self,
        rt: &TokenStream,
        name: &Ident,
        declared: &str,
        args: &[TokenStream],
    ) -> TokenStream {
        let k = (0..args.len()).map(Literal::usize_unsuffixed);
        let call = quote! {
            #rt::__private::call_each([#(#args),*], |v| self.externs.#name(#(v[#k]),*))
        };
        match &self.user_check {
            Some(_) => quote!(#rt::__private::check_user_result_lanes(#call, #declared)?),
            None => call,
        }
    }

    fn leaf(&self, l: Leaf) -> TokenStream {
        let i = &self.prog.interface;
        match l {
            Leaf::Param(k) => {
                let id = ident(&i.model.parameters[k].name);
                let p = &self.locals.p;
                self.read(LaneValue::Parameter(k), quote!(#p.#id))
            }
            Leaf::State(k) => {
                let id = ident(&i.states.state(k).name);
                quote!(#id)
            }
            Leaf::Input(k) => {
                let id = ident(&i.model.inputs[k].name);
                quote!(#id)
            }
            Leaf::Discrete(k) => {
                let id = ident(&i.model.discrete[k].name);
                quote!(#id)
            }
            Leaf::Time => quote!(t),
            Leaf::SubOut(s, k) => {
                let id = ident(&i.model.subroutines[s].outputs[k]);
                quote!(#id)
            }
            Leaf::Accel(k) => {
                let id = ident(&i.states.speed_rate_name(k));
                quote!(#id)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_literal_beyond_f32_range_is_infinity_not_a_panic() {
        let big = literal(3.4e153, FloatType::F32).to_string();
        assert_eq!(big.replace(' ', ""), "f32::INFINITY");
        let small = literal(-1e300, FloatType::F32).to_string();
        assert_eq!(small.replace(' ', ""), "f32::NEG_INFINITY");
        assert_eq!(literal(0.5, FloatType::F32).to_string(), "0.5");
    }

    #[test]
    fn no_non_finite_literal_reaches_proc_macro2() {
        // proc-macro2 asserts its literals are finite: 1e40 is finite in
        // f64 but not in f32 (the fuzzer's panic, through a sum's receiver).
        assert!(magnitude_literal(1e40, FloatType::F32, true).is_none());
        assert!(magnitude_literal(f64::NAN, FloatType::F64, false).is_none());
        assert!(magnitude_literal(f64::INFINITY, FloatType::F64, true).is_none());
        let lit = magnitude_literal(-0.5, FloatType::F32, true).map(|l| l.to_string());
        assert_eq!(lit.as_deref(), Some("0.5f32"));
    }
}

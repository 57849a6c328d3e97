//! A scheduled block as Rust statements: bindings of the values it reads,
//! user calls, named intermediates, pivot checks and stores.

use super::expr::{ExprPrinter, Locals, ident};
use super::lane_values::LaneValue;
use super::sines;
use crate::limits::MAX_LETS_IN_FUNCTION;
use crate::opt::FloatType;
use crate::opt::{Block, BlockKind, Guard, Leaf, Nid, Program, Stmt};
use proc_macro2::{Literal, TokenStream};
use quote::quote;
use rustc_hash::FxHashMap;

/// Where a block's stores go.
pub enum Target<'a> {
    /// `<array>[slot] = value;`
    Array(&'a proc_macro2::Ident),
    /// `results::set(&mut <array>[slot], value);`, for the functions with
    /// an x86-64-v4 copy (the runtime's `results`, whose x86-64-v4 copy
    /// writes each value alone: `float/dispatch.rs`).
    Results(&'a proc_macro2::Ident),
    /// `<array>[slot / n][slot % n] = value;`
    Matrix(&'a proc_macro2::Ident, usize),
    /// `<array>[slot] = value;` in `Constants::new`, which has no `self`
    /// (the parameters are its argument).
    Constants(&'a proc_macro2::Ident),
    /// Consecutive row-major matrices `(path, rows, columns)`:
    /// `<path>[i][j] = value;` (literal zeros are skipped: the matrices
    /// start at zero).
    Matrices(&'a [(TokenStream, usize, usize)]),
}

/// Blocks with more bound values than this compute the sines and cosines
/// they do not take in pairs (`emit/sines.rs`: one left over, or of an
/// angle the block computes) by `math::sin_cos_inline` (no branch on the
/// angle) instead of libm's `sincos`, whose branches, mispredicted at
/// random angles, discard the work a block has in flight; smaller blocks
/// keep libm's shorter path (timings: `bench/results/compiler-choices.md`).
pub const MIN_VALUES_FOR_INLINE_SINES: usize = 600;

/// The array index of each bound value of a block with more than
/// [`MAX_LETS_IN_FUNCTION`] of them (none otherwise).
fn array_slots(block: &Block) -> FxHashMap<Nid, usize> {
    if block.names.len() <= MAX_LETS_IN_FUNCTION {
        return FxHashMap::default();
    }
    all_slots(block)
}

/// The array index of every bound value of a block, in statement order.
pub fn all_slots(block: &Block) -> FxHashMap<Nid, usize> {
    let mut slots = FxHashMap::default();
    for st in &block.stmts {
        let bound: &[Nid] = match st {
            Stmt::Let(n) => std::slice::from_ref(n),
            Stmt::SinCos { sin, cos } => &[*sin, *cos],
            _ => &[],
        };
        for n in bound {
            let k = slots.len();
            slots.insert(*n, k);
        }
    }
    slots
}

/// `<path>[i][j] = e;` for slot `k` of consecutive matrices.
fn matrix_store(list: &[(TokenStream, usize, usize)], k: usize, e: TokenStream) -> TokenStream {
    let mut k = k;
    for (path, rows, cols) in list {
        if k < rows * cols {
            let i = Literal::usize_unsuffixed(k / cols);
            let j = Literal::usize_unsuffixed(k % cols);
            return quote!(#path[#i][#j] = #e;);
        }
        k -= rows * cols;
    }
    TokenStream::new()
}

/// Emits a block.
pub struct BlockEmitter<'a> {
    /// The program.
    pub prog: &'a Program,
    /// Float type.
    pub float: FloatType,
    /// Slot of each hoisted constant.
    pub constant_slot: &'a FxHashMap<Nid, usize>,
    /// Slot of each value of the common block.
    pub common_slot: &'a FxHashMap<Nid, usize>,
    /// Path of the runtime's math module.
    pub math: TokenStream,
    /// Path of the runtime crate.
    pub rt: TokenStream,
    /// The generated code's own locals.
    pub locals: &'a Locals,
    /// Whether the block is printed for `derivatives_lanes`: every value a
    /// `Lanes<L>` (see [`ExprPrinter::lanes`]).
    pub lanes: bool,
}

impl BlockEmitter<'_> {
    /// The statements of `block` (with `hoisted`: constants read from `c`).
    pub fn emit(&self, block: &Block, hoisted: bool, target: Target<'_>) -> TokenStream {
        let array = array_slots(block);
        let declare = !array.is_empty();
        self.statements(block, hoisted, target, false, (&array, declare))
    }

    /// The statements of one part of a block cut into parts
    /// (`parts.rs`): every bound value in the array its caller declared,
    /// at `array`'s index.
    pub fn emit_part(
        &self,
        part: &Block,
        array: &FxHashMap<Nid, usize>,
        target: Target<'_>,
    ) -> TokenStream {
        self.statements(part, true, target, false, (array, false))
    }

    /// [`BlockEmitter::emit`] for a function that returns `Result<_,
    /// ModelError>`: every result of user code is checked, and NaN or
    /// infinity returns `NonFiniteUserResult` naming the function.
    pub fn emit_checked(&self, block: &Block, hoisted: bool, target: Target<'_>) -> TokenStream {
        let array = array_slots(block);
        let declare = !array.is_empty();
        self.statements(block, hoisted, target, true, (&array, declare))
    }

    fn statements(
        &self,
        block: &Block,
        hoisted: bool,
        target: Target<'_>,
        check_user_results: bool,
        (array, declare): (&FxHashMap<Nid, usize>, bool),
    ) -> TokenStream {
        let none = FxHashMap::default();
        let printer = ExprPrinter {
            common_slot: match block.common.is_empty() {
                true => &none,
                false => self.common_slot,
            },
            prog: self.prog,
            names: &block.names,
            hoisted,
            float: self.float,
            constant_slot: self.constant_slot,
            math: self.math.clone(),
            locals: self.locals,
            array,
            timing: Default::default(),
            user_check: check_user_results.then(|| self.rt.clone()),
            lanes: self.lanes.then(|| self.rt.clone()),
        };
        let mut out = self.reads(block, hoisted, &target, &printer);
        out.extend(self.shared_terms_call(block));
        if declare {
            let (z, len) = (&self.locals.z, Literal::usize_unsuffixed(array.len()));
            let zero = printer.splat(quote!(0.0));
            out.extend(quote!(let mut #z = [#zero; #len];));
        }
        // The branch-free kernel computes in `f64`, which a single-precision
        // FPU (a Cortex-M4F's) does in software: `f32` models keep libm's
        // `sincosf` for every angle.
        let branch_free = self.float == FloatType::F64;
        let inline_sines = branch_free && block.names.len() > MIN_VALUES_FOR_INLINE_SINES;
        let groups = match branch_free {
            true => sines::groups(&self.prog.ir, block, &|n| printer.is_outside(n)),
            false => Default::default(),
        };
        for (i, st) in block.stmts.iter().enumerate() {
            if groups.skip.contains(&i) {
                continue;
            }
            if let Some(group) = groups.at.get(&i) {
                out.extend(self.sin_cos_lanes(block, &printer, group, !array.is_empty()));
                continue;
            }
            match st {
                Stmt::Let(n) => {
                    let e = printer.definition(*n);
                    match array.contains_key(n) {
                        true => {
                            let z = printer.expr(*n);
                            out.extend(quote!(#z = #e;));
                        }
                        false => {
                            let name = ident(&block.names[n]);
                            out.extend(quote!(let #name = #e;));
                        }
                    }
                }
                Stmt::SinCos { sin, cos } => {
                    let (s, c) = (ident(&block.names[sin]), ident(&block.names[cos]));
                    let arg = match self.prog.ir.op(*sin) {
                        crate::opt::Op::Call(_, args) => printer.expr(args[0]),
                        _ => printer.definition(*sin),
                    };
                    let m = &self.math;
                    let f = match inline_sines {
                        true => quote!(sin_cos_inline),
                        false => quote!(sin_cos),
                    };
                    if array.contains_key(sin) {
                        let (s, c) = (printer.expr(*sin), printer.expr(*cos));
                        out.extend(quote!((#s, #c) = #m::#f(#arg);));
                    } else {
                        out.extend(quote!(let (#s, #c) = #m::#f(#arg);));
                    }
                }
                Stmt::CallSub(k) => out.extend(self.call_subroutine(block, &printer, *k)),
                Stmt::Check { pivot, guard } => {
                    out.extend(self.pivot_check(&printer, *pivot, *guard))
                }
                Stmt::Store { slot, value } => {
                    let e = printer.expr(*value);
                    match target {
                        Target::Array(a) | Target::Constants(a) => {
                            let k = Literal::usize_unsuffixed(*slot);
                            out.extend(quote!(#a[#k] = #e;));
                        }
                        Target::Results(a) => {
                            let k = Literal::usize_unsuffixed(*slot);
                            out.extend(quote!(results::set(&mut #a[#k], #e);));
                        }
                        Target::Matrix(a, n) => {
                            let i = Literal::usize_unsuffixed(slot / n);
                            let j = Literal::usize_unsuffixed(slot % n);
                            out.extend(quote!(#a[#i][#j] = #e;));
                        }
                        Target::Matrices(list) => {
                            if self.prog.ir.as_num(*value) != Some(0.0) {
                                out.extend(matrix_store(list, *slot, e));
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// Sines and cosines in one call: `let ([sin_q1, sin_q2], [cos_q1,
    /// cos_q2]) = math::sin_cos_lanes([q1, q2]);` (assigned to `z[k]`
    /// in a block that keeps its values in the array).
    fn sin_cos_lanes(
        &self,
        block: &Block,
        printer: &ExprPrinter<'_>,
        group: &[sines::SinCos],
        in_array: bool,
    ) -> TokenStream {
        let bound = |n: Nid| match in_array {
            true => printer.expr(n),
            false => {
                let name = ident(&block.names[&n]);
                quote!(#name)
            }
        };
        let sins: Vec<TokenStream> = group.iter().map(|g| bound(g.sin)).collect();
        let coss: Vec<TokenStream> = group.iter().map(|g| bound(g.cos)).collect();
        let angles: Vec<TokenStream> = group.iter().map(|g| printer.expr(g.angle)).collect();
        let m = &self.math;
        let call = quote!(#m::sin_cos_lanes([#(#angles),*]));
        match in_array {
            true => quote!(([#(#sins),*], [#(#coss),*]) = #call;),
            false => quote!(let ([#(#sins),*], [#(#coss),*]) = #call;),
        }
    }

    /// Bindings of the values the block reads: parameters, constants,
    /// states, inputs and accelerations.
    fn reads(
        &self,
        block: &Block,
        hoisted: bool,
        target: &Target<'_>,
        printer: &ExprPrinter<'_>,
    ) -> TokenStream {
        let in_constants = matches!(target, Target::Constants(_));
        let Locals { x, dx, p, c, .. } = self.locals;
        let mut out = TokenStream::new();
        // A lanes function reads parameters and constants from its lane
        // values.
        if !in_constants && !self.lanes && block.reads_parameters() {
            out.extend(quote!(let #p = &self.parameters;));
        }
        if hoisted && !self.lanes && !block.hoisted.is_empty() {
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
                    let id = ident(&self.prog.interface.model.inputs[i].name);
                    let value = printer.read(LaneValue::Input(i), quote!(self.inputs.#id));
                    out.extend(quote!(let #id = #value;));
                }
                Leaf::Accel(i) => {
                    let id = ident(&self.prog.states().speed_rate_name(i));
                    let k = Literal::usize_unsuffixed(self.prog.states().speed_slot(i));
                    out.extend(quote!(let #id = #dx[#k];));
                }
                Leaf::Discrete(i) => {
                    let id = ident(&self.prog.interface.model.discrete[i].name);
                    let value = printer.read(LaneValue::Discrete(i), quote!(self.discrete.#id));
                    out.extend(quote!(let #id = #value;));
                }
                Leaf::Param(_) | Leaf::Time | Leaf::SubOut(..) => {}
            }
        }
        out
    }

    /// `let mut s = [0.0; K]; self.shared_terms(t, x, &mut s);` in a block
    /// that reads the common block's values. In lanes, the common block
    /// itself in a nested block, so that it computes with the `MulAdd` and
    /// `math` of the copy it is in (the x86-64-v3 copy's fuse, as
    /// `shared_terms_v3` does for one state).
    fn shared_terms_call(&self, block: &Block) -> TokenStream {
        if block.common.is_empty() {
            return TokenStream::new();
        }
        let s = &self.locals.s;
        let len = Literal::usize_unsuffixed(self.prog.common.len());
        let (t, x) = self.shared_reads();
        let lx = &self.locals.x;
        let args = [t.then(|| quote!(t)), x.then(|| quote!(#lx))]
            .into_iter()
            .flatten();
        if self.lanes {
            let l = &self.locals.lanes;
            let common = self.prog.block(BlockKind::Common);
            let body = self.emit(common, true, Target::Array(&self.locals.s));
            return quote! {
                let mut #s = [Lanes::<#l>::ZERO; #len];
                {
                    let #s = &mut #s;
                    #body
                }
            };
        }
        quote! {
            let mut #s = [0.0; #len];
            self.shared_terms(#(#args,)* &mut #s);
        }
    }

    /// Whether the common block reads the time and the state (the
    /// arguments `shared_terms` takes).
    pub fn shared_reads(&self) -> (bool, bool) {
        match self.prog.try_block(BlockKind::Common) {
            Some(b) => (b.reads_time(), b.reads_state()),
            None => (false, false),
        }
    }

    /// `let [a, _, b] = self.externs.sub(args);` (its results checked in a
    /// function that returns `Result`).
    fn call_subroutine(&self, block: &Block, printer: &ExprPrinter<'_>, k: usize) -> TokenStream {
        let sub = &self.prog.interface.model.subroutines[k];
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
        let (call, check) = match self.lanes {
            false => (
                quote!(self.externs.#f(#(#args),*)),
                quote!(check_user_results),
            ),
            true => {
                let (rt, k) = (&self.rt, (0..args.len()).map(Literal::usize_unsuffixed));
                (
                    quote!(#rt::__private::call_each_sub([#(#args),*], |v| self.externs.#f(#(v[#k]),*))),
                    quote!(__private::check_user_results_lanes),
                )
            }
        };
        match &printer.user_check {
            Some(rt) => {
                let name = &sub.name;
                quote!(let [#(#pats),*] = #rt::#check(#call, #name)?;)
            }
            None => quote!(let [#(#pats),*] = #call;),
        }
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
                let name = &self.prog.interface.model.constraints[constraint].name;
                quote! {
                    if !#m::is_regular(#e) {
                        return Err(#rt::ModelError::SingularConstraints { constraint: #k, name: #name });
                    }
                }
            }
        }
    }
}

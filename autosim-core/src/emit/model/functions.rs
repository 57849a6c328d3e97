//! The bodies and signatures of the generated functions, one per block of
//! the program: `derivatives`, `outputs`, `mass_matrix`, `forcing`,
//! `initial_state` and `Constants::new`.

use super::versions::{self, Copies, Param, Versions, versions};
use crate::emit::block::{BlockEmitter, Target};
use crate::emit::expr::Locals;
use crate::opt::{Block, BlockKind, MassLayout, Ops, Program, Stmt};
use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

/// The arguments a block function names: `t` or `_`, the state array or
/// `_`, as the block reads them.
pub(super) struct Args {
    pub t: TokenStream,
    pub x: TokenStream,
}

/// `t`/`_` and `x`/`_` for the function of a block (the outputs take both
/// when they compute the derivatives first; a block reading the common
/// block passes on what that reads).
pub(super) fn args(prog: &Program, kind: BlockKind, locals: &Locals) -> Args {
    let b = prog.block(kind);
    let shared = match (b.common.is_empty(), prog.try_block(BlockKind::Common)) {
        (false, Some(c)) => c,
        _ => b,
    };
    let need = kind == BlockKind::Outputs && prog.outputs_need_derivatives;
    let lx = &locals.x;
    Args {
        t: if b.reads_time() || shared.reads_time() || need {
            quote!(t)
        } else {
            quote!(_)
        },
        x: if b.reads_state() || shared.reads_state() || need {
            quote!(#lx)
        } else {
            quote!(_)
        },
    }
}

/// The statements of the function of a block.
pub(super) fn body(be: &BlockEmitter<'_>, kind: BlockKind) -> TokenStream {
    let prog = be.prog;
    let l = be.locals;
    let block = prog.block(kind);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    // The functions with an x86-64-v4 copy write their results by
    // `results::set` (in that copy one store each: merged, 512-bit ones).
    let results = |array| match !be.lanes && versions::copies(prog) == Copies::UpToV4 {
        true => Target::Results(array),
        false => Target::Array(array),
    };
    match kind {
        BlockKind::Derivatives => be.emit_checked(block, true, results(&l.dx)),
        BlockKind::MassMatrix => match prog.mass_layout {
            MassLayout::Entries => be.emit(block, true, Target::Matrix(&l.m, prog.n().max(1))),
            MassLayout::Products => be.emit(block, true, Target::Array(&l.f)),
        },
        BlockKind::Forcing => be.emit(block, true, Target::Array(&l.f)),
        BlockKind::Common => be.emit(block, true, results(&l.s)),
        BlockKind::Outputs => {
            let body = be.emit_checked(block, true, Target::Array(&l.y));
            if !prog.outputs_need_derivatives {
                return body;
            }
            let (lx, ldx, rt) = (&l.x, &l.dx, &be.rt);
            quote! {
                let mut #ldx = [0.0; #n_states];
                <Self as #rt::Model>::derivatives(self, t, #lx, &mut #ldx)?;
                #body
            }
        }
        BlockKind::Initial => initial_state(be, block, n_states),
        BlockKind::Constants => constants_new(be, block),
        BlockKind::Assembly => be.emit(block, true, Target::Array(&l.step)),
        BlockKind::Linearize => linearize_body(be, block),
        BlockKind::EventIndicators | BlockKind::EventAction(_) => {
            be.emit_checked(block, true, Target::Array(&l.y))
        }
    }
}

/// `mass_matrix`: the block's entries, or (`MassLayout::Products`) one
/// call per column of a private `inertia_forces` computing `M du/dt` in
/// O(n) operations (`M` is symmetric, so column `j` fills row `j`).
pub(super) fn mass_matrix(be: &BlockEmitter<'_>, t: TokenStream, x: TokenStream) -> TokenStream {
    let prog = be.prog;
    let l = be.locals;
    let ty = crate::emit::expr::float_type(be.float);
    let n = prog.n();
    let n_lit = Literal::usize_unsuffixed(n);
    let n_states = Literal::usize_unsuffixed(prog.states().len());
    let body = body(be, BlockKind::MassMatrix);
    let (lm, lx, ldx, lf) = (&l.m, &l.x, &l.dx, &l.f);
    if prog.mass_layout == MassLayout::Entries {
        let m_arg = if n == 0 { quote!(_) } else { quote!(#lm) };
        return quote! {
            /// The mass matrix `M(q)` of `M du/dt = f` (symmetric).
            pub fn mass_matrix(&mut self, #t: #ty, #x: &[#ty; #n_states], #m_arg: &mut [[#ty; #n_lit]; #n_lit]) {
                #body
            }
        };
    }
    let first = prog.states().speed_slot(0);
    let is_unit = match first {
        0 => quote!(slot == column),
        _ => {
            let first = Literal::usize_unsuffixed(first);
            quote!(slot == column + #first)
        }
    };
    quote! {
        /// The mass matrix `M(q)` of `M du/dt = f` (symmetric), a column
        /// at a time: the articulated-body recursion never forms it.
        pub fn mass_matrix(&mut self, t: #ty, #lx: &[#ty; #n_states], #lm: &mut [[#ty; #n_lit]; #n_lit]) {
            for (column, row) in #lm.iter_mut().enumerate() {
                let unit: [#ty; #n_states] =
                    core::array::from_fn(|slot| if #is_unit { 1.0 } else { 0.0 });
                self.inertia_forces(t, #lx, &unit, row);
            }
        }

        /// The generalized inertia forces `M du/dt` for the accelerations
        /// in the speed slots of `dx` (the others are not read), in O(n)
        /// operations.
        fn inertia_forces(&mut self, #t: #ty, #x: &[#ty; #n_states], #ldx: &[#ty; #n_states], #lf: &mut [#ty; #n_lit]) {
            #body
        }
    }
}

/// `shared_terms`, the function of the common block (none without one), in
/// several copies (`versions`): the caller with its doc and the baseline copy
/// for the inherent impl, the module-level items apart.
pub(super) fn shared_terms(be: &BlockEmitter<'_>) -> Versions {
    if be.prog.try_block(BlockKind::Common).is_none() {
        return Versions {
            caller: TokenStream::new(),
            copies: TokenStream::new(),
            items: TokenStream::new(),
        };
    }
    let ty = crate::emit::expr::float_type(be.float);
    let (lx, ls) = (&be.locals.x, &be.locals.s);
    let n_states = Literal::usize_unsuffixed(be.prog.states().len());
    let len = Literal::usize_unsuffixed(be.prog.common.len());
    let (t, x) = be.shared_reads();
    let param = |name: &Ident, ty: TokenStream| Param {
        pattern: quote!(#name),
        name: name.clone(),
        ty,
    };
    let t_name = format_ident!("t");
    let mut params = Vec::new();
    if t {
        params.push(param(&t_name, quote!(#ty)));
    }
    if x {
        params.push(param(lx, quote!(&[#ty; #n_states])));
    }
    params.push(param(ls, quote!(&mut [#ty; #len])));
    let body = body(be, BlockKind::Common);
    let Versions {
        caller,
        copies,
        items,
    } = versions(
        &be.rt,
        super::versions::copies(be.prog),
        &super::impl_head(&be.prog.interface),
        "shared_terms",
        quote!(&self),
        &params,
        quote!(),
        body,
    );
    Versions {
        caller: quote! {
            /// What `derivatives` and `forcing` both compute, computed once
            /// for either: they read slot `k` as `s[k]`.
            #caller
        },
        copies,
        items,
    }
}

/// What one call of a block's function costs: the block's operations,
/// times the columns where `mass_matrix` runs it per column.
pub(super) fn ops_per_call(prog: &Program, kind: BlockKind, block: &Block) -> Ops {
    let o = block.ops;
    match (kind, prog.mass_layout) {
        (BlockKind::MassMatrix, MassLayout::Products) => {
            let n = prog.n();
            Ops {
                adds: o.adds * n,
                muls: o.muls * n,
                divs: o.divs * n,
                funcs: o.funcs * n,
                user_calls: o.user_calls * n,
            }
        }
        _ => o,
    }
}

/// The sizes of the linear model: states, inputs, outputs.
pub(super) fn linear_sizes(prog: &Program) -> (usize, usize, usize) {
    let i = &prog.interface;
    let nl = i.linear_states.as_ref().map_or(0, Vec::len);
    (nl, i.model.inputs.len(), i.model.outputs.len())
}

/// The body of `linearize`: the matrices start at zero, the block writes
/// the others.
fn linearize_body(be: &BlockEmitter<'_>, block: &Block) -> TokenStream {
    let lin = &be.locals.lin;
    let list = linear_matrices(be);
    let rt = &be.rt;
    let body = be.emit(block, true, Target::Matrices(&list));
    quote! {
        let mut #lin = #rt::Linear::zeros();
        #body
        Ok(#lin)
    }
}

/// Where the linear model's slots go: `lin.a`, `lin.b`, `lin.c`, `lin.d`
/// with their sizes.
pub(super) fn linear_matrices(be: &BlockEmitter<'_>) -> [(TokenStream, usize, usize); 4] {
    let (nl, nw, ny) = linear_sizes(be.prog);
    let lin = &be.locals.lin;
    [
        (quote!(#lin.a), nl, nl),
        (quote!(#lin.b), nl, nw),
        (quote!(#lin.c), ny, nl),
        (quote!(#lin.d), ny, nw),
    ]
}

/// The initial state: only its nonzero entries are computed.
fn initial_state(be: &BlockEmitter<'_>, block: &Block, n_states: Literal) -> TokenStream {
    let mut nonzero = block.clone();
    nonzero.stmts.retain(|st| match st {
        Stmt::Store { value, .. } => be.prog.ir.as_num(*value) != Some(0.0),
        _ => true,
    });
    if !nonzero
        .stmts
        .iter()
        .any(|st| matches!(st, Stmt::Store { .. }))
    {
        return quote!([0.0; #n_states]);
    }
    let lx0 = &be.locals.x0;
    let body = be.emit(&nonzero, false, Target::Array(lx0));
    quote!(let mut #lx0 = [0.0; #n_states]; #body #lx0)
}

/// The body of `Constants::new` (which names its argument `_parameters`
/// when no constant reads a parameter): the constants computed into an
/// array `c`, then `Constants { p: c }`.
fn constants_new(be: &BlockEmitter<'_>, block: &Block) -> TokenStream {
    if be.prog.hoisted.is_empty() {
        return quote!(Constants { p: [] });
    }
    let lc = &be.locals.c;
    let n = Literal::usize_unsuffixed(be.prog.hoisted.len());
    let body = be.emit(block, false, Target::Constants(lc));
    let body = quote!(let mut #lc = [0.0; #n]; #body Constants { p: #lc });
    if block.reads_parameters() {
        let lp = &be.locals.p;
        quote!(let #lp = parameters; #body)
    } else {
        body
    }
}

/// The constant reporting the cost of a block's function, if it has one:
/// its name and what one call of it is.
pub(super) fn ops_constant(kind: BlockKind) -> Option<(&'static str, &'static str)> {
    Some(match kind {
        BlockKind::Derivatives => ("DERIVATIVE_OPS", "one `derivatives` call"),
        BlockKind::Outputs => ("OUTPUT_OPS", "one `outputs` call"),
        BlockKind::Constants => ("CONSTANT_OPS", "a parameter change"),
        BlockKind::MassMatrix => ("MASS_MATRIX_OPS", "one `mass_matrix` call"),
        BlockKind::Forcing => ("FORCING_OPS", "one `forcing` call"),
        BlockKind::Assembly => ("ASSEMBLY_OPS", "one `assembly_step` call"),
        BlockKind::Linearize => ("LINEARIZE_OPS", "one `linearize` call"),
        BlockKind::EventIndicators => ("EVENT_INDICATOR_OPS", "one `event_indicators` call"),
        // `EVENT_OPS` lists the actions' costs, one per event.
        BlockKind::Initial | BlockKind::Common | BlockKind::EventAction(_) => return None,
    })
}

//! Forward differentiation of the program IR: the derivative of a node
//! with respect to one leaf (a state or an input), built as IR nodes so
//! the linearization shares the optimizer's naming, hoisting and counting.
//!
//! Values the caller knows the derivative of are seeded (the
//! accelerations: their derivative comes from the mass matrix's factor,
//! not from differentiating the unrolled solve). A user function's
//! derivative is a central difference (generated code cannot see inside
//! user code); a subroutine's outputs are leaves computed before the
//! program and are held: their derivative is zero (documented in
//! `language.md`).
//!
//! Independence is structural: a node none of whose operands moves with
//! the leaf has the literal zero as its derivative, whichever its rule, so
//! a Jacobian entry that does not depend on the leaf costs nothing and is
//! exactly `0.0` (the rules alone would leave `0 / b` for quotients and
//! roots, which the IR does not fold: it is NaN where `b` is zero).

use crate::expr::Func;
use crate::opt::ir::{Ir, Leaf, Nid, Op};
use rustc_hash::FxHashMap;

/// Derivatives of IR nodes with respect to one leaf, memoized.
pub struct Tangent {
    wrt: Leaf,
    /// The relative step of a user function's central difference.
    user_step: f64,
    memo: FxHashMap<Nid, Nid>,
}

impl Tangent {
    /// Derivatives with respect to `wrt`; a user function's central
    /// difference steps its argument `a` by `user_step · max(|a|, 1)`.
    pub fn new(wrt: Leaf, user_step: f64) -> Tangent {
        Tangent {
            wrt,
            user_step,
            memo: FxHashMap::default(),
        }
    }

    /// Declares `d leaf / d wrt = value` for another leaf (the IR's
    /// rewriting can absorb an inner node into its users, never a leaf).
    pub fn seed(&mut self, leaf: Nid, value: Nid) {
        self.memo.insert(leaf, value);
    }

    /// `d n / d wrt`. Iterative: dependency chains of big models are
    /// thousands deep.
    pub fn d(&mut self, ir: &mut Ir, n: Nid) -> Nid {
        let mut stack: Vec<(Nid, bool)> = vec![(n, false)];
        while let Some((m, expanded)) = stack.pop() {
            if self.memo.contains_key(&m) {
                continue;
            }
            if ir.is_constant(m) {
                let zero = ir.num(0.0);
                self.memo.insert(m, zero);
                continue;
            }
            if expanded {
                let dm = self.rule(ir, m);
                self.memo.insert(m, dm);
                continue;
            }
            stack.push((m, true));
            for c in ir.children(m) {
                if !self.memo.contains_key(&c) {
                    stack.push((c, false));
                }
            }
        }
        self.memo[&n]
    }

    /// The derivative of `n`, its children's known. A node none of whose
    /// children moves with `wrt` does not either: its derivative is the
    /// literal zero, whatever the rule would build (a quotient's rule
    /// gives `0 / b`, which the IR keeps: it is NaN where `b` is zero).
    fn rule(&mut self, ir: &mut Ir, n: Nid) -> Nid {
        let d = |t: &Tangent, c: Nid| t.memo[&c];
        let op = ir.op(n).clone();
        if !matches!(op, Op::Leaf(_))
            && ir
                .children(n)
                .iter()
                .all(|c| ir.as_num(d(self, *c)) == Some(0.0))
        {
            return ir.num(0.0);
        }
        match op {
            Op::Num(_) => ir.num(0.0),
            Op::Leaf(l) => ir.num(if l == self.wrt { 1.0 } else { 0.0 }),
            Op::Sum { pos, neg } => {
                let p = pos.iter().map(|c| d(self, *c)).collect();
                let m = neg.iter().map(|c| d(self, *c)).collect();
                ir.sum(p, m)
            }
            Op::Mul(a, b) => {
                let (da, db) = (d(self, a), d(self, b));
                let x = ir.mul(da, b);
                let y = ir.mul(a, db);
                ir.sum(vec![x, y], Vec::new())
            }
            Op::Div(a, b) => {
                // (da − (a/b) db) / b
                let (da, db) = (d(self, a), d(self, b));
                let q = ir.mul(n, db);
                let num = ir.sum(vec![da], vec![q]);
                ir.div(num, b)
            }
            Op::Neg(a) => {
                let da = d(self, a);
                ir.neg(da)
            }
            Op::Powi(a, k) => {
                let da = d(self, a);
                let p = ir.powi(a, k - 1);
                let kk = ir.num(f64::from(k));
                let s = ir.mul(kk, p);
                ir.mul(s, da)
            }
            Op::Sqrt(a) => {
                // da / (2 sqrt(a))
                let da = d(self, a);
                let two = ir.num(2.0);
                let den = ir.mul(two, n);
                ir.div(da, den)
            }
            Op::Powf(a, b) => {
                let (da, db) = (d(self, a), d(self, b));
                // b a^(b−1) da + a^b ln(a) db
                let one = ir.num(1.0);
                let bm1 = ir.sum(vec![b], vec![one]);
                let p = ir.powf(a, bm1);
                let t1 = ir.mul(b, p);
                let t1 = ir.mul(t1, da);
                let t2 = match ir.as_num(db) {
                    Some(0.0) => ir.num(0.0),
                    _ => {
                        let ln = ir.call(Func::Ln, vec![a]);
                        let x = ir.mul(n, ln);
                        ir.mul(x, db)
                    }
                };
                ir.sum(vec![t1, t2], Vec::new())
            }
            Op::Call(f, args) => self.call_rule(ir, n, f, &args),
        }
    }

    fn call_rule(&mut self, ir: &mut Ir, n: Nid, f: Func, args: &[Nid]) -> Nid {
        let da: Vec<Nid> = args.iter().map(|c| self.memo[c]).collect();
        let a = args[0];
        match f {
            Func::Sin => {
                let c = ir.call(Func::Cos, vec![a]);
                ir.mul(c, da[0])
            }
            Func::Cos => {
                let s = ir.call(Func::Sin, vec![a]);
                let x = ir.mul(s, da[0]);
                ir.neg(x)
            }
            Func::Tan => {
                let one = ir.num(1.0);
                let t2 = ir.powi(n, 2);
                let s = ir.sum(vec![one, t2], Vec::new());
                ir.mul(s, da[0])
            }
            Func::Asin | Func::Acos => {
                let one = ir.num(1.0);
                let a2 = ir.powi(a, 2);
                let s = ir.sum(vec![one], vec![a2]);
                let r = ir.sqrt(s);
                let q = ir.div(da[0], r);
                if f == Func::Acos { ir.neg(q) } else { q }
            }
            Func::Atan2 => {
                // (x dy − y dx) / (x² + y²)
                let (y, x) = (args[0], args[1]);
                let t1 = ir.mul(x, da[0]);
                let t2 = ir.mul(y, da[1]);
                let num = ir.sum(vec![t1], vec![t2]);
                let x2 = ir.powi(x, 2);
                let y2 = ir.powi(y, 2);
                let den = ir.sum(vec![x2, y2], Vec::new());
                ir.div(num, den)
            }
            Func::Exp => ir.mul(n, da[0]),
            Func::Ln => ir.div(da[0], a),
            Func::Abs => {
                let s = ir.call(Func::Sign, vec![a]);
                ir.mul(s, da[0])
            }
            Func::Min | Func::Max => {
                // (da + db ∓ sign(a − b)(da − db)) / 2
                let b = args[1];
                let diff = ir.sum(vec![a], vec![b]);
                let s = ir.call(Func::Sign, vec![diff]);
                let dd = ir.sum(vec![da[0]], vec![da[1]]);
                let sd = ir.mul(s, dd);
                let both = ir.sum(vec![da[0], da[1]], Vec::new());
                let num = match f {
                    Func::Min => ir.sum(vec![both], vec![sd]),
                    _ => ir.sum(vec![both, sd], Vec::new()),
                };
                let half = ir.num(0.5);
                ir.mul(half, num)
            }
            // Held: sign is piecewise constant.
            Func::Sign => ir.num(0.0),
            Func::User(_) => self.central_difference(ir, f, args, &da),
        }
    }

    /// A user function's derivative, `Σ_i ∂f/∂a_i · da_i` over the
    /// arguments that move, each partial
    /// `(f(…, a_i + h, …) − f(…, a_i − h, …)) / 2h` with
    /// `h = user_step · max(|a_i|, 1)` (the step that balances truncation
    /// and rounding for a smooth `f`: about 1e-10 relative error in `f64`).
    fn central_difference(&self, ir: &mut Ir, f: Func, args: &[Nid], da: &[Nid]) -> Nid {
        let mut terms = Vec::new();
        for (i, &da_i) in da.iter().enumerate() {
            if ir.as_num(da_i) == Some(0.0) {
                continue;
            }
            let a = args[i];
            let size = ir.call(Func::Abs, vec![a]);
            let one = ir.num(1.0);
            let scale = ir.call(Func::Max, vec![size, one]);
            let step = ir.num(self.user_step);
            let h = ir.mul(step, scale);
            let at = |ir: &mut Ir, shifted: Nid| {
                let mut moved = args.to_vec();
                moved[i] = shifted;
                ir.call(f, moved)
            };
            let ahead = ir.sum(vec![a, h], Vec::new());
            let behind = ir.sum(vec![a], vec![h]);
            let (f_ahead, f_behind) = (at(ir, ahead), at(ir, behind));
            let rise = ir.sum(vec![f_ahead], vec![f_behind]);
            let two = ir.num(2.0);
            let run = ir.mul(two, h);
            let slope = ir.div(rise, run);
            terms.push(ir.mul(slope, da_i));
        }
        ir.sum(terms, Vec::new())
    }
}

/// `roots` with the nodes of `map` replaced (their users rebuilt).
pub fn substitute(ir: &mut Ir, roots: &[Nid], map: &FxHashMap<Nid, Nid>) -> Vec<Nid> {
    let mut done: FxHashMap<Nid, Nid> = map.clone();
    for &root in roots {
        let mut stack: Vec<(Nid, bool)> = vec![(root, false)];
        while let Some((m, expanded)) = stack.pop() {
            if done.contains_key(&m) {
                continue;
            }
            if ir.is_constant(m) || matches!(ir.op(m), Op::Leaf(_) | Op::Num(_)) {
                done.insert(m, m);
                continue;
            }
            if expanded {
                let r = rebuild(ir, m, &done);
                done.insert(m, r);
                continue;
            }
            stack.push((m, true));
            for c in ir.children(m) {
                stack.push((c, false));
            }
        }
    }
    roots.iter().map(|r| done[r]).collect()
}

/// Node `n` with its children replaced by `new[child]`.
fn rebuild(ir: &mut Ir, n: Nid, new: &FxHashMap<Nid, Nid>) -> Nid {
    let c = |x: &Nid| new[x];
    match ir.op(n).clone() {
        Op::Num(_) | Op::Leaf(_) => n,
        Op::Sum { pos, neg } => {
            let p = pos.iter().map(c).collect();
            let m = neg.iter().map(c).collect();
            ir.sum(p, m)
        }
        Op::Mul(a, b) => ir.mul(c(&a), c(&b)),
        Op::Div(a, b) => ir.div(c(&a), c(&b)),
        Op::Neg(a) => ir.neg(c(&a)),
        Op::Powi(a, k) => ir.powi(c(&a), k),
        Op::Sqrt(a) => ir.sqrt(c(&a)),
        Op::Powf(a, b) => ir.powf(c(&a), c(&b)),
        Op::Call(f, args) => ir.call(f, args.iter().map(c).collect()),
    }
}

/// `nodes` with `Leaf::Accel(k)` replaced by `du[k]`.
pub(crate) fn with_accelerations(ir: &mut Ir, nodes: &[Nid], du: &[Nid]) -> Vec<Nid> {
    let map: FxHashMap<Nid, Nid> = du
        .iter()
        .enumerate()
        .map(|(k, d)| (ir.leaf(Leaf::Accel(k)), *d))
        .collect();
    substitute(ir, nodes, &map)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Evaluates `n` with the state leaves `x`.
    fn eval(ir: &Ir, n: Nid, x: &[f64]) -> f64 {
        let v = |m: Nid| eval(ir, m, x);
        match ir.op(n) {
            Op::Num(b) => f64::from_bits(*b),
            Op::Leaf(Leaf::State(i)) => x[*i],
            Op::Leaf(_) => 0.0,
            Op::Sum { pos, neg } => {
                pos.iter().map(|c| v(*c)).sum::<f64>() - neg.iter().map(|c| v(*c)).sum::<f64>()
            }
            Op::Mul(a, b) => v(*a) * v(*b),
            Op::Div(a, b) => v(*a) / v(*b),
            Op::Neg(a) => -v(*a),
            Op::Powi(a, k) => v(*a).powi(*k),
            Op::Sqrt(a) => v(*a).sqrt(),
            Op::Powf(a, b) => v(*a).powf(v(*b)),
            Op::Call(f, args) => {
                let xs: Vec<f64> = args.iter().map(|c| v(*c)).collect();
                f.eval_builtin(&xs).unwrap_or(f64::NAN)
            }
        }
    }

    /// The `f64` step of user functions' differences.
    const STEP: f64 = 6.055_454_452_393_343e-6;

    #[test]
    fn a_user_call_is_differenced_along_the_arguments_that_move() {
        let mut ir = Ir::new();
        let (x, y) = (ir.leaf(Leaf::State(0)), ir.leaf(Leaf::State(1)));
        let sx = ir.call(Func::Sin, vec![x]);
        let call = ir.call(Func::User(crate::expr::UserFnId(0)), vec![sx, y]);
        // The distinct user calls `n` reads.
        let calls = |ir: &Ir, n: Nid| {
            let (mut seen, mut stack) = (std::collections::HashSet::new(), vec![n]);
            while let Some(m) = stack.pop() {
                if seen.insert(m) {
                    stack.extend(ir.children(m));
                }
            }
            seen.iter()
                .filter(|m| matches!(ir.op(**m), Op::Call(Func::User(_), _)))
                .count()
        };
        // Along x: the call twice more, its first argument stepped.
        let dx = Tangent::new(Leaf::State(0), STEP).d(&mut ir, call);
        assert_eq!(calls(&ir, dx), 2);
        // Along a leaf no argument reads: the literal zero.
        let dz = Tangent::new(Leaf::State(2), STEP).d(&mut ir, call);
        assert_eq!(ir.as_num(dz), Some(0.0));
    }

    #[test]
    fn values_independent_of_the_leaf_have_literal_zero_derivatives() {
        let mut ir = Ir::new();
        let (x, y) = (ir.leaf(Leaf::State(0)), ir.leaf(Leaf::State(1)));
        // Every rule that divides (quotient, root, inverse sine, atan2,
        // logarithm) would build `0 / ...` from zero derivatives.
        let q = ir.div(x, y);
        let r = ir.sqrt(y);
        let a = ir.call(Func::Asin, vec![y]);
        let t = ir.call(Func::Atan2, vec![y, r]);
        let l = ir.call(Func::Ln, vec![a]);
        let s = ir.sum(vec![r, t, l], Vec::new());
        let independent = ir.mul(s, q);
        let d = Tangent::new(Leaf::State(2), STEP).d(&mut ir, independent);
        assert_eq!(ir.as_num(d), Some(0.0));
        // Along a dependent path the rules still apply.
        let d = Tangent::new(Leaf::State(1), STEP).d(&mut ir, independent);
        assert_eq!(ir.as_num(d), None);
    }

    #[test]
    fn derivatives_match_central_differences() {
        let mut ir = Ir::new();
        let (x, y) = (ir.leaf(Leaf::State(0)), ir.leaf(Leaf::State(1)));
        let s = ir.call(Func::Sin, vec![x]);
        let c = ir.call(Func::Cos, vec![y]);
        let p = ir.mul(s, c);
        let q = ir.div(p, y);
        let r = ir.sqrt(q);
        let a = ir.call(Func::Atan2, vec![x, y]);
        let e = ir.call(Func::Exp, vec![a]);
        let three = ir.num(3.0);
        let pw = ir.powf(y, x);
        let cube = ir.powi(x, 3);
        let m = ir.call(Func::Max, vec![x, cube]);
        let t = ir.call(Func::Tan, vec![x]);
        let as_ = ir.call(Func::Asin, vec![c]);
        let f = ir.sum(vec![r, e, pw, m, t, as_], vec![three]);
        let at = [0.7, 1.3];
        for (k, leaf) in [Leaf::State(0), Leaf::State(1)].into_iter().enumerate() {
            let mut tangent = Tangent::new(leaf, STEP);
            let df = tangent.d(&mut ir, f);
            let h = 1e-6;
            let (mut lo, mut hi) = (at, at);
            lo[k] -= h;
            hi[k] += h;
            let fd = (eval(&ir, f, &hi) - eval(&ir, f, &lo)) / (2.0 * h);
            let got = eval(&ir, df, &at);
            assert!(
                (got - fd).abs() < 1e-7 * (1.0 + fd.abs()),
                "d/dx{k}: {got} vs {fd}"
            );
        }
    }
}

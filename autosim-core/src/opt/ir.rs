//! The program IR: a hash-consed DAG of the operations generated code
//! performs (binary products, signed n-ary sums, divisions, powers, calls),
//! with leaves for parameters, states, inputs, time and user outputs.
//!
//! The symbolic arena keeps expressions canonical (flattened products and
//! sums); this IR keeps them the way they will be computed, so that common
//! pairs of factors and hoisted constants can be shared.

use crate::expr::Func;
use indexmap::IndexSet;
use rustc_hash::FxBuildHasher;

crate::ids::id_type!(
    /// A node of the program IR.
    Nid,
    "IR"
);

/// Values the program reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Leaf {
    /// Parameter number `i` (declaration order).
    Param(usize),
    /// State number `i` (coordinates, speeds, added states).
    State(usize),
    /// Input number `i`.
    Input(usize),
    /// Time.
    Time,
    /// Output `k` of user subroutine `s`.
    SubOut(usize, usize),
    /// du/dt of speed `i` (outputs only; computed by the derivatives).
    Accel(usize),
    /// Discrete variable number `i` (declaration order).
    Discrete(usize),
}

/// An operation.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    /// A float literal (by bits).
    Num(u64),
    /// A value read by the program.
    Leaf(Leaf),
    /// `Σ pos - Σ neg`.
    Sum {
        /// Added terms.
        pos: Box<[Nid]>,
        /// Subtracted terms.
        neg: Box<[Nid]>,
    },
    /// `a * b`.
    Mul(Nid, Nid),
    /// `a / b`.
    Div(Nid, Nid),
    /// `-a`.
    Neg(Nid),
    /// `a^n` for an integer `n ≥ 2`.
    Powi(Nid, i32),
    /// `sqrt(a)`.
    Sqrt(Nid),
    /// `a^b` for a float exponent.
    Powf(Nid, Nid),
    /// A function call.
    Call(Func, Box<[Nid]>),
}

/// The IR: nodes with children before parents.
#[derive(Clone, Debug, Default)]
pub struct Ir {
    nodes: IndexSet<Op, FxBuildHasher>,
    constant: Vec<bool>,
}

impl Ir {
    /// An empty IR.
    pub fn new() -> Ir {
        Ir::default()
    }

    /// The operation of a node.
    pub fn op(&self, n: Nid) -> &Op {
        &self.nodes[n.index()]
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// `true` if empty.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// `true` if the node depends only on parameters and literals.
    pub fn is_constant(&self, n: Nid) -> bool {
        self.constant[n.index()]
    }

    /// The literal value, if the node is one.
    pub fn as_num(&self, n: Nid) -> Option<f64> {
        match self.op(n) {
            Op::Num(b) => Some(f64::from_bits(*b)),
            _ => None,
        }
    }

    /// Every literal's value.
    pub fn literals(&self) -> impl Iterator<Item = f64> + '_ {
        self.nodes.iter().filter_map(|op| match op {
            Op::Num(b) => Some(f64::from_bits(*b)),
            _ => None,
        })
    }

    /// The children of a node.
    pub fn children(&self, n: Nid) -> Vec<Nid> {
        match self.op(n) {
            Op::Num(_) | Op::Leaf(_) => Vec::new(),
            Op::Sum { pos, neg } => pos.iter().chain(neg.iter()).copied().collect(),
            Op::Mul(a, b) | Op::Div(a, b) | Op::Powf(a, b) => vec![*a, *b],
            Op::Neg(a) | Op::Powi(a, _) | Op::Sqrt(a) => vec![*a],
            Op::Call(_, args) => args.to_vec(),
        }
    }

    fn intern(&mut self, op: Op) -> Nid {
        // Leaves other than parameters, and user calls (which may keep
        // state), are variable; everything else is as constant as its
        // operands.
        let own = match &op {
            Op::Leaf(l) => matches!(l, Leaf::Param(_)),
            Op::Call(Func::User(_), _) => false,
            _ => true,
        };
        let (idx, inserted) = self.nodes.insert_full(op);
        if inserted {
            let n = Nid(idx as u32);
            let c = own && self.children(n).iter().all(|k| self.constant[k.index()]);
            self.constant.push(c);
        }
        Nid(idx as u32)
    }

    /// The node of an operation, if it exists (never creates one).
    pub fn find(&self, op: &Op) -> Option<Nid> {
        self.nodes.get_index_of(op).map(|i| Nid(i as u32))
    }

    /// A literal (`-0.0` becomes `0.0`).
    pub fn num(&mut self, x: f64) -> Nid {
        let x = if x == 0.0 { 0.0 } else { x };
        self.intern(Op::Num(x.to_bits()))
    }

    /// A leaf.
    pub fn leaf(&mut self, l: Leaf) -> Nid {
        self.intern(Op::Leaf(l))
    }

    /// `Σ pos - Σ neg`, with literal folding and trivial cases removed.
    pub fn sum(&mut self, pos: Vec<Nid>, neg: Vec<Nid>) -> Nid {
        let mut p: Vec<Nid> = Vec::with_capacity(pos.len());
        let mut m: Vec<Nid> = Vec::with_capacity(neg.len());
        let mut lit = 0.0;
        for x in pos {
            match self.op(x).clone() {
                Op::Num(b) => lit += f64::from_bits(b),
                Op::Neg(y) => m.push(y),
                _ => p.push(x),
            }
        }
        for x in neg {
            match self.op(x).clone() {
                Op::Num(b) => lit -= f64::from_bits(b),
                Op::Neg(y) => p.push(y),
                _ => m.push(x),
            }
        }
        if lit > 0.0 {
            let l = self.num(lit);
            p.push(l);
        } else if lit < 0.0 {
            let l = self.num(-lit);
            m.push(l);
        }
        p.sort();
        m.sort();
        match (p.len(), m.len()) {
            (0, 0) => self.num(0.0),
            (1, 0) => p[0],
            (0, 1) => self.neg(m[0]),
            (0, _) => {
                let s = self.intern(Op::Sum {
                    pos: m.into(),
                    neg: Box::new([]),
                });
                self.neg(s)
            }
            (1, 1) | (2, 0) => self.intern(Op::Sum {
                pos: p.into(),
                neg: m.into(),
            }),
            _ => self.chain(&p, &m),
        }
    }

    /// A sum of three or more terms (added ones first) as a chain of
    /// binary sums, left to right: the order generated code adds them in
    /// anyway, and sums sharing their first terms share their first links
    /// (the absolute angular speeds `u1 + ... + uk` of a chain about
    /// parallel axes cost one addition each, not `k - 1`).
    fn chain(&mut self, p: &[Nid], m: &[Nid]) -> Nid {
        let mut acc = p[0];
        for (k, t) in p.iter().chain(m).enumerate().skip(1) {
            let (pos, neg): (Box<[Nid]>, Box<[Nid]>) = match (k < p.len(), k == 1) {
                // The first link is the ordinary sum of its two terms.
                (true, true) => (Box::new([p[0], *t]), Box::new([])),
                (true, false) => (Box::new([acc, *t]), Box::new([])),
                (false, _) => (Box::new([acc]), Box::new([*t])),
            };
            acc = self.intern(Op::Sum { pos, neg });
        }
        acc
    }

    /// `a * b` (commutative: operands ordered; ±1 and 0 folded).
    pub fn mul(&mut self, a: Nid, b: Nid) -> Nid {
        match (self.as_num(a), self.as_num(b)) {
            (Some(x), Some(y)) => return self.num(x * y),
            (Some(1.0), _) => return b,
            (_, Some(1.0)) => return a,
            (Some(-1.0), _) => return self.neg(b),
            (_, Some(-1.0)) => return self.neg(a),
            (Some(x), _) | (_, Some(x)) if x == 0.0 => return self.num(0.0),
            _ => {}
        }
        // Pull signs out so that -a*b and a*-b share a*b.
        if let Op::Neg(x) = *self.op(a) {
            let p = self.mul(x, b);
            return self.neg(p);
        }
        if let Op::Neg(y) = *self.op(b) {
            let p = self.mul(a, y);
            return self.neg(p);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        if a == b {
            return self.intern(Op::Powi(a, 2));
        }
        self.intern(Op::Mul(a, b))
    }

    /// `a / b`.
    pub fn div(&mut self, a: Nid, b: Nid) -> Nid {
        if let Some(y) = self.as_num(b) {
            if y == 1.0 {
                return a;
            }
            if let Some(x) = self.as_num(a) {
                return self.num(x / y);
            }
        }
        if let Op::Neg(x) = *self.op(a) {
            let q = self.div(x, b);
            return self.neg(q);
        }
        self.intern(Op::Div(a, b))
    }

    /// `-a`; a negation is pushed into a sum that has subtracted terms
    /// (`-(a - b)` is `b - a`), also through a product or quotient.
    pub fn neg(&mut self, a: Nid) -> Nid {
        if let Some(x) = self.as_num(a) {
            return self.num(-x);
        }
        match self.op(a).clone() {
            Op::Neg(x) => return x,
            Op::Sum { pos, neg } if !neg.is_empty() => {
                return self.sum(neg.to_vec(), pos.to_vec());
            }
            Op::Mul(x, y) => {
                for (s, other) in [(y, x), (x, y)] {
                    if matches!(self.op(s), Op::Sum { neg, .. } if !neg.is_empty()) {
                        let ns = self.neg(s);
                        return self.mul(other, ns);
                    }
                }
            }
            Op::Div(x, y) => {
                if matches!(self.op(x), Op::Sum { neg, .. } if !neg.is_empty()) {
                    let nx = self.neg(x);
                    return self.div(nx, y);
                }
            }
            _ => {}
        }
        self.intern(Op::Neg(a))
    }

    /// `a^n` for an integer `n` (negative powers become divisions).
    pub fn powi(&mut self, a: Nid, n: i32) -> Nid {
        match n {
            0 => self.num(1.0),
            1 => a,
            n if n < 0 => {
                let one = self.num(1.0);
                let p = self.powi(a, -n);
                self.div(one, p)
            }
            n => self.intern(Op::Powi(a, n)),
        }
    }

    /// `sqrt(a)`.
    pub fn sqrt(&mut self, a: Nid) -> Nid {
        self.intern(Op::Sqrt(a))
    }

    /// `a^b`.
    pub fn powf(&mut self, a: Nid, b: Nid) -> Nid {
        self.intern(Op::Powf(a, b))
    }

    /// A function call.
    pub fn call(&mut self, f: Func, args: Vec<Nid>) -> Nid {
        self.intern(Op::Call(f, args.into()))
    }
}

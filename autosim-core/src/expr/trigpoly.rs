//! Sums that are identically a number: the Pythagorean identity beyond one
//! angle. A sum of products of sines and cosines (and of anything else,
//! taken as an opaque atom) is expanded into a polynomial over its atoms
//! with `sin(a)^2` replaced by `1 - cos(a)^2` for every angle `a`. That is
//! a normal form (the relations `sin² + cos² - 1` of distinct angles have
//! coprime leading terms, so they are a Gröbner basis): a sum whose normal
//! form is a number is that number for every value of its symbols. This
//! collapses the sums of squared direction cosines of a row or column (1)
//! and the products of two rows or columns (0) that rotating a vector into
//! other axes and back leaves, which `sin² + cos²` of one angle cannot see.
//!
//! The sine and cosine of a sum of angles are expanded into the sines and
//! cosines of its terms (the constructor makes `sin(a + b)` of `sin a cos
//! b + cos a sin b`, `angle_sum.rs`), so the identities see through them.
//!
//! The expansion is bounded ([`MAX_MONOMIALS`]): a sum too big to expand is
//! left as it is, so the check costs little where it cannot help.

use super::arena::{Arena, ExprId, Func, Node};
use super::number::Number;
use std::sync::Arc;

/// The most monomials an expansion may reach before it is abandoned.
const MAX_MONOMIALS: usize = 64;
/// The highest integer power expanded.
const MAX_POWER: i128 = 4;

/// A monomial: atoms with positive exponents, sorted by atom.
type Monomial = Vec<(ExprId, u32)>;
/// A polynomial: monomials with their coefficients, sorted by monomial.
pub(crate) type Poly = Vec<(Monomial, Number)>;

impl Arena {
    /// The number or single term a sum of `constant` and `terms`
    /// (`c · monomial`, at least two of them) is identically, if its
    /// trigonometric normal form is one: `1 - sin(a)^2 cos(b)^2 - ...` of
    /// squared direction cosines to `1`, and a sum that is a product in
    /// disguise, `x + y sin(a) - sin(a) (x sin(a) + y)` (a component of
    /// `w - (w·e) e`), to `x cos(a)^2`.
    pub(crate) fn sum_collapsed(
        &mut self,
        constant: Number,
        terms: &[(ExprId, Number)],
    ) -> Option<ExprId> {
        let poly = self.sum_normal_form(constant, terms)?;
        match poly.as_slice() {
            [] => Some(self.zero()),
            [(mono, c)] if mono.is_empty() => Some(self.num(*c)),
            [(mono, c)] => {
                let factors: Vec<ExprId> = mono
                    .iter()
                    .map(|&(a, k)| self.powi(a, i64::from(k)))
                    .collect();
                Some(self.product_with(*c, &factors))
            }
            _ => None,
        }
    }

    /// The trigonometric normal form of a sum of `constant` and `terms`,
    /// `None` if it has no sine or cosine or is too big to expand.
    fn sum_normal_form(&mut self, constant: Number, terms: &[(ExprId, Number)]) -> Option<Poly> {
        if !terms.iter().any(|t| self.has_trig(t.0)) {
            return None;
        }
        let mut acc: Poly = constant_poly(constant);
        for &(m, c) in terms {
            let p = self.poly_of(m)?;
            acc = add(&acc, &scale(&p, c));
            if acc.len() > MAX_MONOMIALS {
                return None;
            }
        }
        Some(acc)
    }

    /// `true` if `e` has a sine or cosine within two levels (a cheap
    /// filter: direction cosines are products and sums of them).
    fn has_trig(&self, e: ExprId) -> bool {
        fn trig(a: &Arena, e: ExprId, depth: u32) -> bool {
            match a.node(e) {
                Node::Func(Func::Sin | Func::Cos, _) => true,
                _ if depth == 0 => false,
                Node::Sum(cs) | Node::Prod(_, cs) => cs.iter().any(|c| trig(a, *c, depth - 1)),
                Node::Pow(b, _) => trig(a, *b, depth - 1),
                _ => false,
            }
        }
        trig(self, e, 3)
    }

    /// The normal form of `e`, or `None` if it has more than
    /// [`MAX_MONOMIALS`] monomials (memoized per node).
    fn poly_of(&mut self, e: ExprId) -> Option<Arc<Poly>> {
        if let Some(p) = self.poly_memo.get(&e) {
            return p.clone();
        }
        let p = self.expand(e).map(Arc::new);
        self.poly_memo.insert(e, p.clone());
        p
    }

    fn expand(&mut self, e: ExprId) -> Option<Poly> {
        let node = self.node(e).clone();
        let p = match node {
            Node::Num(n) => constant_poly(n),
            Node::Sum(ts) => {
                let mut acc = Poly::new();
                for t in ts.iter() {
                    let p = self.poly_of(*t)?;
                    acc = add(&acc, &p);
                    if acc.len() > MAX_MONOMIALS {
                        return None;
                    }
                }
                acc
            }
            Node::Prod(c, fs) => {
                let mut acc = constant_poly(c);
                for f in fs.iter() {
                    let p = self.poly_of(*f)?;
                    acc = self.poly_mul(&acc, &p)?;
                }
                acc
            }
            Node::Pow(b, x) => match self.as_number(x).and_then(|n| n.as_integer()) {
                Some(n) if (1..=MAX_POWER).contains(&n) => {
                    let base = self.poly_of(b)?;
                    let mut acc = (*base).clone();
                    for _ in 1..n {
                        acc = self.poly_mul(&acc, &base)?;
                    }
                    acc
                }
                _ => atom(e),
            },
            Node::Func(f @ (Func::Sin | Func::Cos), args) if args.len() == 1 => {
                match self.angle_sum_polys(args[0]) {
                    Some((sin, _)) if f == Func::Sin => sin,
                    Some((_, cos)) => cos,
                    None => atom(e),
                }
            }
            _ => atom(e),
        };
        (p.len() <= MAX_MONOMIALS).then_some(p)
    }

    /// The normal forms of `sin(x)` and `cos(x)` of a sum `x = t1 + t2 +
    /// ...`, expanded through `sin(a + b) = sin a cos b + cos a sin b` and
    /// `cos(a + b) = cos a cos b - sin a sin b` into the sines and cosines
    /// of its terms (`angle_sum.rs` makes such nodes of those products).
    /// `None` if `x` is not a sum or the expansion is too big.
    fn angle_sum_polys(&mut self, x: ExprId) -> Option<(Poly, Poly)> {
        let Node::Sum(items) = self.node(x).clone() else {
            return None;
        };
        let (mut sin, mut cos) = self.term_trig_polys(items[0])?;
        for &t in &items[1..] {
            let (st, ct) = self.term_trig_polys(t)?;
            let sc = self.poly_mul(&sin, &ct)?;
            let cs = self.poly_mul(&cos, &st)?;
            let cc = self.poly_mul(&cos, &ct)?;
            let ss = self.poly_mul(&sin, &st)?;
            sin = add(&sc, &cs);
            cos = add(&cc, &scale(&ss, Number::MINUS_ONE));
            if sin.len() > MAX_MONOMIALS || cos.len() > MAX_MONOMIALS {
                return None;
            }
        }
        Some((sin, cos))
    }

    /// The normal forms of `sin(t)` and `cos(t)` of one term of an angle
    /// sum (made if they are not nodes yet: the form of a node must not
    /// depend on what else the arena holds, it is memoized).
    fn term_trig_polys(&mut self, t: ExprId) -> Option<(Poly, Poly)> {
        let (sin, cos) = (self.sin(t), self.cos(t));
        let sin = self.poly_of(sin)?;
        let cos = self.poly_of(cos)?;
        Some(((*sin).clone(), (*cos).clone()))
    }

    /// `a b`, reduced (`sin² → 1 - cos²`), or `None` when too big.
    fn poly_mul(&mut self, a: &Poly, b: &Poly) -> Option<Poly> {
        if a.len() * b.len() > MAX_MONOMIALS * MAX_MONOMIALS {
            return None;
        }
        let mut terms = Poly::new();
        for (ma, ca) in a {
            for (mb, cb) in b {
                let mono = multiply_monomials(ma, mb);
                terms.extend(self.reduce(mono, *ca * *cb));
            }
        }
        let acc = combine(terms);
        (acc.len() <= MAX_MONOMIALS).then_some(acc)
    }

    /// `c mono` with every `sin(a)^k`, `k ≥ 2`, rewritten through
    /// `sin(a)^2 = 1 - cos(a)^2` (where `cos(a)` is a node of the arena).
    fn reduce(&mut self, mono: Monomial, c: Number) -> Poly {
        for (i, &(a, k)) in mono.iter().enumerate() {
            if k < 2 {
                continue;
            }
            let Node::Func(Func::Sin, args) = self.node(a) else {
                continue;
            };
            let Some(cos) = self.find(&Node::Func(Func::Cos, args.clone())) else {
                continue;
            };
            // c m sin^k = c m sin^(k-2) - c m sin^(k-2) cos^2
            let mut rest = mono.clone();
            if k == 2 {
                rest.remove(i);
            } else {
                rest[i].1 = k - 2;
            }
            let with_cos = multiply_monomials(&rest, &[(cos, 2)]);
            let first = self.reduce(rest, c);
            let second = self.reduce(with_cos, -c);
            return add(&first, &second);
        }
        vec![(mono, c)]
    }
}

fn constant_poly(c: Number) -> Poly {
    if c.is_zero() {
        Poly::new()
    } else {
        vec![(Monomial::new(), c)]
    }
}

fn atom(e: ExprId) -> Poly {
    vec![(vec![(e, 1)], Number::ONE)]
}

fn scale(p: &Poly, c: Number) -> Poly {
    if c.is_zero() {
        return Poly::new();
    }
    p.iter().map(|(m, k)| (m.clone(), *k * c)).collect()
}

/// The sum of `terms` as a polynomial, exactly as adding them one at a
/// time with [`add`] gives it (like monomials summed in the order given, a
/// sum that is zero dropped), in one sort instead of a pass per term.
fn combine(mut terms: Poly) -> Poly {
    // Stable: the coefficients of one monomial stay in the order given.
    terms.sort_by(|x, y| x.0.cmp(&y.0));
    let mut out = Poly::with_capacity(terms.len());
    let mut run: Option<(Monomial, Option<Number>)> = None;
    for (mono, c) in terms {
        run = match run {
            Some((m, sum)) if m == mono => {
                // `add` drops a zero sum, and the next term starts afresh.
                let next = match sum {
                    None => c,
                    Some(s) => s + c,
                };
                let zero = sum.is_some() && next.is_zero();
                Some((m, (!zero).then_some(next)))
            }
            previous => {
                out.extend(previous.and_then(|(m, sum)| sum.map(|s| (m, s))));
                Some((mono, Some(c)))
            }
        };
    }
    out.extend(run.and_then(|(m, sum)| sum.map(|s| (m, s))));
    out
}

/// `a + b`, like monomials combined, zeros dropped.
fn add(a: &Poly, b: &Poly) -> Poly {
    let mut out = Poly::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let order = match (a.get(i), b.get(j)) {
            (Some(x), Some(y)) => x.0.cmp(&y.0),
            (Some(_), None) => std::cmp::Ordering::Less,
            _ => std::cmp::Ordering::Greater,
        };
        match order {
            std::cmp::Ordering::Less => {
                out.push(a[i].clone());
                i += 1;
            }
            std::cmp::Ordering::Greater => {
                out.push(b[j].clone());
                j += 1;
            }
            std::cmp::Ordering::Equal => {
                let c = a[i].1 + b[j].1;
                if !c.is_zero() {
                    out.push((a[i].0.clone(), c));
                }
                i += 1;
                j += 1;
            }
        }
    }
    out
}

fn multiply_monomials(a: &[(ExprId, u32)], b: &[(ExprId, u32)]) -> Monomial {
    let mut out = Monomial::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        match (a.get(i), b.get(j)) {
            (Some(x), Some(y)) if x.0 == y.0 => {
                out.push((x.0, x.1 + y.1));
                i += 1;
                j += 1;
            }
            (Some(x), Some(y)) if x.0 < y.0 => {
                out.push(*x);
                i += 1;
            }
            (Some(x), None) => {
                out.push(*x);
                i += 1;
            }
            (_, Some(y)) => {
                out.push(*y);
                j += 1;
            }
            (None, None) => break,
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::expr::{Arena, Bindings, NoUserFunctions, SymbolKind};

    /// The first column of the rotation 3-1-2 (yaw ψ, lean φ, spin θ) of
    /// the rolling disc: squared and summed it is 1, and its product with
    /// the second column is 0; a sum that is not a number is left alone.
    #[test]
    fn squared_direction_cosines_sum_to_one_and_columns_are_orthogonal() {
        let mut a = Arena::new();
        let [psi, phi, theta] = ["psi", "phi", "theta"].map(|n| {
            let s = a.add_symbol(n, SymbolKind::Free).unwrap();
            a.sym(s)
        });
        let (sp, cp) = (a.sin(psi), a.cos(psi));
        let (sf, cf) = (a.sin(phi), a.cos(phi));
        let (st, ct) = (a.sin(theta), a.cos(theta));
        let t = |a: &mut Arena, fs: &[crate::expr::ExprId]| a.product(fs);
        // column 1: (cθ cψ - sθ sφ sψ, -cφ sψ, sθ cψ + cθ sφ sψ)
        let x1 = t(&mut a, &[ct, cp]);
        let x2 = t(&mut a, &[st, sf, sp]);
        let c11 = a.sub(x1, x2);
        let c21 = t(&mut a, &[cf, sp]);
        let c21 = a.neg(c21);
        let y1 = t(&mut a, &[st, cp]);
        let y2 = t(&mut a, &[ct, sf, sp]);
        let c31 = a.add(y1, y2);
        // column 2: (cθ sψ + sθ sφ cψ, cφ cψ, sθ sψ - cθ sφ cψ)
        let z1 = t(&mut a, &[ct, sp]);
        let z2 = t(&mut a, &[st, sf, cp]);
        let c12 = a.add(z1, z2);
        let c22 = t(&mut a, &[cf, cp]);
        let w1 = t(&mut a, &[st, sp]);
        let w2 = t(&mut a, &[ct, sf, cp]);
        let c32 = a.sub(w1, w2);
        let squares = [c11, c21, c31].map(|c| a.powi(c, 2));
        let one = a.sum(&squares);
        assert_eq!(one, a.one(), "{}", a.to_text(one));
        let products = [(c11, c12), (c21, c22), (c31, c32)].map(|(x, y)| a.mul(x, y));
        let zero = a.sum(&products);
        assert_eq!(zero, a.zero(), "{}", a.to_text(zero));
        // Two of the three squares are not a number: kept, same value.
        let two = a.sum(&squares[..2]);
        assert!(a.as_number(two).is_none());
        let mut b = Bindings::with_defaults(&a);
        for (name, v) in [("psi", 0.3), ("phi", -0.7), ("theta", 1.9)] {
            b.set(a.symbol_named(name).unwrap(), v);
        }
        let c31v = a.eval(c31, &b, &mut NoUserFunctions);
        let v = a.eval(two, &b, &mut NoUserFunctions);
        assert!((v - (1.0 - c31v * c31v)).abs() < 1e-15);
    }

    /// A sum that is a single term in disguise collapses to it: `x² + y sin
    /// a - sin a (x² sin a + y)` is `x² cos²a`, and its square root `|x cos
    /// a|` (`|x| |cos a|`); `x / |x|` is `sign(x)` and `x² / |x|` is `|x|`.
    /// A sum whose normal form has two terms, `x² + cos²a`, is kept, and so
    /// is its square root.
    #[test]
    fn sums_that_are_one_term_collapse_and_their_square_roots_are_abs() {
        use crate::expr::{Func, Node};
        let mut a = Arena::new();
        let [x, y, q] = ["x", "y", "q"].map(|n| {
            let s = a.add_symbol(n, SymbolKind::Free).unwrap();
            a.sym(s)
        });
        let (s, c) = (a.sin(q), a.cos(q));
        let x2 = a.powi(x, 2);
        let xs = a.mul(x2, s);
        let inner = a.add(xs, y);
        let proj = a.mul(s, inner);
        let ys = a.mul(y, s);
        let sum = a.sum(&[x2, ys]);
        let e = a.sub(sum, proj);
        let c2 = a.powi(c, 2);
        assert_eq!(e, a.mul(x2, c2), "{}", a.to_text(e));
        let root = a.sqrt(e);
        let (ax, ac) = (a.func(Func::Abs, &[x]), a.func(Func::Abs, &[c]));
        assert_eq!(root, a.mul(ax, ac), "{}", a.to_text(root));
        assert_eq!(a.div(x, ax), a.func(Func::Sign, &[x]));
        assert_eq!(a.div(x2, ax), ax);
        let kept = a.add(x2, c2);
        assert!(matches!(a.node(kept), Node::Sum(_)));
        let root = a.sqrt(kept);
        assert!(matches!(a.node(root), Node::Pow(b, _) if *b == kept));
    }
}

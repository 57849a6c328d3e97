//! Operation counts of expression DAGs: the size measure the paper reports
//! for generated equations (each distinct node counted once, as a program
//! that names every common subexpression would compute it).

use super::arena::{Arena, ExprId, Node};
use super::number::Number;
use rustc_hash::FxHashSet;
use std::fmt;

/// Arithmetic operations needed to evaluate a set of expressions, each
/// distinct DAG node computed once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions and subtractions (`k - 1` for a sum of `k` terms).
    pub adds: usize,
    /// Multiplications.
    pub muls: usize,
    /// Divisions (a factor `x^-1`, or `1/x` on its own).
    pub divs: usize,
    /// Function calls (including `sqrt`).
    pub funcs: usize,
    /// Integer and other non-square-root powers.
    pub pows: usize,
}

impl OpCount {
    /// All operations.
    pub fn total(&self) -> usize {
        self.adds + self.muls + self.divs + self.funcs + self.pows
    }
}

impl fmt::Display for OpCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} adds, {} muls, {} divs, {} funcs, {} pows ({} operations)",
            self.adds,
            self.muls,
            self.divs,
            self.funcs,
            self.pows,
            self.total()
        )
    }
}

impl core::ops::Add for OpCount {
    type Output = OpCount;
    fn add(self, o: OpCount) -> OpCount {
        OpCount {
            adds: self.adds + o.adds,
            muls: self.muls + o.muls,
            divs: self.divs + o.divs,
            funcs: self.funcs + o.funcs,
            pows: self.pows + o.pows,
        }
    }
}

impl Arena {
    /// The exponent of a power node, if it is a number.
    fn numeric_exponent(&self, e: ExprId) -> Option<(ExprId, Number)> {
        match self.node(e) {
            Node::Pow(b, x) => self.as_number(*x).map(|n| (*b, n)),
            _ => None,
        }
    }

    /// Counts the operations of the expressions `roots`, each distinct node
    /// once.
    ///
    /// - a sum of `k` terms: `k - 1` adds (a subtraction is an add);
    /// - a product of `k` factors: `k - 1` multiplications, plus one if the
    ///   coefficient is not ±1; each factor `x^-1` is a division instead of
    ///   a multiplication (`a/b`: one division, and the node `b^-1` is not
    ///   computed on its own). A product of inverses only, `1/(a b)`, is
    ///   `k - 1` multiplications and one division;
    /// - `x^-1` on its own: one division; `sqrt(x)`: one function;
    ///   `x^(-1/2)`: one function and one division; any other power: one
    ///   power;
    /// - a function call: one function. Numbers and symbols are free.
    pub fn op_count(&self, roots: &[ExprId]) -> OpCount {
        let half = Number::rational(1, 2).unwrap_or(Number::ZERO);
        let minus_half = -half;
        let mut count = OpCount::default();
        let mut seen: FxHashSet<ExprId> = FxHashSet::default();
        let mut stack: Vec<ExprId> = roots.to_vec();
        while let Some(x) = stack.pop() {
            if !seen.insert(x) {
                continue;
            }
            match self.node(x) {
                Node::Num(_) | Node::Sym(_) => {}
                Node::Sum(ts) => {
                    count.adds += ts.len().saturating_sub(1);
                    stack.extend(ts.iter().copied());
                }
                Node::Prod(c, fs) => {
                    let coef = usize::from(!(c.is_one() || *c == Number::MINUS_ONE));
                    let mut numer = coef;
                    let mut denom = 0usize;
                    for f in fs.iter() {
                        match self.numeric_exponent(*f) {
                            Some((b, n)) if n == Number::MINUS_ONE => {
                                denom += 1;
                                // The inverse is a division here: visit
                                // only its base.
                                stack.push(b);
                            }
                            _ => {
                                numer += 1;
                                stack.push(*f);
                            }
                        }
                    }
                    if numer == 0 {
                        // 1/(a b ...): multiply the denominators, divide once.
                        count.muls += denom.saturating_sub(1);
                        count.divs += usize::from(denom > 0);
                    } else {
                        count.muls += numer - 1;
                        count.divs += denom;
                    }
                }
                Node::Pow(b, e) => {
                    match self.as_number(*e) {
                        Some(n) if n == Number::MINUS_ONE => count.divs += 1,
                        Some(n) if n == half => count.funcs += 1,
                        Some(n) if n == minus_half => {
                            count.funcs += 1;
                            count.divs += 1;
                        }
                        _ => count.pows += 1,
                    }
                    stack.push(*b);
                    stack.push(*e);
                }
                Node::Func(_, args) => {
                    count.funcs += 1;
                    stack.extend(args.iter().copied());
                }
            }
        }
        count
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn count(text: &str) -> OpCount {
        let mut a = Arena::new();
        let e = a.parse_text(text).unwrap();
        a.op_count(&[e])
    }

    fn ops(adds: usize, muls: usize, divs: usize, funcs: usize, pows: usize) -> OpCount {
        OpCount {
            adds,
            muls,
            divs,
            funcs,
            pows,
        }
    }

    #[test]
    fn leaves_are_free() {
        assert_eq!(count("x"), OpCount::default());
        assert_eq!(count("3/4"), OpCount::default());
        assert_eq!(count("2.5f").total(), 0);
    }

    /// Each text and its counts `[adds, muls, divs, funcs, pows]`.
    const COUNTS: &[(&str, [usize; 5])] = &[
        // Sums and subtractions; -(a + b) is a negated sum: the negation is free.
        ("a + b", [1, 0, 0, 0, 0]),
        ("a - b + c - d", [3, 0, 0, 0, 0]),
        ("-a - b", [1, 0, 0, 0, 0]),
        ("1 + a", [1, 0, 0, 0, 0]),
        // Products, coefficients and divisions.
        ("a*b*c", [0, 2, 0, 0, 0]),
        ("-a*b", [0, 1, 0, 0, 0]),
        ("3*a", [0, 1, 0, 0, 0]),
        ("3*a*b", [0, 2, 0, 0, 0]),
        ("-a", [0, 0, 0, 0, 0]),
        ("a/b", [0, 0, 1, 0, 0]),
        ("a*b/c", [0, 1, 1, 0, 0]),
        ("a/(b*c)", [0, 0, 2, 0, 0]),
        ("3*a/b", [0, 1, 1, 0, 0]),
        ("1/b", [0, 0, 1, 0, 0]),
        ("-1/b", [0, 0, 1, 0, 0]),
        ("1/(a*b)", [0, 1, 1, 0, 0]),
        ("a/2", [0, 1, 0, 0, 0]),
        // Powers and functions.
        ("x^2", [0, 0, 0, 0, 1]),
        ("x^-2", [0, 0, 0, 0, 1]),
        ("sqrt(x)", [0, 0, 0, 1, 0]),
        ("1/sqrt(x)", [0, 0, 1, 1, 0]),
        ("x^(1/3)", [0, 0, 0, 0, 1]),
        ("x^y", [0, 0, 0, 0, 1]),
        ("sin(x)", [0, 0, 0, 1, 0]),
        ("atan2(y, x + 1)", [1, 0, 0, 1, 0]),
        ("a*sin(x)^2", [0, 1, 0, 1, 1]),
    ];

    #[test]
    fn sums_products_powers_and_functions() {
        for (text, [adds, muls, divs, funcs, pows]) in COUNTS {
            assert_eq!(
                count(text),
                ops(*adds, *muls, *divs, *funcs, *pows),
                "{text}"
            );
        }
    }

    #[test]
    fn shared_nodes_count_once() {
        let mut a = Arena::new();
        let s = a.parse_text("sin(x + y)").unwrap();
        let e1 = a.parse_text("a*sin(x + y)").unwrap();
        let e2 = a.parse_text("b + sin(x + y)").unwrap();
        // sin(x + y): 1 add + 1 func, once; a*...: 1 mul; b + ...: 1 add.
        assert_eq!(a.op_count(&[s, e1, e2]), ops(2, 1, 0, 1, 0));
        assert_eq!(a.op_count(&[e1, e1]), ops(1, 1, 0, 1, 0));
        // The node b^-1 used on its own and as a factor: computed once as
        // 1/b, and a*b^-1 is then a division of its own.
        let inv_b = a.parse_text("1/b").unwrap();
        let a_over_b = a.parse_text("a/b").unwrap();
        let c = a.parse_text("c").unwrap();
        let sum = a.add(inv_b, c);
        assert_eq!(a.op_count(&[sum, a_over_b]), ops(1, 0, 2, 0, 0));
        // Common factors are pulled out: a/b + 1/b = (1 + a)/b.
        assert_eq!(count("a/b + 1/b"), ops(1, 0, 1, 0, 0));
    }

    #[test]
    fn display_and_total() {
        let c = ops(1, 2, 3, 4, 5);
        assert_eq!(c.total(), 15);
        assert_eq!(
            c.to_string(),
            "1 adds, 2 muls, 3 divs, 4 funcs, 5 pows (15 operations)"
        );
    }
}

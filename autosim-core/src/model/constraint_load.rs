//! Where a constraint's load acts, read from how its expression is
//! written: at the speed level a constraint is a row `A u`, and when the
//! expression is a sum of `dot(vel(P, Q), d)` and `dot(rot(B), e)` terms
//! (through `let`s, `cross`, sums and factors without velocities; a
//! position constraint the same with `pos` for `vel`, and a distance
//! `mag(pos(P, Q))` as `dot(pos(P, Q), dir(pos(P, Q)))`), the generalized
//! force `Aᵀ λ` is the force `λ d` at `P`, `−λ d` at `Q` and the moment
//! `λ e` on `B`. Each term is read here ([`read`]), then checked against
//! the constraint itself in [`super::constraint_check`]: a load whose
//! generalized force is not `Aᵀ λ` is refused.

use super::scope::{Named, Resolver};
use super::value::Value;
use crate::expr::ExprId;
use crate::mech::{BodyId, ConstraintKind, ConstraintLoad, PointId, Vector};
use crate::syntax::ast::{BinOp, Expr, UnOp};

/// What a velocity-level term moves: a point (relative to another, or to
/// N) or a body's rotation.
#[derive(Clone, Copy, Debug)]
enum Atom {
    /// `vel(P, Q)` (or `pos(P, Q)` in a position constraint).
    Point(PointId, Option<PointId>),
    /// `rot(B)`.
    Body(BodyId),
}

/// How a vector expression holds an atom `a`.
#[derive(Clone, Debug)]
enum Map {
    /// `s a`.
    Scale(ExprId),
    /// `r × a`.
    Left(Vector),
    /// `a × r`.
    Right(Vector),
}

/// The scalar `Σ e·a` over its terms `(a, e)`.
type ScalarForm = Vec<(Atom, Vector)>;

/// The vector `Σ map(a)`.
type VectorForm = Vec<(Atom, Map)>;

/// The load of constraint `g` per unit of its multiplier, read from its
/// expression; `None` when the expression is not a sum of such terms.
pub(super) fn read(r: &mut Resolver<'_>, g: &Expr, kind: ConstraintKind) -> Option<ConstraintLoad> {
    let atoms: &[&str] = match kind {
        ConstraintKind::Position => &["pos"],
        ConstraintKind::Speed => &["vel", "rot"],
    };
    let form = Reader { atoms, depth: 0 }.scalar(r, g)?;
    let mut load = ConstraintLoad::default();
    for (atom, e) in form {
        match atom {
            Atom::Point(p, q) => {
                if let Some(q) = q {
                    let back = e.neg(&mut r.sys.arena);
                    load.forces.push((q, back));
                }
                load.forces.push((p, e));
            }
            Atom::Body(b) => load.moments.push((b, e)),
        }
    }
    Some(load)
}

/// Reads an expression as a form in the atoms named `atoms`.
struct Reader<'n> {
    atoms: &'n [&'n str],
    /// How many `let`s deep (bounded: `let`s resolved without cycles, but
    /// the walk is bounded anyway).
    depth: usize,
}

const MAX_LET_DEPTH: usize = 64;

impl Reader<'_> {
    /// Whether `e` uses an atom, through `let`s too.
    fn mentions(&self, r: &Resolver<'_>, e: &Expr, depth: usize) -> bool {
        if depth > MAX_LET_DEPTH {
            return true;
        }
        match e {
            Expr::Name(n) => match r.names.get(&n.text) {
                Some((Named::Let(i), _)) => self.mentions(r, &r.lets[*i].0.value, depth + 1),
                _ => false,
            },
            Expr::Call { func, args, .. } => {
                self.atoms.contains(&func.text.as_str())
                    || args.iter().any(|a| self.mentions(r, a, depth))
            }
            Expr::Member { base, .. } => self.mentions(r, base, depth),
            Expr::Unary { operand, .. } => self.mentions(r, operand, depth),
            Expr::Binary { lhs, rhs, .. } => {
                self.mentions(r, lhs, depth) || self.mentions(r, rhs, depth)
            }
            Expr::List { items, .. } => items.iter().any(|a| self.mentions(r, a, depth)),
            Expr::As { inner, .. } | Expr::Paren { inner, .. } => self.mentions(r, inner, depth),
            Expr::Number(_) | Expr::Quantity { .. } => false,
        }
    }

    fn plain(&self, r: &Resolver<'_>, e: &Expr) -> bool {
        !self.mentions(r, e, self.depth)
    }

    /// The `let` a name refers to.
    fn let_body<'a>(r: &Resolver<'a>, e: &Expr) -> Option<&'a Expr> {
        let Expr::Name(n) = e else { return None };
        match r.names.get(&n.text) {
            Some((Named::Let(i), _)) => {
                let item: &'a crate::syntax::ast::Let = r.lets[*i].0;
                Some(&item.value)
            }
            _ => None,
        }
    }

    fn deeper(&self) -> Option<Reader<'_>> {
        (self.depth < MAX_LET_DEPTH).then_some(Reader {
            atoms: self.atoms,
            depth: self.depth + 1,
        })
    }

    /// `e` as `Σ e_i·a_i` plus a part without atoms (dropped: the check
    /// against the constraint sees it).
    fn scalar(&self, r: &mut Resolver<'_>, e: &Expr) -> Option<ScalarForm> {
        if self.plain(r, e) {
            return Some(Vec::new());
        }
        if let Some(body) = Self::let_body(r, e) {
            return self.deeper()?.scalar(r, body);
        }
        match e {
            Expr::Paren { inner, .. } | Expr::As { inner, .. } => self.scalar(r, inner),
            Expr::Unary { op, operand, .. } => {
                let f = self.scalar(r, operand)?;
                Some(match op {
                    UnOp::Neg => negate_scalar(r, f),
                    UnOp::Plus => f,
                })
            }
            Expr::Binary { op, lhs, rhs, .. } => match op {
                BinOp::Add | BinOp::Sub => {
                    let mut f = self.scalar(r, lhs)?;
                    let g = self.scalar(r, rhs)?;
                    f.extend(match op {
                        BinOp::Sub => negate_scalar(r, g),
                        _ => g,
                    });
                    Some(f)
                }
                BinOp::Mul | BinOp::Div => {
                    let (s, f) = self.factor(r, *op, lhs, rhs)?;
                    let f = self.scalar(r, f)?;
                    Some(
                        f.into_iter()
                            .map(|(a, e)| (a, e.scale(&mut r.sys.arena, s)))
                            .collect(),
                    )
                }
                _ => None,
            },
            Expr::Call { func, args, .. } if func.text == "dot" && args.len() == 2 => {
                let (v, d) = match self.plain(r, &args[1]) {
                    true => (&args[0], &args[1]),
                    false => (&args[1], &args[0]),
                };
                if !self.plain(r, d) {
                    return None;
                }
                let d = r.vector(d, "`dot`")?;
                let f = self.vector(r, v)?;
                Some(f.into_iter().map(|(a, m)| (a, dotted(r, m, &d))).collect())
            }
            // A length changes along its direction, `d|v| = dir(v)·dv`: a
            // distance `mag(pos(P, Q)) - L` is held along the line.
            Expr::Call { func, args, .. } if func.text == "mag" && args.len() == 1 => {
                let whole = r.vector(&args[0], "`mag`")?;
                let d = r.sys.frames.dir(&mut r.sys.arena, &whole)?;
                let f = self.vector(r, &args[0])?;
                Some(f.into_iter().map(|(a, m)| (a, dotted(r, m, &d))).collect())
            }
            _ => None,
        }
    }

    /// For `lhs * rhs` or `lhs / rhs` with one side a scalar without
    /// atoms: that scalar (inverted for `/`) and the other side.
    fn factor<'e>(
        &self,
        r: &mut Resolver<'_>,
        op: BinOp,
        lhs: &'e Expr,
        rhs: &'e Expr,
    ) -> Option<(ExprId, &'e Expr)> {
        let (s, f) = match (op, self.plain(r, lhs)) {
            (BinOp::Mul, true) => (lhs, rhs),
            (BinOp::Mul, false) | (BinOp::Div, _) => (rhs, lhs),
            _ => return None,
        };
        if !self.plain(r, s) {
            return None;
        }
        let Value::Scalar(s) = r.eval(s)? else {
            return None;
        };
        let s = match op {
            BinOp::Div => {
                let one = r.sys.arena.one();
                r.sys.arena.div(one, s)
            }
            _ => s,
        };
        Some((s, f))
    }

    /// `e` as `Σ map_i(a_i)` plus a part without atoms (dropped).
    fn vector(&self, r: &mut Resolver<'_>, e: &Expr) -> Option<VectorForm> {
        if self.plain(r, e) {
            return Some(Vec::new());
        }
        if let Some(body) = Self::let_body(r, e) {
            return self.deeper()?.vector(r, body);
        }
        match e {
            Expr::Paren { inner, .. } | Expr::As { inner, .. } => self.vector(r, inner),
            Expr::Unary { op, operand, .. } => {
                let f = self.vector(r, operand)?;
                Some(match op {
                    UnOp::Neg => {
                        let m1 = r.sys.arena.int(-1);
                        f.into_iter()
                            .map(|(a, m)| (a, scale_map(r, m, m1)))
                            .collect()
                    }
                    UnOp::Plus => f,
                })
            }
            Expr::Binary { op, lhs, rhs, .. } => match op {
                BinOp::Add | BinOp::Sub => {
                    let mut f = self.vector(r, lhs)?;
                    let g = self.vector(r, rhs)?;
                    let sign = r.sys.arena.int(if *op == BinOp::Sub { -1 } else { 1 });
                    f.extend(g.into_iter().map(|(a, m)| (a, scale_map(r, m, sign))));
                    Some(f)
                }
                BinOp::Mul | BinOp::Div => {
                    let (s, f) = self.factor(r, *op, lhs, rhs)?;
                    let f = self.vector(r, f)?;
                    Some(
                        f.into_iter()
                            .map(|(a, m)| (a, scale_map(r, m, s)))
                            .collect(),
                    )
                }
                _ => None,
            },
            Expr::Call { func, args, .. } => self.call(r, &func.text, args),
            _ => None,
        }
    }

    /// An atom, or `cross` of a vector without atoms and one with.
    fn call(&self, r: &mut Resolver<'_>, func: &str, args: &[Expr]) -> Option<VectorForm> {
        let one = r.sys.arena.one();
        match (func, args) {
            ("rot", [b]) if self.atoms.contains(&"rot") => {
                Some(vec![(Atom::Body(r.body(b, "`rot`")?), Map::Scale(one))])
            }
            ("vel" | "pos", [p, rest @ ..]) if self.atoms.contains(&func) && rest.len() <= 1 => {
                let p = r.point(p, func)?;
                let q = match rest.first() {
                    Some(q) => Some(r.point(q, func)?),
                    None => None,
                };
                Some(vec![(Atom::Point(p, q), Map::Scale(one))])
            }
            ("cross", [a, b]) => {
                let left = self.plain(r, a);
                let (plain, form) = if left { (a, b) } else { (b, a) };
                if !self.plain(r, plain) {
                    return None;
                }
                let w = r.vector(plain, "`cross`")?;
                let form = self.vector(r, form)?;
                form.into_iter()
                    .map(|(atom, m)| {
                        let Map::Scale(s) = m else { return None };
                        let w = w.scale(&mut r.sys.arena, s);
                        Some((atom, if left { Map::Left(w) } else { Map::Right(w) }))
                    })
                    .collect()
            }
            _ => None,
        }
    }
}

fn negate_scalar(r: &mut Resolver<'_>, f: ScalarForm) -> ScalarForm {
    f.into_iter()
        .map(|(a, e)| (a, e.neg(&mut r.sys.arena)))
        .collect()
}

fn scale_map(r: &mut Resolver<'_>, m: Map, s: ExprId) -> Map {
    let arena = &mut r.sys.arena;
    match m {
        Map::Scale(x) => Map::Scale(arena.mul(x, s)),
        Map::Left(w) => Map::Left(w.scale(arena, s)),
        Map::Right(w) => Map::Right(w.scale(arena, s)),
    }
}

/// The `e` with `d·map(a) = e·a`: `s d`, `d × r` for `r × a`, `r × d` for
/// `a × r`.
fn dotted(r: &mut Resolver<'_>, m: Map, d: &Vector) -> Vector {
    let sys = &mut r.sys;
    match m {
        Map::Scale(s) => d.scale(&mut sys.arena, s),
        Map::Left(w) => sys.frames.cross_vec(&mut sys.arena, d, &w),
        Map::Right(w) => sys.frames.cross_vec(&mut sys.arena, &w, d),
    }
}

//! The vector operations of the paper's Table 6 built on dot and cross
//! products: `mag`, `dir`, `dot-plane` and `angle`.

use super::frames::{FrameId, Frames};
use super::vector::Vector;
use crate::expr::{Arena, ExprId, Func, Node};

impl Frames {
    /// `|v| = sqrt(v · v)`.
    pub fn mag(&mut self, arena: &mut Arena, v: &Vector) -> ExprId {
        let vv = self.dot_vec(arena, v, v);
        arena.sqrt(vv)
    }

    /// `v / |v|`, or `None` for the zero vector. Where the length has
    /// factors `|c|` (the squared length simplified to a perfect square)
    /// and `v = c w` in the axes of some frame, `sign(c) w / (|v| / |c|)`
    /// (see `Frames::dir_without_factors`).
    pub fn dir(&mut self, arena: &mut Arena, v: &Vector) -> Option<Vector> {
        if v.is_zero() {
            return None;
        }
        let m = self.mag(arena, v);
        if let Some(d) = self.dir_without_factors(arena, v, m) {
            return Some(d);
        }
        let inv = arena.inv(m);
        Some(v.scale(arena, inv))
    }

    /// `dir(v)` for a length `m = |c| r` with factors `|c|`: `v` expressed
    /// in each frame of its unit vectors and their ancestors, each
    /// component divided by `c`; among the frames where every division
    /// cancels, the one with the fewest operations gives `w`, and
    /// `dir(v) = (c / m) w = sign(c) w / r`. The rolling disc's contact
    /// direction `dir(n3 - (n3·d) d)` has length `|cos φ|` and is `sign(cos
    /// φ)` times the lean frame's third axis: no division by the length
    /// left to differentiate. `None` if `m` has no such factor or no frame
    /// cancels it.
    fn dir_without_factors(&mut self, arena: &mut Arena, v: &Vector, m: ExprId) -> Option<Vector> {
        let factors = abs_factors(arena, m);
        if factors.is_empty() {
            return None;
        }
        let c = arena.product(&factors);
        let mut best: Option<(usize, FrameId, [ExprId; 3])> = None;
        for frame in self.frames_of(v) {
            let comps = self.express_in(arena, v, frame);
            let w = comps.map(|x| arena.div(x, c));
            if w.iter().any(|x| divides_by(arena, *x, &factors)) {
                continue;
            }
            let ops = arena.op_count(&w).total();
            if best.as_ref().is_none_or(|b| ops < b.0) {
                best = Some((ops, frame, w));
            }
        }
        let (_, frame, w) = best?;
        let s = arena.div(c, m);
        Some(self.vector_in(arena, frame, w).scale(arena, s))
    }

    /// The frames of `v`'s unit vectors and all their ancestors, by id.
    fn frames_of(&self, v: &Vector) -> Vec<FrameId> {
        let mut out: Vec<FrameId> = Vec::new();
        for (u, _) in v.terms() {
            let mut f = Some(self.uv(*u).home);
            while let Some(id) = f {
                if !out.contains(&id) {
                    out.push(id);
                }
                f = self.frame(id).parent;
            }
        }
        out.sort();
        out
    }

    /// `a - (a·b)/(b·b) b`: `a` projected on the plane normal to `b`.
    pub fn dot_plane(&mut self, arena: &mut Arena, a: &Vector, b: &Vector) -> Vector {
        let ab = self.dot_vec(arena, a, b);
        let bb = self.dot_vec(arena, b, b);
        let k = arena.div(ab, bb);
        let proj = b.scale(arena, k);
        a.sub(arena, &proj)
    }

    /// The angle from `a` to `b`: in [0, π] without `axis`; signed by the
    /// direction of `axis` (positive when `a × b` points along it, the
    /// paper's Figure 3) with it.
    pub fn angle(
        &mut self,
        arena: &mut Arena,
        a: &Vector,
        b: &Vector,
        axis: Option<&Vector>,
    ) -> ExprId {
        let cosine = self.dot_vec(arena, a, b);
        let axb = self.cross_vec(arena, a, b);
        let sine = match axis {
            Some(c) => {
                let s = self.dot_vec(arena, &axb, c);
                let m = self.mag(arena, c);
                arena.div(s, m)
            }
            None => self.mag(arena, &axb),
        };
        arena.func(Func::Atan2, &[sine, cosine])
    }
}

/// The `c` of each factor `|c|` of `m` (`m` itself or a factor of the
/// product `m`).
fn abs_factors(arena: &Arena, m: ExprId) -> Vec<ExprId> {
    let factors = match arena.node(m) {
        Node::Prod(_, fs) => fs.to_vec(),
        _ => vec![m],
    };
    factors
        .into_iter()
        .filter_map(|f| match arena.node(f) {
            Node::Func(Func::Abs, args) if args.len() == 1 => Some(args[0]),
            _ => None,
        })
        .collect()
}

/// `true` if `e` divides by one of `factors` (has `c^k`, `k < 0`, within).
fn divides_by(arena: &Arena, e: ExprId, factors: &[ExprId]) -> bool {
    let mut seen: Vec<ExprId> = Vec::new();
    let mut stack = vec![e];
    while let Some(x) = stack.pop() {
        if seen.contains(&x) {
            continue;
        }
        seen.push(x);
        if let Node::Pow(b, k) = arena.node(x)
            && factors.contains(b)
            && arena.as_number(*k).is_some_and(|k| k.is_negative())
        {
            return true;
        }
        stack.extend(arena.children(x));
    }
    false
}

#[cfg(test)]
mod tests {
    use crate::expr::{Arena, Bindings, NoUserFunctions};
    use crate::mech::{FrameId, Frames, Vector};

    #[test]
    fn table6_vector_operations_in_numbers() {
        let mut a = Arena::new();
        let mut f = Frames::new();
        let t = f.frame(FrameId::N).triad;
        let n = |a: &mut Arena, k: usize, c: i64| {
            let c = a.int(c);
            Vector::term(a, t[k], c)
        };
        // u = 3 n1 + 4 n2, v = 2 n2
        let u1 = n(&mut a, 0, 3);
        let u2 = n(&mut a, 1, 4);
        let u = u1.add(&mut a, &u2);
        let v = n(&mut a, 1, 2);
        let b = Bindings::with_defaults(&a);
        let ev = |a: &Arena, e| a.eval(e, &b, &mut NoUserFunctions);
        let m = f.mag(&mut a, &u);
        assert_eq!(ev(&a, m), 5.0);
        let d = f.dir(&mut a, &u).unwrap();
        let dm = f.mag(&mut a, &d);
        assert!((ev(&a, dm) - 1.0).abs() < 1e-15);
        assert!(f.dir(&mut a, &Vector::zero()).is_none());
        let p = f.dot_plane(&mut a, &u, &v);
        // Only the n1 part is left.
        let pv = f.dot_vec(&mut a, &p, &v);
        assert_eq!(ev(&a, pv), 0.0);
        let n3 = n(&mut a, 2, 1);
        let ang = f.angle(&mut a, &u, &v, Some(&n3));
        assert!((ev(&a, ang) - (3.0f64).atan2(4.0)).abs() < 1e-15);
        let back = f.angle(&mut a, &v, &u, Some(&n3));
        assert!((ev(&a, back) + (3.0f64).atan2(4.0)).abs() < 1e-15);
        let unsigned = f.angle(&mut a, &v, &u, None);
        assert!((ev(&a, unsigned) - (3.0f64).atan2(4.0)).abs() < 1e-15);
    }

    /// The rolling disc's contact direction, `dir(n3 - (n3·d2) d2)` with
    /// `d` yawed by ψ, leaned by φ and spun by θ: its squared length
    /// `1 - sin²φ` is `cos²φ`, so its length is `|cos φ|`, and the direction
    /// is `sign(cos φ)` times the lean frame's third axis, with no division
    /// left; its value is `v / |v|` on both sides of `cos φ = 0`. A length
    /// that is no perfect square, `|n1 + sin φ n2|`, stays a square root.
    #[test]
    fn direction_of_a_vector_whose_length_is_a_perfect_square() {
        use crate::expr::{Func, Node, Number, SymbolKind};
        use crate::mech::Axis;
        let mut a = Arena::new();
        let mut f = Frames::new();
        let [psi, phi, theta] = ["psi", "phi", "theta"].map(|n| {
            let s = a.add_symbol(n, SymbolKind::Free).unwrap();
            a.sym(s)
        });
        let y = f.add_rotated(&mut a, FrameId::N, Axis::A3, psi, "Y", "y");
        let l = f.add_rotated(&mut a, y, Axis::A1, phi, "L", "l");
        let d = f.add_rotated(&mut a, l, Axis::A2, theta, "D", "d");
        let n3 = Vector::uv(&mut a, f.frame(FrameId::N).triad[2]);
        let d2 = Vector::uv(&mut a, f.frame(d).triad[1]);
        let along = f.dot_vec(&mut a, &n3, &d2);
        let proj = d2.scale(&mut a, along);
        let v = n3.sub(&mut a, &proj);
        let m = f.mag(&mut a, &v);
        let cos_phi = a.cos(phi);
        assert_eq!(m, a.func(Func::Abs, &[cos_phi]), "{}", a.to_text(m));
        let dv = f.dir(&mut a, &v).unwrap();
        let l3 = f.frame(l).triad[2];
        assert_eq!(dv.terms().len(), 1);
        assert_eq!(dv.terms()[0].0, l3);
        assert_eq!(dv.terms()[0].1, a.func(Func::Sign, &[cos_phi]));
        let dn = f.express_in(&mut a, &dv, FrameId::N);
        let vn = f.express_in(&mut a, &v, FrameId::N);
        for phi_v in [0.4, 2.5, -1.9] {
            let mut b = Bindings::with_defaults(&a);
            for (name, x) in [("psi", 0.3), ("phi", phi_v), ("theta", 1.1)] {
                b.set(a.symbol_named(name).unwrap(), x);
            }
            let ev = |e| a.eval(e, &b, &mut NoUserFunctions);
            let len = ev(m);
            assert!((len - phi_v.cos().abs()).abs() < 1e-15);
            for k in 0..3 {
                assert!((ev(dn[k]) - ev(vn[k]) / len).abs() < 1e-15, "{phi_v} {k}");
            }
        }
        // |n1 + sin φ n2| = sqrt(1 + sin²φ): not a perfect square.
        let n1 = Vector::uv(&mut a, f.frame(FrameId::N).triad[0]);
        let n2 = Vector::uv(&mut a, f.frame(FrameId::N).triad[1]);
        let sin_phi = a.sin(phi);
        let side = n2.scale(&mut a, sin_phi);
        let u = n1.add(&mut a, &side);
        let mu = f.mag(&mut a, &u);
        let half = Number::rational(1, 2).unwrap();
        assert!(
            matches!(a.node(mu), Node::Pow(_, x) if a.as_number(*x) == Some(half)),
            "{}",
            a.to_text(mu)
        );
        let du = f.dir(&mut a, &u).unwrap();
        let inv = a.inv(mu);
        assert_eq!(du, u.scale(&mut a, inv));
    }
}

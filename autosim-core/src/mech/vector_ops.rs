//! The vector operations of the paper's Table 6 built on dot and cross
//! products: `mag`, `dir`, `dot-plane` and `angle`.

use super::frames::Frames;
use super::vector::Vector;
use crate::expr::{Arena, ExprId, Func};

impl Frames {
    /// `|v| = sqrt(v · v)`.
    pub fn mag(&mut self, arena: &mut Arena, v: &Vector) -> ExprId {
        let vv = self.dot_vec(arena, v, v);
        arena.sqrt(vv)
    }

    /// `v / |v|`, or `None` for the zero vector.
    pub fn dir(&mut self, arena: &mut Arena, v: &Vector) -> Option<Vector> {
        if v.is_zero() {
            return None;
        }
        let m = self.mag(arena, v);
        let inv = arena.inv(m);
        Some(v.scale(arena, inv))
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
}

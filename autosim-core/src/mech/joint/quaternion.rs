//! Euler parameters: the body's orientation as a unit quaternion
//! `e0..e3` (free of singularities). `e1..e3` are coordinates paired with
//! the three speeds (the angular velocity relative to the parent in body
//! axes); `e0` is an extra state with its own rate.

use super::symbols::RotationParts;
use super::{Axis, DofKind};
use crate::expr::{Arena, ExprId, Number, SymId};
use crate::mech::error::ModelError;
use crate::mech::frames::FrameId;
use crate::mech::system::System;

/// What the quaternion needs of its body.
pub(super) struct QuaternionBody<'a> {
    /// The body's name.
    pub name: &'a str,
    /// The name of `e0`.
    pub e0_name: &'a str,
    /// The initial value of `e0`.
    pub e0_initial: ExprId,
}

impl System {
    /// The body's frame from its Euler parameters, the relative angular
    /// velocity, and the rates of `e1, e2, e3` (`e0` becomes an added state
    /// with its own rate).
    ///
    /// `C_ij = b_i · a_j` in terms of `e0..e3`, and `de/dt = ½ e ⊗ (0, ω)`
    /// with `ω` the angular velocity relative to the parent in body axes.
    pub(super) fn quaternion_rotation(
        &mut self,
        body: &QuaternionBody<'_>,
        frame: FrameId,
        syms: &[(SymId, SymId)],
    ) -> Result<RotationParts, ModelError> {
        let mut w: [ExprId; 3] = [self.arena.zero(); 3];
        for (k, w) in w.iter_mut().enumerate() {
            *w = self.arena.sym(syms[k].1);
        }
        if self.arena.symbol_named(body.e0_name).is_some()
            || self.body_named(body.e0_name).is_some()
        {
            return Err(ModelError::DuplicateName(body.e0_name.to_string()));
        }
        let e0s = self.add_state(body.e0_name, Some("1"), body.e0_initial)?;
        let e = [
            self.arena.sym(e0s),
            self.arena.sym(syms[0].0),
            self.arena.sym(syms[1].0),
            self.arena.sym(syms[2].0),
        ];
        let c = cosine_matrix(&mut self.arena, &e);
        let prefix = body.name.to_lowercase();
        let frame = self
            .frames
            .add_general(&mut self.arena, frame, c, body.name, &prefix);
        let [e0dot, e1dot, e2dot, e3dot] = rates(&mut self.arena, &e, &w);
        self.set_state_derivative(e0s, e0dot)?;
        Ok(RotationParts {
            frame,
            rotation_frames: Vec::new(),
            w_rel: w,
            kinds: Axis::ALL.map(|axis| DofKind::Rotation { axis }).to_vec(),
            rates: Some(vec![e1dot, e2dot, e3dot]),
        })
    }
}

/// `C_ij = b_i · a_j` of the Euler parameters `e`.
fn cosine_matrix(a: &mut Arena, e: &[ExprId; 4]) -> [[ExprId; 3]; 3] {
    let sq = e.map(|x| a.powi(x, 2));
    let two = Number::int(2);
    let mut pr = |i: usize, j: usize| a.mul(e[i], e[j]);
    let (e01, e02, e03, e12, e13, e23) =
        (pr(0, 1), pr(0, 2), pr(0, 3), pr(1, 2), pr(1, 3), pr(2, 3));
    let lin = |a: &mut Arena, p: ExprId, m: ExprId| {
        let d = a.sub(p, m);
        a.scale(two, d)
    };
    let plus = |a: &mut Arena, p: ExprId, m: ExprId| {
        let d = a.add(p, m);
        a.scale(two, d)
    };
    let diag = |a: &mut Arena, k: usize| {
        let mut terms = vec![sq[0]];
        for (i, s) in sq.iter().enumerate().skip(1) {
            terms.push(if i == k { *s } else { a.neg(*s) });
        }
        a.sum(&terms)
    };
    [
        [diag(a, 1), plus(a, e12, e03), lin(a, e13, e02)],
        [lin(a, e12, e03), diag(a, 2), plus(a, e23, e01)],
        [plus(a, e13, e02), lin(a, e23, e01), diag(a, 3)],
    ]
}

/// `ė0 = -½ (e1 ω1 + e2 ω2 + e3 ω3)`, `ė = ½ (e0 ω + e × ω)`.
fn rates(a: &mut Arena, e: &[ExprId; 4], w: &[ExprId; 3]) -> [ExprId; 4] {
    let half = Number::rational(1, 2).unwrap_or(Number::ONE);
    let mut rate = |terms: [(ExprId, ExprId, i64); 3]| {
        let parts: Vec<ExprId> = terms
            .iter()
            .map(|(x, y, s)| {
                let p = a.mul(*x, *y);
                a.scale(Number::int(*s), p)
            })
            .collect();
        let sum = a.sum(&parts);
        a.scale(half, sum)
    };
    [
        rate([(e[1], w[0], -1), (e[2], w[1], -1), (e[3], w[2], -1)]),
        rate([(e[0], w[0], 1), (e[2], w[2], 1), (e[3], w[1], -1)]),
        rate([(e[0], w[1], 1), (e[3], w[0], 1), (e[1], w[2], -1)]),
        rate([(e[0], w[2], 1), (e[1], w[1], 1), (e[2], w[0], -1)]),
    ]
}

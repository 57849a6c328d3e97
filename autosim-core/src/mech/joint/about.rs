//! A rotation about a constant direction `d` fixed in the parent (the
//! paper's `d_rot`, Table 7), such as a bicycle's tilted steering axis.
//!
//! Without a reference direction the body's axes coincide with the
//! parent's at zero angle, and the frame is the parent's turned by `q`
//! about `d` (Rodrigues: `C = cos q I − sin q [d]× + (1 − cos q) d dᵀ`,
//! `C_ij = b_i · a_j`). With a reference direction `r` the body's nominal
//! axes follow the paper's Eq. 8 — `b3 = d`, `b2 = d × r / |d × r|`,
//! `b1 = b2 × b3` — and the body turns about its axis 3 from there. Either
//! way the speed is `u = dq/dt` and the angular velocity relative to the
//! parent is `u d`.

use super::symbols::RotationParts;
use super::{Axis, DofKind};
use crate::expr::{Arena, ExprId, SymId};
use crate::mech::frames::FrameId;
use crate::mech::system::System;

/// `v / |v|`.
pub(crate) fn normalized(a: &mut Arena, v: &[ExprId; 3]) -> [ExprId; 3] {
    let sq: Vec<ExprId> = v.iter().map(|x| a.powi(*x, 2)).collect();
    let s = a.sum(&sq);
    let len = a.sqrt(s);
    v.map(|x| a.div(x, len))
}

/// `a × b` of components.
fn cross(ar: &mut Arena, a: &[ExprId; 3], b: &[ExprId; 3]) -> [ExprId; 3] {
    let mut c = [ar.zero(); 3];
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let p = ar.mul(a[j], b[k]);
        let m = ar.mul(a[k], b[j]);
        c[i] = ar.sub(p, m);
    }
    c
}

/// The direction-cosine matrix of a turn by `q` about the unit vector `d`.
pub(crate) fn rodrigues(a: &mut Arena, d: &[ExprId; 3], q: ExprId) -> [[ExprId; 3]; 3] {
    let s = a.sin(q);
    let c = a.cos(q);
    let one = a.one();
    let one_minus_c = a.sub(one, c);
    let mut m = [[a.zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let ddt = a.mul(d[i], d[j]);
            let mut terms = vec![a.mul(one_minus_c, ddt)];
            if i == j {
                terms.push(c);
            } else {
                // −sin q [d]×: [d]×_ij = −ε_ijk d_k, so the term is s ε_ijk d_k.
                let k = 3 - i - j;
                let sign = if (j + 3 - i) % 3 == 1 { 1 } else { -1 };
                let sd = a.mul(s, d[k]);
                terms.push(a.scale(crate::expr::Number::int(sign), sd));
            }
            m[i][j] = a.sum(&terms);
        }
    }
    m
}

impl System {
    /// The frame turned from `frame` by `angle` about `direction` (parent
    /// axes), with an optional reference direction, and the unit motion of
    /// the turn's speed in the new frame's axes.
    pub(crate) fn about_frame(
        &mut self,
        (name, prefix): (&str, &str),
        frame: FrameId,
        (direction, reference): (&[ExprId; 3], Option<&[ExprId; 3]>),
        angle: ExprId,
    ) -> (FrameId, DofKind) {
        let d = normalized(&mut self.arena, direction);
        let Some(r) = reference else {
            let c = rodrigues(&mut self.arena, &d, angle);
            let frame = self
                .frames
                .add_general(&mut self.arena, frame, c, name, prefix);
            return (frame, DofKind::RotationAbout { direction: d });
        };
        // The nominal axes of Eq. 8 as a constant frame, then a turn about
        // its axis 3.
        let b2 = cross(&mut self.arena, &d, r);
        let b2 = normalized(&mut self.arena, &b2);
        let b1 = cross(&mut self.arena, &b2, &d);
        let nominal = self.frames.add_general(
            &mut self.arena,
            frame,
            [b1, b2, d],
            &format!("{name}#ref"),
            &format!("{prefix}#ref_"),
        );
        let w = self.frame_w[frame.index()].clone();
        self.frame_w.push(w);
        let turned =
            self.frames
                .add_rotated(&mut self.arena, nominal, Axis::A3, angle, name, prefix);
        (turned, DofKind::Rotation { axis: Axis::A3 })
    }

    /// The body's frame and relative angular velocity for a rotation about
    /// `direction` (parent axes), with an optional reference direction.
    pub(super) fn rotation_about(
        &mut self,
        name: &str,
        frame: FrameId,
        direction: &[ExprId; 3],
        reference: Option<&[ExprId; 3]>,
        (q, u): (SymId, SymId),
    ) -> RotationParts {
        let prefix = name.to_lowercase();
        let angle = self.arena.sym(q);
        let (frame, kind) = self.about_frame((name, &prefix), frame, (direction, reference), angle);
        let speed = self.arena.sym(u);
        let w_rel = match &kind {
            DofKind::RotationAbout { direction } => direction.map(|x| self.arena.mul(x, speed)),
            _ => {
                let mut w = [self.arena.zero(); 3];
                w[2] = speed;
                w
            }
        };
        RotationParts {
            frame,
            rotation_frames: Vec::new(),
            w_rel,
            kinds: vec![kind],
            rates: None,
        }
    }
}

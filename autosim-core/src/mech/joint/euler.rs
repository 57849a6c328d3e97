//! Three body-fixed rotations in sequence (e.g. 1-2-3 or 3-1-3): a chain of
//! three frames `B''`, `B'`, `B`, speeds that are the angular velocity
//! relative to the parent in the body's axes, and the rates
//! `dq/dt = E⁻¹ ω` (singular where the first and third axes line up).

use super::symbols::RotationParts;
use super::{Axis, DofKind};
use crate::expr::{ExprId, SymId};
use crate::mech::frames::FrameId;
use crate::mech::system::System;
use crate::mech::vector::Vector;

impl System {
    /// The three frames and the relative angular velocity in body axes.
    pub(super) fn rotation_sequence(
        &mut self,
        name: &str,
        mut frame: FrameId,
        axes: [Axis; 3],
        syms: &[(SymId, SymId)],
    ) -> RotationParts {
        let prefix = name.to_lowercase();
        let mut rotation_frames = Vec::with_capacity(3);
        for (k, &axis) in axes.iter().enumerate() {
            let q = self.arena.sym(syms[k].0);
            let primes = "'".repeat(2 - k);
            frame = self.frames.add_rotated(
                &mut self.arena,
                frame,
                axis,
                q,
                &format!("{name}{primes}"),
                &format!("{prefix}{primes}"),
            );
            rotation_frames.push(frame);
        }
        let mut w_rel: [ExprId; 3] = [self.arena.zero(); 3];
        for (k, w) in w_rel.iter_mut().enumerate() {
            *w = self.arena.sym(syms[k].1);
        }
        RotationParts {
            frame,
            rotation_frames,
            w_rel,
            kinds: Axis::ALL.map(|axis| DofKind::Rotation { axis }).to_vec(),
            rates: None,
        }
    }

    /// dq/dt of the three angles from the angular velocity components:
    /// q̇ = E⁻¹ ω with E's rows from cross products of the rotation axes
    /// (`det = e1 · (e2 × e3)`).
    pub(super) fn euler_rates(
        &mut self,
        axes: [Axis; 3],
        rotation_frames: &[FrameId],
        parent_frame: FrameId,
        w_rel: &[ExprId; 3],
    ) -> [ExprId; 3] {
        let body_frame = rotation_frames[2];
        let e1u = self.frames.frame(parent_frame).triad[axes[0].index()];
        let e2u = self.frames.frame(rotation_frames[0]).triad[axes[1].index()];
        let e3u = self.frames.frame(rotation_frames[1]).triad[axes[2].index()];
        let e = [e1u, e2u, e3u].map(|u| Vector::uv(&mut self.arena, u));
        let w = self.frames.vector_in(&mut self.arena, body_frame, *w_rel);
        let c23 = self.frames.cross_vec(&mut self.arena, &e[1], &e[2]);
        let c31 = self.frames.cross_vec(&mut self.arena, &e[2], &e[0]);
        let c12 = self.frames.cross_vec(&mut self.arena, &e[0], &e[1]);
        let det = self.frames.dot_vec(&mut self.arena, &e[0], &c23);
        let mut out = [self.arena.zero(); 3];
        for (k, c) in [c23, c31, c12].iter().enumerate() {
            let n = self.frames.dot_vec(&mut self.arena, c, &w);
            out[k] = self.arena.div(n, det);
        }
        out
    }
}

//! A simple rotation: the body turns about one axis of its parent, which it
//! shares (the paper's Table 8: `c1, c2, b3`); its speed is `dq/dt`.

use super::symbols::RotationParts;
use super::{Axis, DofKind};
use crate::expr::{ExprId, SymId};
use crate::mech::frames::FrameId;
use crate::mech::system::System;

impl System {
    /// The body's frame, rotated from `frame` about `axis` by `q`, and the
    /// relative angular velocity `u` about that axis.
    pub(super) fn simple_rotation(
        &mut self,
        name: &str,
        frame: FrameId,
        axis: Axis,
        (q, u): (SymId, SymId),
    ) -> RotationParts {
        let angle = self.arena.sym(q);
        let prefix = name.to_lowercase();
        let frame = self
            .frames
            .add_rotated(&mut self.arena, frame, axis, angle, name, &prefix);
        let mut w_rel: [ExprId; 3] = [self.arena.zero(); 3];
        w_rel[axis.index()] = self.arena.sym(u);
        RotationParts {
            frame,
            rotation_frames: vec![frame],
            w_rel,
            kinds: vec![DofKind::Rotation { axis }],
            rates: None,
        }
    }
}

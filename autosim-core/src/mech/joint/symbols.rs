//! Building a joint into the system: the symbols of its degrees of
//! freedom, its frames (constant rotations first, then the rotation's), the
//! relative angular velocity, the kinematical equations and the angular
//! velocities of the new frames (the paper's Eqs. 8-10).

use super::quaternion::QuaternionBody;
use super::{DofKind, FixedTurn, Rotation};
use crate::expr::{ExprId, SymId, SymbolKind};
use crate::mech::error::ModelError;
use crate::mech::frames::FrameId;
use crate::mech::system::{BodySpec, System};
use crate::mech::vector::Vector;

/// The symbols `(q, u, du/dt)` of each degree of freedom of a body.
pub(crate) type DofSymbols = Vec<(SymId, SymId, SymId)>;

/// What a rotation kind builds.
pub(super) struct RotationParts {
    /// The body's frame.
    pub frame: FrameId,
    /// The frames of the rotations, one per axis rotated about.
    pub rotation_frames: Vec<FrameId>,
    /// The angular velocity relative to the parent, body axes.
    pub w_rel: [ExprId; 3],
    /// The unit motion of each rotational speed.
    pub kinds: Vec<DofKind>,
    /// dq/dt of the rotational coordinates, where not `u` (nor computed
    /// later, as a sequence's are).
    pub rates: Option<Vec<ExprId>>,
}

/// What building a joint gives its body.
pub(crate) struct BuiltJoint {
    /// The body's frame (its parent's if it does not rotate).
    pub frame: FrameId,
    /// The angular velocity relative to the parent, body axes.
    pub w_rel: [ExprId; 3],
    /// The unit motion of each rotational speed (after the translations').
    pub rotation_kinds: Vec<DofKind>,
    /// dq/dt of every coordinate paired with a speed.
    pub qdots: Vec<ExprId>,
}

impl System {
    /// Declares `q`, `u` and `u_dot` of every degree of freedom, with
    /// units, smallness and `du/dt`.
    pub(crate) fn dof_symbols(&mut self, spec: &BodySpec) -> Result<DofSymbols, ModelError> {
        let joint = &spec.joint;
        let first = self.coordinates.len();
        let mut syms = Vec::with_capacity(joint.dofs());
        for k in 0..joint.dofs() {
            let global = first + k;
            let qn = spec
                .coordinate_names
                .as_ref()
                .map(|v| v[joint.coordinate_of_speed(k)].clone())
                .unwrap_or_else(|| format!("q{}", global + 1));
            let un = spec
                .speed_names
                .as_ref()
                .map(|v| v[k].clone())
                .unwrap_or_else(|| format!("u{}", global + 1));
            let dn = format!("{un}_dot");
            for n in [&qn, &un, &dn] {
                if self.arena.symbol_named(n).is_some() || self.body_named(n).is_some() {
                    return Err(ModelError::DuplicateName(n.clone()));
                }
            }
            let q = self
                .arena
                .add_symbol(&qn, SymbolKind::Coordinate { index: global })?;
            let u = self
                .arena
                .add_symbol(&un, SymbolKind::Speed { index: global })?;
            let du = self
                .arena
                .add_symbol(&dn, SymbolKind::SpeedRate { index: global })?;
            let (qu, uu) = if k < joint.translations.len() {
                ("m", "m/s")
            } else {
                ("rad", "rad/s")
            };
            self.arena.set_unit(q, Some(qu.to_string()));
            self.arena.set_unit(u, Some(uu.to_string()));
            self.arena.set_unit(du, Some(format!("{uu}^2")));
            let small = spec.small.get(k).copied().unwrap_or(false);
            for s in [q, u, du] {
                self.arena.set_small(s, small);
            }
            let du_e = self.arena.sym(du);
            self.arena.set_dxdt(u, du_e);
            syms.push((q, u, du));
        }
        Ok(syms)
    }

    /// The frames, relative angular velocity and kinematical equations of
    /// a body's joint (its translations' directions are built before).
    pub(crate) fn build_joint(
        &mut self,
        spec: &BodySpec,
        parent_frame: FrameId,
        syms: &DofSymbols,
    ) -> Result<BuiltJoint, ModelError> {
        let name = &spec.name;
        let prefix = name.to_lowercase();
        let mut frame = parent_frame;
        for (k, (turn, angle)) in spec.fixed_rotations.iter().enumerate() {
            let (tag, uv) = (format!("{name}#{k}"), format!("{prefix}#{k}_"));
            frame = match turn {
                FixedTurn::Axis(axis) => {
                    self.frames
                        .add_rotated(&mut self.arena, frame, *axis, *angle, &tag, &uv)
                }
                FixedTurn::About {
                    direction,
                    reference,
                } => {
                    let about = (direction, reference.as_ref());
                    self.about_frame((&tag, &uv), frame, about, *angle).0
                }
            };
            let w = self.frame_w[parent_frame.index()].clone();
            self.frame_w.push(w);
        }
        let nt = spec.joint.translations.len();
        let rot: Vec<(SymId, SymId)> = syms[nt..].iter().map(|s| (s.0, s.1)).collect();
        let rotation = spec.joint.rotation.clone();
        let parts = match &rotation {
            Rotation::None => RotationParts {
                frame,
                rotation_frames: Vec::new(),
                w_rel: [self.arena.zero(); 3],
                kinds: Vec::new(),
                rates: None,
            },
            Rotation::Simple(axis) => self.simple_rotation(name, frame, *axis, rot[0]),
            Rotation::Sequence(axes) => self.rotation_sequence(name, frame, *axes, &rot),
            Rotation::About {
                direction,
                reference,
            } => self.rotation_about(name, frame, direction, reference.as_ref(), rot[0]),
            Rotation::Quaternion => {
                let e0_name = spec
                    .coordinate_names
                    .as_ref()
                    .map(|v| v[nt].clone())
                    .unwrap_or_else(|| format!("{name}_e0"));
                let e0_initial = spec
                    .initial_coordinates
                    .as_ref()
                    .and_then(|v| v.get(nt).copied())
                    .unwrap_or(self.arena.one());
                let body = QuaternionBody {
                    name,
                    e0_name: &e0_name,
                    e0_initial,
                };
                self.quaternion_rotation(&body, frame, &rot)?
            }
        };

        // Kinematical equations dq/dt = f(q, u).
        let mut qdots: Vec<ExprId> = syms.iter().map(|s| self.arena.sym(s.1)).collect();
        if let Some(rates) = &parts.rates {
            qdots[nt..].copy_from_slice(rates);
        }
        if let Rotation::Sequence(axes) = rotation {
            let rates = self.euler_rates(axes, &parts.rotation_frames, frame, &parts.w_rel);
            qdots[nt..].copy_from_slice(&rates);
        }

        // Angular velocities of the rotation's intermediate frames (the
        // body's own is set with its velocity).
        let mut w_frame = self.frame_w[parent_frame.index()].clone();
        let axes = rotation.axes();
        for (k, f) in parts.rotation_frames.iter().enumerate() {
            let from = self.frames.frame(*f).parent.unwrap_or(FrameId::N);
            let e = self.frames.frame(from).triad[axes[k].index()];
            let t = Vector::term(&mut self.arena, e, qdots[nt + k]);
            w_frame = w_frame.add(&mut self.arena, &t);
            if k + 1 < axes.len() {
                debug_assert_eq!(self.frame_w.len(), f.index());
                self.frame_w.push(w_frame.clone());
            }
        }
        Ok(BuiltJoint {
            frame: parts.frame,
            w_rel: parts.w_rel,
            rotation_kinds: parts.kinds,
            qdots,
        })
    }
}

//! Kane's equations for tree systems in composite-body form.
//!
//! For a speed `u_k` of body `K`, every point of `K`'s subtree has partial
//! velocity `d_k` (translation along `d_k`) or `e_k × r` (rotation about
//! `e_k` through `K`'s origin), and every body of the subtree has partial
//! angular velocity `0` or `e_k`; bodies outside the subtree have none. So
//! the generalized active plus inertia force of `u_k` is `d_k · R_K` or
//! `e_k · H_K`, where `R_K` and `H_K` are the resultant force and the moment
//! about `K`'s origin of all applied and (velocity-dependent) inertia forces
//! on the subtree. Those are accumulated from the leaves inward, each body's
//! in its own axes, which keeps the expressions of size O(1) per body.
//! Likewise the mass matrix `M_kl` is `d_k · P_l + e_k · H_l` with the
//! momentum of the subtree of `l` moving at unit rate `u_l` (composite
//! mass, first moment and inertia), carried inward body by body. Gravity is
//! an acceleration `-g` of N. The mass matrix is never inverted: the
//! accelerations are solved numerically by the caller.

mod body_kinetics;
mod constraints;
mod loads;
mod mass;
mod reactions;
mod recursion;

pub use body_kinetics::{BodyKinetics, TreeKinetics};
pub use constraints::{ConstraintEquations, ConstraintRow, Prescribed};
pub use reactions::JointReaction;

use super::error::{ItemRef, LocatedError, ModelError};
use super::joint::UnitMotion;
use super::system::System;
use crate::expr::{ExprId, SymId};

/// The equations of motion `dq/dt = f(q, u)`, `M(q) du/dt = f(q, u, t)`.
#[derive(Clone, Debug)]
pub struct Equations {
    /// Generalized coordinates.
    pub coordinates: Vec<SymId>,
    /// Generalized speeds.
    pub speeds: Vec<SymId>,
    /// Symbols for du/dt.
    pub speed_rates: Vec<SymId>,
    /// dq/dt for each coordinate.
    pub kinematics: Vec<ExprId>,
    /// The mass matrix, symmetric, `n × n`.
    pub mass_matrix: Vec<Vec<ExprId>>,
    /// The forcing vector: generalized active forces plus the
    /// velocity-dependent generalized inertia forces.
    pub forcing: Vec<ExprId>,
    /// Added state variables.
    pub states: Vec<SymId>,
    /// Their derivatives.
    pub state_derivatives: Vec<ExprId>,
    /// The constraints at the speed level, with their dependents (empty
    /// without constraints).
    pub constraints: ConstraintEquations,
    /// The prescribed coordinates (none without motions).
    pub prescribed: Vec<Prescribed>,
    /// Each body's data for a recursive solve of `M du/dt = f`.
    pub tree: TreeKinetics,
}

impl System {
    /// Derives the equations of motion (Kane's method, composite-body form).
    pub fn equations(&mut self) -> Result<Equations, LocatedError> {
        let n = self.coordinates.len();
        let zero = self.arena.zero();
        let loads = self.applied_loads();
        let acc = self.accelerations();
        let mut resultants = self.body_resultants(&loads, &acc);
        let own = resultants.clone();
        let composite = self.subtrees(&mut resultants);
        let (res, mom) = (&resultants.force, &resultants.moment);

        // Forcing: project each subtree's resultants on its joint's speeds.
        let motions: Vec<UnitMotion> = (0..n).map(|k| self.unit_motion(k)).collect();
        let mut forcing = vec![zero; n];
        for (k, um) in motions.iter().enumerate() {
            let b = self.coordinates[k].body.index();
            let a = um.v.dot(&mut self.arena, &res[b]);
            let c = um.w.dot(&mut self.arena, &mom[b]);
            forcing[k] = self.arena.add(a, c);
        }
        self.moving_point_forcing(&mut forcing)?;
        let mass = self.mass_matrix(&motions, &composite);
        let mut joint_forcing = vec![zero; n];
        self.moving_point_forcing(&mut joint_forcing)?;
        let tree = self.tree_kinetics(&motions, &own, joint_forcing);
        let state_derivatives = self.state_derivatives()?;
        let prescribed = self.prescribed()?;
        let constraints = self.constraint_equations(&prescribed)?;
        Ok(Equations {
            coordinates: self.coordinates.iter().map(|c| c.q).collect(),
            speeds: self.coordinates.iter().map(|c| c.u).collect(),
            speed_rates: self.coordinates.iter().map(|c| c.du).collect(),
            kinematics: self.coordinates.iter().map(|c| c.qdot).collect(),
            mass_matrix: mass,
            forcing,
            states: self.states.iter().map(|s| s.sym).collect(),
            state_derivatives,
            constraints,
            prescribed,
            tree,
        })
    }

    /// d/dt of each added state (every one must have been given).
    fn state_derivatives(&self) -> Result<Vec<ExprId>, LocatedError> {
        self.states
            .iter()
            .map(|st| {
                st.derivative.ok_or_else(|| {
                    LocatedError::new(
                        ItemRef::State(st.sym),
                        ModelError::Invalid(format!(
                            "the added state `{}` has no derivative",
                            self.arena.symbol(st.sym).name
                        )),
                    )
                })
            })
            .collect()
    }
}

//! What lowering hands to scheduling: the equations as IR nodes
//! (`Lowered`, and `Assembly` for position constraints).

use crate::opt::ir::Nid;
use crate::opt::solve::Solve;
use crate::opt::solve::elim::Elimination;

/// The equations lowered to IR nodes.
pub(crate) struct Lowered {
    /// dq/dt of the state's coordinates.
    pub kinematics: Vec<Nid>,
    /// Lower triangle of the mass matrix of the independent speeds
    /// (`None`: structurally zero).
    pub mass: Vec<Vec<Option<Nid>>>,
    /// The forcing vector of the independent speeds.
    pub forcing: Vec<Nid>,
    /// The solve of `M du/dt = f`.
    pub solve: Solve,
    /// Pivots of the constraint solve, with their constraint.
    pub constraint_checks: Vec<(Nid, usize)>,
    /// d/dt of the extra states.
    pub extra: Vec<Nid>,
    /// The same, reading the state's accelerations as `Leaf::Accel`.
    pub extra_in_rates: Vec<Nid>,
    /// The outputs.
    pub outputs: Vec<Nid>,
    /// The initial state.
    pub initial: Vec<Nid>,
    /// Subroutine arguments.
    pub sub_args: Vec<Vec<Nid>>,
    /// User-function calls in model order.
    pub call_order: Vec<Nid>,
    /// Values named after a symbol (the dependent speeds).
    pub named: Vec<(String, Nid)>,
    /// The Newton step of assembly (models with position constraints).
    pub assembly: Option<Assembly>,
}

/// One Newton step of assembly.
pub(crate) struct Assembly {
    /// The corrections of the dependent coordinates.
    pub step: Vec<Nid>,
    /// The residuals of the position constraints.
    pub residuals: Vec<Nid>,
    /// Pivots of the Jacobian's solve, with their constraint.
    pub checks: Vec<(Nid, usize)>,
    /// The factored Jacobian `G_d` of the residuals by the dependent
    /// coordinates.
    pub elim: Elimination,
}

//! Joint reactions and the energy and momentum built-ins, through the
//! interpreter of the compiled program: static cases with known answers,
//! the chains against Pinocchio's RNEA
//! (`tests/reference/gen/pinocchio_reactions.py`) and SymPy's energy
//! (`chains`), the satellite's boom hinge reaction, kinetic energy and
//! momenta against a Newton–Euler computation written here with the
//! reference's accelerations (`satellite`); the four-bar's pin force
//! (`constraint_force`) against planar Newton–Euler (`four_bar`).

mod chains;
mod four_bar;
mod newton_euler;
mod satellite;
mod support;

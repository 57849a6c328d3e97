//! Joint reactions and the energy and momentum built-ins, through the
//! interpreter of the compiled program: static cases with known answers,
//! the chains against Pinocchio's RNEA
//! (`tests/reference/gen/pinocchio_reactions.py`) and SymPy's energy
//! (`chains`), the satellite's boom hinge reaction, kinetic energy and
//! momenta against a Newton–Euler computation written here with the
//! reference's accelerations (`satellite`); the four-bar's pin force
//! and joint reactions against planar Newton–Euler (`four_bar`), the
//! rolling disc's friction and contact forces against Newton–Euler
//! (`rolling_disc`); loads read from speed constraints with known static
//! answers (`supports`).

mod chains;
mod four_bar;
mod newton_euler;
mod rolling_disc;
mod satellite;
mod support;
mod supports;

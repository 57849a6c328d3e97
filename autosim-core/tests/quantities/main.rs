//! Joint reactions and the energy and momentum built-ins, through the
//! interpreter of the compiled program: static cases with known answers,
//! the chains against Pinocchio's RNEA
//! (`tests/reference/gen/pinocchio_reactions.py`) and SymPy's energy
//! (`chains`), the satellite's boom hinge reaction, kinetic energy and
//! momenta against a Newton–Euler computation written here with the
//! reference's accelerations (`satellite`).

mod chains;
mod newton_euler;
mod satellite;
mod support;

//! The words the generators use: ordinary and extreme numbers, names that
//! clash with something, units, functions and operations.

/// Ordinary numbers.
pub(crate) const NUMBERS: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "0.5",
    "1.5",
    "10",
    "9.81",
    "1e-3",
    "3.1415926",
    "0.0",
    "00007",
    "1_000",
    "2.5e+2",
    "1e0",
    "0.000001",
    "65536",
    "0.2",
];

/// Extreme numbers: beyond 38 digits, beyond the exponents of `f64`.
pub(crate) const EXTREME_NUMBERS: &[&str] = &[
    "1e38",
    "1e39",
    "1e-38",
    "1e-39",
    "1e300",
    "1e-300",
    "1e400",
    "1e-400",
    "12345678901234567890123456789012345678",
    "123456789012345678901234567890123456789012",
    "0.1234567890123456789012345678901234567890",
    "170141183460469231731687303715884105727",
    "340282366920938463463374607431768211456",
    "4294967296",
    "18446744073709551616",
];

/// Exponents for `^`.
pub(crate) const EXPONENTS: &[&str] = &[
    "2", "3", "0", "-1", "-2", "0.5", "(1/2)", "(1/3)", "(-1/2)", "10", "64", "100", "1000000",
    "1e30", "-3", "1.5", "(2^10)", "(10^10)",
];

pub(crate) const BODY_NAMES: &[&str] = &["A", "B", "C", "D", "E", "Arm", "Bus", "W"];
/// Names that clash with something: keywords, built-ins, reserved names.
pub(crate) const ODD_NAMES: &[&str] = &[
    "N",
    "t",
    "n1",
    "b2",
    "x",
    "k",
    "r#x",
    "_",
    "self",
    "fn",
    "q",
    "u",
    "dot",
    "sin",
    "all",
    "cm",
    "origin",
    "Model",
    "B",
    "undeclared",
    "é",
    "ẞ",
    "a1",
    "M",
];
pub(crate) const PARAM_NAMES: &[&str] = &["k", "m", "g", "L", "c", "I1", "I2", "p", "tau", "mu"];
/// Units the unit check reads (declared where a unit is optional).
pub(crate) const UNITS: &[&str] = &[
    "",
    " [m]",
    " [kg]",
    " [N m/rad]",
    " [m/s^2]",
    " [rad]",
    " [1/s]",
    " [N]",
    " [J]",
    " [kg m^2/s]",
    " [m^(1/2)]",
];
/// Units the unit check refuses somewhere: unknown, two `/`, a factor
/// where none is allowed (inputs, states, subroutine outputs), `//` starting
/// a comment.
pub(crate) const BAD_UNITS: &[&str] = &[
    " [deg]",
    " [mm]",
    " [m/s/s]",
    " [furlong]",
    " [N//m]",
    " [m^x]",
    " []",
];
pub(crate) const SCALAR_FUNCS: &[&str] = &[
    "sin", "cos", "tan", "asin", "acos", "atan2", "exp", "ln", "abs", "sign", "min", "max", "sqrt",
];
/// Every operation, and names that are not one.
pub(crate) const OPERATIONS: &[&str] = &[
    "dot",
    "cross",
    "mag",
    "dir",
    "angle",
    "dot_plane",
    "pos",
    "vel",
    "rot",
    "q",
    "u",
    "dxdt",
    "partial",
    "nominal",
    "constant_part",
    "sqrt",
    "diag",
    "frob",
    "sin",
    "atan2",
];

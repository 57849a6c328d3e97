//! The paper's Figure 8 user code (SUBROUTINE CMD and FUNCTION THRUST), shared
//! by the examples that fly the satellite's slew maneuver (`satellite.rs`,
//! `tradeoff.rs`). Include it with
//!
//! ```ignore
//! #[macro_use]
//! #[path = "common/figure8.rs"]
//! mod figure8;
//! use figure8::Figure8;
//! figure8_externs!(full::satellite => f64);
//! ```

/// The paper's Figure 8: the controller commands (SUBROUTINE CMD) and the
/// thrusters (FUNCTION THRUST) with their saved state, one per axis.
#[derive(Clone, Debug)]
pub struct Figure8 {
    /// FIRE(axis): the thruster pair's state, -1, 0 or 1.
    pub fire: [f64; 3],
    /// TOFF(axis): the earliest time the pair may switch off.
    pub toff: [f64; 3],
    /// `false` keeps the thrusters off (THRUST returns 0): the slew commands
    /// alone, a smooth problem whose integration error can be measured.
    pub thrusters: bool,
}

impl Default for Figure8 {
    fn default() -> Self {
        Self::new()
    }
}

#[allow(dead_code)] // each example uses its own part
impl Figure8 {
    /// `PARAMETER (PI = 3.1415926)`, exactly as the Fortran (the reference
    /// data use this value, not `f64::consts::PI`).
    #[allow(clippy::approx_constant)]
    pub const PI: f64 = 3.1415926;
    /// Dead zone of the attitude error (rad).
    pub const DBAND: f64 = 0.0025;
    /// Shortest burst (s).
    pub const TMIN: f64 = 0.02;

    /// The paper's user code, thrusters on.
    pub fn new() -> Self {
        Self {
            fire: [0.0; 3],
            toff: [0.0; 3],
            thrusters: true,
        }
    }

    /// The slew commands with the thrusters off.
    pub fn commands_only() -> Self {
        Self {
            thrusters: false,
            ..Self::new()
        }
    }

    /// SUBROUTINE CMD(T, CLKCMD, CAMCMD).
    pub fn cmd(&mut self, t: f64) -> [f64; 2] {
        let pi = Self::PI;
        if t < 1.0 {
            [4.0 - pi, -0.5]
        } else if t < 11.0 {
            [4.0 - 0.025 * (t - 1.0) - pi, -0.5 + 0.01 * (t - 1.0)]
        } else {
            [3.75 - pi, -0.4]
        }
    }

    /// FUNCTION THRUST(T, AXIS, ERROR).
    pub fn thrust(&mut self, t: f64, axis: f64, error: f64) -> f64 {
        if !self.thrusters {
            return 0.0;
        }
        let i = axis as usize - 1;
        if error < -Self::DBAND {
            if self.fire[i] < 1.0 {
                self.toff[i] = t + Self::TMIN;
            }
            self.fire[i] = 1.0;
        } else if error > Self::DBAND {
            if self.fire[i] > -1.0 {
                self.toff[i] = t + Self::TMIN;
            }
            self.fire[i] = -1.0;
        } else if t >= self.toff[i] {
            self.fire[i] = 0.0;
        }
        self.fire[i]
    }
}

/// Implements the `Externs` trait of generated satellite modules for
/// [`Figure8`]: `figure8_externs!(full::satellite => f64, single::satellite_f32 => f32);`.
/// The user code computes in `f64` whatever the model's float type.
macro_rules! figure8_externs {
    ($($($module:ident)::+ => $float:ty),+ $(,)?) => {
        $(
            impl $($module)::+::Externs for Figure8 {
                fn thrust(&mut self, t: $float, axis: $float, error: $float) -> $float {
                    use autosim::runtime::Float;
                    <$float>::from_f64(Figure8::thrust(self, t.to_f64(), axis.to_f64(), error.to_f64()))
                }
                fn cmd(&mut self, t: $float) -> [$float; 2] {
                    use autosim::runtime::Float;
                    Figure8::cmd(self, t.to_f64()).map(<$float>::from_f64)
                }
            }
        )+
    };
}

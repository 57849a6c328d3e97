//! The paper's thrusters as events: the Figure 8 controller (dead band
//! DBAND, shortest burst TMIN) written as discrete modes switched by
//! located events instead of state kept inside user code, around the
//! generated satellite (`satellite.sim`, whose `thrust(t, axis, error)`
//! then only reads the mode). Shared by the examples and tests that fly
//! the event-based slew. Include it after `figure8.rs`:
//!
//! ```ignore
//! #[path = "common/slew_events.rs"]
//! mod slew_events;
//! slew_events_externs!(full::satellite);
//! ```
//!
//! Per axis k (error e = G·u(B, k) + q(B, k), the paper's argument of
//! THRUST) three events:
//!
//! | event | indicator, direction | action |
//! | --- | --- | --- |
//! | `fire_plus_k` | `−DBAND − e`, rising (e falls below −DBAND) | `toff := t + TMIN` unless already firing +1; `fire := 1` |
//! | `fire_minus_k` | `e − DBAND`, rising (e rises above DBAND) | `toff := t + TMIN` unless already firing −1; `fire := −1` |
//! | `coast_k` | `min(DBAND − abs(e), t − toff)`, rising (inside the band and the burst long enough) | `fire := 0` |
//!
//! which is Figure 8's THRUST with its decisions taken at the located
//! instants of the sign changes rather than at whatever stages the
//! integrator evaluates: the dead band is a hysteresis (on outside ±DBAND,
//! off inside it only after TMIN), the modes `fire_k` and `toff_k` are the
//! model's discrete variables (saved with the state, in the CSV).

use autosim::runtime::{EventIndicator, EventOutcome, Model, ModelError};

use crate::figure8::Figure8;

/// The thrusters' modes: what the generated model's user code reads.
#[derive(Clone, Debug, Default)]
pub struct Modes {
    /// The pairs' thrust direction, -1, 0 or 1.
    pub fire: [f64; 3],
    /// The earliest time each pair may switch off.
    pub toff: [f64; 3],
}

impl Modes {
    /// SUBROUTINE CMD of Figure 8 (the commanded slew).
    pub fn cmd(&mut self, t: f64) -> [f64; 2] {
        Figure8::new().cmd(t)
    }

    /// THRUST reads the mode only.
    pub fn thrust(&self, axis: f64) -> f64 {
        self.fire[(axis as usize).clamp(1, 3) - 1]
    }
}

/// Implements a generated satellite module's `Externs` for [`Modes`].
macro_rules! slew_events_externs {
    ($($module:ident)::+) => {
        impl $($module)::+::Externs for slew_events::Modes {
            fn thrust(&mut self, _t: f64, axis: f64, _error: f64) -> f64 {
                slew_events::Modes::thrust(self, axis)
            }
            fn cmd(&mut self, t: f64) -> [f64; 2] {
                slew_events::Modes::cmd(self, t)
            }
        }
        impl slew_events::Thrusted for $($module)::+::Satellite<slew_events::Modes> {
            fn modes(&self) -> &slew_events::Modes {
                &self.externs
            }
            fn modes_mut(&mut self) -> &mut slew_events::Modes {
                &mut self.externs
            }
        }
    };
}

/// A generated satellite whose user code is [`Modes`].
pub trait Thrusted: Model<Float = f64, State = [f64; 20]> {
    /// The modes.
    fn modes(&self) -> &Modes;
    /// The modes, to switch.
    fn modes_mut(&mut self) -> &mut Modes;
}

/// The nine events, three per axis.
const EVENTS: [EventIndicator; 9] = [
    EventIndicator::rising("fire_plus_1"),
    EventIndicator::rising("fire_minus_1"),
    EventIndicator::rising("coast_1"),
    EventIndicator::rising("fire_plus_2"),
    EventIndicator::rising("fire_minus_2"),
    EventIndicator::rising("coast_2"),
    EventIndicator::rising("fire_plus_3"),
    EventIndicator::rising("fire_minus_3"),
    EventIndicator::rising("coast_3"),
];

/// The satellite with its thrusters switched by events.
pub struct EventSlew<M> {
    /// The generated model.
    pub model: M,
    /// Rate gain G of the attitude error (s).
    gain: f64,
    /// State indices of q(B, 4..6) and u(B, 4..6).
    angle: [usize; 3],
    rate: [usize; 3],
}

impl<M: Thrusted> EventSlew<M> {
    /// Wraps a generated satellite (parameters as they are set in it).
    pub fn new(model: M) -> Self {
        let index = |name: &str| {
            M::STATE_NAMES
                .iter()
                .position(|n| *n == name)
                .unwrap_or_else(|| panic!("the satellite has a state {name}"))
        };
        let mut values = vec![0.0; M::PARAMETER_NAMES.len()];
        model.parameter_values(&mut values);
        let g = M::PARAMETER_NAMES.iter().position(|n| *n == "G");
        Self {
            gain: g.map_or(2.0, |i| values[i]),
            angle: [index("q4"), index("q5"), index("q6")],
            rate: [index("u4"), index("u5"), index("u6")],
            model,
        }
    }

    /// The attitude error of axis `k` (0-based) at state `x`.
    fn error(&self, x: &[f64; 20], k: usize) -> f64 {
        self.gain * x[self.rate[k]] + x[self.angle[k]]
    }
}

impl<M: Thrusted> Model for EventSlew<M> {
    type Float = f64;
    type State = [f64; 20];
    type Outputs = M::Outputs;
    const NAME: &'static str = "SatelliteEventSlew";
    const STATE_NAMES: &'static [&'static str] = M::STATE_NAMES;
    const STATE_UNITS: &'static [&'static str] = M::STATE_UNITS;
    const PARAMETER_NAMES: &'static [&'static str] = M::PARAMETER_NAMES;
    const PARAMETER_UNITS: &'static [&'static str] = M::PARAMETER_UNITS;
    const OUTPUT_NAMES: &'static [&'static str] = M::OUTPUT_NAMES;
    const OUTPUT_UNITS: &'static [&'static str] = M::OUTPUT_UNITS;
    const EVENT_INDICATORS: &'static [EventIndicator] = &EVENTS;
    const DISCRETE_NAMES: &'static [&'static str] =
        &["fire_1", "fire_2", "fire_3", "toff_1", "toff_2", "toff_3"];
    const DISCRETE_UNITS: &'static [&'static str] = &["1", "1", "1", "s", "s", "s"];

    fn derivatives(&mut self, t: f64, x: &[f64; 20], dx: &mut [f64; 20]) -> Result<(), ModelError> {
        self.model.derivatives(t, x, dx)
    }
    fn outputs(&mut self, t: f64, x: &[f64; 20], y: &mut M::Outputs) -> Result<(), ModelError> {
        self.model.outputs(t, x, y)
    }
    fn parameter_values(&self, values: &mut [f64]) {
        self.model.parameter_values(values);
    }
    fn initial_state(&self) -> [f64; 20] {
        self.model.initial_state()
    }
    fn event_indicators(&mut self, t: f64, x: &[f64; 20], g: &mut [f64]) -> Result<(), ModelError> {
        let band = Figure8::DBAND;
        for k in 0..3 {
            let e = self.error(x, k);
            g[3 * k] = -band - e;
            g[3 * k + 1] = e - band;
            g[3 * k + 2] = (band - e.abs()).min(t - self.model.modes().toff[k]);
        }
        Ok(())
    }
    fn event(
        &mut self,
        index: usize,
        t: f64,
        _x: &mut [f64; 20],
    ) -> Result<EventOutcome, ModelError> {
        let modes = self.model.modes_mut();
        let k = index / 3;
        match index % 3 {
            kind @ (0 | 1) => {
                let fire = if kind == 0 { 1.0 } else { -1.0 };
                if modes.fire[k] != fire {
                    modes.toff[k] = t + Figure8::TMIN;
                }
                modes.fire[k] = fire;
            }
            _ => modes.fire[k] = 0.0,
        }
        Ok(EventOutcome::Continue)
    }
    fn discrete_values(&self, values: &mut [f64]) {
        let modes = self.model.modes();
        for (v, m) in values.iter_mut().zip(modes.fire.iter().chain(&modes.toff)) {
            *v = *m;
        }
    }
    fn set_discrete_values(&mut self, values: &[f64]) {
        let modes = self.model.modes_mut();
        for (m, v) in modes
            .fire
            .iter_mut()
            .chain(modes.toff.iter_mut())
            .zip(values)
        {
            *m = *v;
        }
    }
}

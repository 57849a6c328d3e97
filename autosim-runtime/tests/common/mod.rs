//! Small hand-written models with known solutions, shared by the tests.
#![allow(dead_code)] // each test binary uses a different subset

use std::convert::Infallible;

use autosim_runtime::{
    EventIndicator, EventOutcome, Model, ModelError, RunError, RunSettings, RunSummary, Stepper,
    run,
};

/// x'' = -ω²x as [x, v]; with x(0) = 1, v(0) = 0: x = cos ωt, v = -ω sin ωt.
#[derive(Clone, Debug)]
pub struct Oscillator {
    pub omega: f64,
    pub mass: f64,
}

impl Default for Oscillator {
    fn default() -> Self {
        Self {
            omega: 1.0,
            mass: 2.0,
        }
    }
}

impl Oscillator {
    pub fn exact(&self, t: f64) -> [f64; 2] {
        [(self.omega * t).cos(), -self.omega * (self.omega * t).sin()]
    }
}

impl Model for Oscillator {
    autosim_test_support::model_header!(f64, "Oscillator", states: ["x" in "m", "v" in "m/s"], outputs: ["energy" in "J"]);
    autosim_test_support::model_parameters!(omega in "rad/s", mass in "kg");

    fn derivatives(&mut self, _t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        dx[0] = x[1];
        dx[1] = -self.omega * self.omega * x[0];
        Ok(())
    }
    fn outputs(&mut self, _t: f64, x: &[f64; 2], y: &mut [f64; 1]) -> Result<(), ModelError> {
        let k = self.mass * self.omega * self.omega;
        y[0] = 0.5 * self.mass * x[1] * x[1] + 0.5 * k * x[0] * x[0];
        Ok(())
    }
    fn initial_state(&self) -> [f64; 2] {
        [1.0, 0.0]
    }
}

/// x' = -k·x: x = e^(-kt).
#[derive(Clone, Debug)]
pub struct Decay {
    pub k: f64,
}

impl Model for Decay {
    autosim_test_support::model_header!(f64, "Decay", states: ["x" in "1"], outputs: 0);
    autosim_test_support::model_parameters!(k in "1/s");

    fn derivatives(&mut self, _t: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        dx[0] = -self.k * x[0];
        Ok(())
    }
    fn initial_state(&self) -> [f64; 1] {
        [1.0]
    }
}

/// A stiff linear system of Prothero–Robinson type:
/// x' = A·(x − φ(t)) + φ'(t), with A = Q·diag(λ)·Qᵀ, Q = I − (2/3)·ones
/// (a symmetric orthogonal reflection) and λ = (-1e4, -1e5, -1e6).
/// With x(0) = φ(0) the exact solution is x = φ(t) = (cos t, sin t, e^(−t)).
#[derive(Clone, Debug)]
pub struct StiffLinear {
    pub a: [[f64; 3]; 3],
}

impl Default for StiffLinear {
    fn default() -> Self {
        let lambda = [-1e4, -1e5, -1e6];
        let q = |i: usize, j: usize| if i == j { 1.0 - 2.0 / 3.0 } else { -2.0 / 3.0 };
        let mut a = [[0.0; 3]; 3];
        for (i, row) in a.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = (0..3).map(|k| q(i, k) * lambda[k] * q(j, k)).sum();
            }
        }
        Self { a }
    }
}

impl StiffLinear {
    pub fn exact(t: f64) -> [f64; 3] {
        [t.cos(), t.sin(), (-t).exp()]
    }
    fn exact_rate(t: f64) -> [f64; 3] {
        [-t.sin(), t.cos(), -(-t).exp()]
    }
}

impl Model for StiffLinear {
    autosim_test_support::model_header!(f64, "StiffLinear", states: ["y1" in "1", "y2" in "1", "y3" in "1"], outputs: 0);

    fn derivatives(&mut self, t: f64, x: &[f64; 3], dx: &mut [f64; 3]) -> Result<(), ModelError> {
        let phi = Self::exact(t);
        let dphi = Self::exact_rate(t);
        for i in 0..3 {
            dx[i] = dphi[i] + (0..3).map(|j| self.a[i][j] * (x[j] - phi[j])).sum::<f64>();
        }
        Ok(())
    }
    fn initial_state(&self) -> [f64; 3] {
        Self::exact(0.0)
    }
}

/// Van der Pol: x'' = μ(1 − x²)x' − k·x, as [x, v]; stiff for large μ.
#[derive(Clone, Debug)]
pub struct VanDerPol {
    pub mu: f64,
    pub stiffness: f64,
}

impl VanDerPol {
    /// Damping `mu`, stiffness 1 (x'' = μ(1 − x²)x' − x).
    pub fn with_mu(mu: f64) -> Self {
        VanDerPol { mu, stiffness: 1.0 }
    }
}

impl Model for VanDerPol {
    autosim_test_support::model_header!(f64, "VanDerPol", states: ["x" in "1", "v" in "1/s"], outputs: ["x_squared" in "1"]);
    autosim_test_support::model_parameters!(mu in "1", stiffness in "1/s2");

    fn derivatives(&mut self, _t: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), ModelError> {
        dx[0] = x[1];
        dx[1] = self.mu * (1.0 - x[0] * x[0]) * x[1] - self.stiffness * x[0];
        Ok(())
    }
    fn outputs(&mut self, _t: f64, x: &[f64; 2], y: &mut [f64; 1]) -> Result<(), ModelError> {
        y[0] = x[0] * x[0];
        Ok(())
    }
    fn initial_state(&self) -> [f64; 2] {
        [2.0, 0.0]
    }
}

/// x' = g(t) with a polynomial g: the solution is a polynomial, so methods
/// of high enough order reproduce it to round-off.
#[derive(Clone, Debug)]
pub struct Polynomial {
    /// Degree of the solution x(t) = t^degree.
    pub degree: i32,
}

impl Model for Polynomial {
    autosim_test_support::model_header!(f64, "Polynomial", states: ["x" in "1"], outputs: 0);

    fn derivatives(&mut self, t: f64, _x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        dx[0] = f64::from(self.degree) * t.powi(self.degree - 1);
        Ok(())
    }
    fn initial_state(&self) -> [f64; 1] {
        [0.0]
    }
}

/// x' = x²: with x(0) = 1 the solution 1/(1 − t) blows up at t = 1.
#[derive(Clone, Debug, Default)]
pub struct BlowUp;

impl Model for BlowUp {
    autosim_test_support::model_header!(f64, "BlowUp", states: ["x" in "1"], outputs: 0);

    fn derivatives(&mut self, _t: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        dx[0] = x[0] * x[0];
        Ok(())
    }
    fn initial_state(&self) -> [f64; 1] {
        [1.0]
    }
}

/// A ball dropped from `H0` onto the floor at h = 0: h'' = -g, and at
/// every impact (h falling through 0) v := -e·v. The event `apex` (v
/// falling through 0, no action) marks the tops. Below `min_speed` the
/// ball comes to rest: the discrete variable `resting` becomes 1 and
/// freezes the motion (the documented fix for Zeno). `Ball` computes in
/// `f64`, `Ball<f32>` in `f32`.
#[derive(Clone, Debug)]
pub struct Ball<F = f64> {
    pub g: F,
    pub e: F,
    pub min_speed: F,
    pub resting: F,
}

impl Ball {
    pub fn new(e: f64, min_speed: f64) -> Self {
        Self {
            g: 9.81,
            e,
            min_speed,
            resting: 0.0,
        }
    }

    /// The analytic n-th bounce (n = 1, 2, ...) from rest at `H0`: its time
    /// and the apex height after it.
    pub fn exact_bounce(&self, n: u32) -> (f64, f64) {
        let t1 = (2.0 * H0 / self.g).sqrt();
        let v1 = self.g * t1;
        // t_n = t1 + Σ_{i=1}^{n-1} 2 eⁱ v1 / g; apex after bounce n: e^{2n} H0.
        let t = t1
            + (1..n)
                .map(|i| 2.0 * self.e.powi(i as i32) * v1 / self.g)
                .sum::<f64>();
        (t, self.e.powi(2 * n as i32) * H0)
    }
}

impl Ball<f32> {
    /// The ball in `f32`, never resting.
    pub fn in_f32(e: f32) -> Self {
        Self {
            g: 9.81,
            e,
            min_speed: 0.0,
            resting: 0.0,
        }
    }
}

/// The ball's drop height (m).
pub const H0: f64 = 1.0;

/// `Model` for `Ball<$f>`.
macro_rules! ball_model {
    ($f:ty, $name:literal) => {
        impl Model for Ball<$f> {
            autosim_test_support::model_header!($f, $name, states: ["h" in "m", "v" in "m/s"], outputs: ["energy" in "J/kg"]);
            const EVENT_INDICATORS: &'static [EventIndicator] = &[
                EventIndicator::falling("bounce"),
                EventIndicator::falling("apex"),
            ];
            const DISCRETE_NAMES: &'static [&'static str] = &["resting"];
            const DISCRETE_UNITS: &'static [&'static str] = &["1"];

            fn derivatives(&mut self, _t: $f, x: &[$f; 2], dx: &mut [$f; 2]) -> Result<(), ModelError> {
                let moving = 1.0 - self.resting;
                dx[0] = moving * x[1];
                dx[1] = -moving * self.g;
                Ok(())
            }
            fn outputs(&mut self, _t: $f, x: &[$f; 2], y: &mut [$f; 1]) -> Result<(), ModelError> {
                y[0] = 0.5 * x[1] * x[1] + self.g * x[0];
                Ok(())
            }
            fn event_indicators(&mut self, _t: $f, x: &[$f; 2], g: &mut [$f]) -> Result<(), ModelError> {
                g[0] = x[0];
                g[1] = x[1];
                Ok(())
            }
            fn event(&mut self, index: usize, _t: $f, x: &mut [$f; 2]) -> Result<EventOutcome, ModelError> {
                if index == 0 {
                    x[1] *= -self.e;
                    if x[1].abs() < self.min_speed {
                        self.resting = 1.0;
                        x[1] = 0.0;
                    }
                }
                Ok(EventOutcome::Continue)
            }
            fn discrete_values(&self, values: &mut [$f]) {
                values[0] = self.resting;
            }
            fn set_discrete_values(&mut self, values: &[$f]) {
                self.resting = values[0];
            }
            fn initial_state(&self) -> [$f; 2] {
                [1.0, 0.0]
            }
        }
    };
}

ball_model!(f64, "Ball");
ball_model!(f32, "BallF32");

/// Least-squares slope of log(error) against log(h).
pub fn convergence_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = points.iter().map(|(h, e)| (h.ln(), e.ln())).unzip();
    let mx = lx.iter().sum::<f64>() / n;
    let my = ly.iter().sum::<f64>() / n;
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// What a run with a closure observer (which cannot fail) returns.
pub type RunResult<M> = Result<RunSummary<<M as Model>::Float>, RunError<Infallible>>;

/// One output of a run: the time, the state and the outputs.
pub type Output<M> = (
    <M as Model>::Float,
    <M as Model>::State,
    <M as Model>::Outputs,
);

/// [`run`] with an observer that ignores the outputs.
pub fn run_unobserved<M: Model, S: Stepper<M> + ?Sized>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    settings: &RunSettings<M::Float>,
) -> RunResult<M> {
    run(
        model,
        stepper,
        x,
        settings,
        &mut |_, _: &M::State, _: &M::Outputs| {},
    )
}

/// [`run`] keeping every output, also those before a failure.
pub fn run_recorded<M: Model, S: Stepper<M> + ?Sized>(
    model: &mut M,
    stepper: &mut S,
    x: &mut M::State,
    settings: &RunSettings<M::Float>,
) -> (RunResult<M>, Vec<Output<M>>) {
    let mut outputs = Vec::new();
    let result = run(
        model,
        stepper,
        x,
        settings,
        &mut |t, x: &M::State, y: &M::Outputs| {
            outputs.push((t, *x, *y));
        },
    );
    (result, outputs)
}

/// [`run_recorded`] from the model's initial state: the result, every
/// output and the last state.
pub fn run_from_start<M: Model, S: Stepper<M> + ?Sized>(
    model: &mut M,
    stepper: &mut S,
    settings: &RunSettings<M::Float>,
) -> (RunResult<M>, Vec<Output<M>>, M::State) {
    let mut x = model.initial_state();
    let (result, outputs) = run_recorded(model, stepper, &mut x, settings);
    (result, outputs, x)
}

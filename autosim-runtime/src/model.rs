//! The interface between generated models and everything that runs them.

use crate::Float;
use crate::batch::LANES;
use crate::event::{EventIndicator, EventOutcome};
use crate::float::lanes::Lanes;

/// A fixed-size state (or output) vector: implemented for `[F; N]` only.
///
/// Integrators keep their workspaces in this type, so stepping a model never
/// allocates.
pub trait StateArray<F: Float>: Copy + AsRef<[F]> + AsMut<[F]> {
    /// Number of entries.
    const LEN: usize;
    /// A vector of zeros.
    fn zeros() -> Self;
}

impl<F: Float, const N: usize> StateArray<F> for [F; N] {
    const LEN: usize = N;
    fn zeros() -> Self {
        [F::ZERO; N]
    }
}

/// Why a derivative evaluation failed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ModelError {
    /// The mass matrix has a zero (or negative, or non-finite) pivot in its
    /// LDLᵀ factorization: the model is singular at this state. `speed` is the
    /// index of the generalized speed whose pivot failed (an index into the
    /// speed part of the state, see [`Model::STATE_NAMES`]).
    SingularMassMatrix {
        /// Index of the generalized speed (0-based, in speed order).
        speed: usize,
        /// Name of that speed.
        name: &'static str,
    },
    /// The constraints restrict the speeds in a way the chosen dependent
    /// speeds cannot express at this state (the constraint matrix is
    /// singular here): `constraint` is the index of the constraint whose
    /// pivot vanished (declaration order).
    SingularConstraints {
        /// Index of the constraint (0-based, declaration order).
        constraint: usize,
        /// Its name.
        name: &'static str,
    },
    /// Assembly (solving the position constraints for the dependent
    /// coordinates) did not converge: the configuration is far from one
    /// that closes the constraints, or none exists near it.
    NotAssembled {
        /// The constraint with the largest residual.
        name: &'static str,
    },
    /// Projecting a state back onto the position constraints moved a
    /// dependent coordinate far (more than a tenth of `1 + |q|`): the
    /// mechanism went through a singular configuration or the integration
    /// step was too large, and the closure jumped to another branch.
    LostBranch {
        /// The dependent coordinate that jumped.
        coordinate: &'static str,
    },
    /// A derivative came out NaN or infinite although the state was
    /// finite: the model divides by zero or calls a function outside its
    /// domain at this state (`-k/x^2` at `x = 0`, `sqrt` of a negative
    /// number), or the state is so large that a derivative overflows (an
    /// integration beyond its stability limit). Generated models check
    /// their derivatives before returning them ([`check_derivatives`]), and
    /// the results of user code before using them
    /// ([`ModelError::NonFiniteUserResult`]).
    NonFiniteDerivative {
        /// Index of the first non-finite derivative (state order).
        index: usize,
        /// Name of the state whose derivative it is.
        name: &'static str,
    },
    /// A user function or subroutine (the model's `extern`s) returned NaN
    /// or infinity. Generated `derivatives`, `outputs`, `event_indicators`
    /// and `event` check every result of user code they call
    /// ([`check_user_result`]).
    NonFiniteUserResult {
        /// The function's name, as the model declares it.
        function: &'static str,
    },
}

/// `Ok(value)` if `value` is finite, else
/// [`ModelError::NonFiniteUserResult`] naming `function`. Generated code
/// wraps every call of a user function in it (one comparison per call).
#[inline(always)]
pub fn check_user_result<F: Float>(value: F, function: &'static str) -> Result<F, ModelError> {
    match value.is_finite() {
        true => Ok(value),
        false => Err(non_finite_user_result(function)),
    }
}

/// [`check_user_result`] for every result of a user subroutine.
#[inline(always)]
pub fn check_user_results<F: Float, const N: usize>(
    values: [F; N],
    function: &'static str,
) -> Result<[F; N], ModelError> {
    match values.iter().all(|v| v.is_finite()) {
        true => Ok(values),
        false => Err(non_finite_user_result(function)),
    }
}

/// The error of a non-finite user result (out of line: the check's hot path
/// is only the comparison).
#[cold]
#[inline(never)]
fn non_finite_user_result(function: &'static str) -> ModelError {
    ModelError::NonFiniteUserResult { function }
}

/// `Ok` if every derivative in `dx` is finite, else
/// [`ModelError::NonFiniteDerivative`] naming the first state whose
/// derivative is not. Generated `derivatives` ends with it.
///
/// One pass over `dx` without early exit (the common case, all finite,
/// is a vectorizable AND of comparisons); the index is searched only on
/// failure.
#[inline]
pub fn check_derivatives<M: Model + ?Sized>(dx: &M::State) -> Result<(), ModelError> {
    match crate::error::first_non_finite(dx.as_ref()) {
        None => Ok(()),
        Some(index) => Err(non_finite_derivative::<M>(index)),
    }
}

impl core::fmt::Display for ModelError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ModelError::SingularMassMatrix { speed, name } => write!(
                f,
                "the mass matrix is singular at this state: pivot of speed {name} (#{speed}) is not positive or is NaN (check that every mass and inertia is positive and every parameter finite)"
            ),
            ModelError::SingularConstraints { constraint, name } => write!(
                f,
                "the constraints are singular at this state: the pivot of constraint {name} (#{constraint}) vanishes: the mechanism is at a singular configuration, or the pivot is one of how the constraints are written or of where a dependent starts (name other dependents with `dependent:`, coordinates for a position constraint and speeds for a speed constraint; start a dependent coordinate where it moves its constraint; or write the constraints along the axes the dependent speeds are measured in: language.md, \"Constraints\")"
            ),
            ModelError::NotAssembled { name } => write!(
                f,
                "the position constraints could not be closed (constraint {name} has the largest residual): no configuration near this one satisfies them, or none exists (a loop cannot close when one link is longer than all the others together: check the lengths), or the start is too far from one (start nearer)"
            ),
            ModelError::LostBranch { coordinate } => write!(
                f,
                "projection onto the position constraints moved {coordinate} too far: the mechanism jumped to another branch (take smaller steps, or avoid the singular configuration)"
            ),
            ModelError::NonFiniteDerivative { index, name } => write!(
                f,
                "the derivative of state {name} (#{index}) is not finite at this state: the model divides by zero or calls a function outside its domain here, a user function returned NaN or infinity, or the state is so large that the derivative overflows (an unstable step: try a smaller one)"
            ),
            ModelError::NonFiniteUserResult { function } => write!(
                f,
                "the user function {function} returned NaN or infinity at this state (check its arguments' range and its divisions)"
            ),
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for ModelError {}

/// A model generated by autosim (or written by hand): a first-order system
/// `dx/dt = f(t, x)` with named, unit-carrying states, parameters, inputs and
/// outputs.
///
/// The state vector holds the generalized coordinates first, then the
/// generalized speeds, then any extra states the model declares.
pub trait Model {
    /// The float type the model computes in (`f64` or `f32`).
    type Float: Float;
    /// The state vector, `[Self::Float; N_STATES]`.
    type State: StateArray<Self::Float>;
    /// The output vector, `[Self::Float; N_OUTPUTS]`.
    type Outputs: StateArray<Self::Float>;

    /// The model's name as written in its source.
    const NAME: &'static str;
    /// A fingerprint of the model's code: generated models set it to a
    /// hash of their generated module (its `FINGERPRINT`), so it changes
    /// when the model or the compiler's output changes; 0 by default.
    /// A study folder records it and refuses to be resumed by a model
    /// with another fingerprint (the results of two builds would mix).
    /// It does not cover the runtime library the code calls, nor user
    /// code.
    const FINGERPRINT: u64 = 0;
    /// Names of the states, in state order.
    const STATE_NAMES: &'static [&'static str];
    /// Units of the states (e.g. `"rad"`, `"m/s"`), in state order.
    const STATE_UNITS: &'static [&'static str];
    /// Names of the parameters (none by default).
    const PARAMETER_NAMES: &'static [&'static str] = &[];
    /// Units of the parameters.
    const PARAMETER_UNITS: &'static [&'static str] = &[];
    /// Names of the inputs (none by default).
    const INPUT_NAMES: &'static [&'static str] = &[];
    /// Units of the inputs.
    const INPUT_UNITS: &'static [&'static str] = &[];
    /// Names of the outputs (none by default).
    const OUTPUT_NAMES: &'static [&'static str] = &[];
    /// Units of the outputs.
    const OUTPUT_UNITS: &'static [&'static str] = &[];
    /// Whether a study may integrate several cases of this model in
    /// lockstep, each case on its own model, evaluating their states
    /// together through [`Model::derivatives_each`] (see the `study`
    /// module's "Lockstep"). Set it only when `derivatives_each` is faster
    /// than one call per model and every function of the model (user code
    /// included) depends on its arguments alone, not on earlier calls nor
    /// on which model of the group it is called on. `false` by default;
    /// models generated with the `lanes` option set it.
    const LOCKSTEP: bool = false;

    /// Writes the state derivatives `dx/dt` at time `t` and state `x` into `dx`.
    fn derivatives(
        &mut self,
        t: Self::Float,
        x: &Self::State,
        dx: &mut Self::State,
    ) -> Result<(), ModelError>;

    /// The derivatives at many states at one time `t`: `dx[k]` and
    /// `status[k]` are what [`Model::derivatives`] gives for `x[k]` (up to
    /// the shortest of the three slices; nothing is allocated). Generated
    /// `f64` models with the `lanes` option evaluate
    /// [`LANES`](crate::batch::LANES) states per call
    /// of their `derivatives_lanes` (vector instructions across states),
    /// with the same bits as one call per state; the default (and `f32`
    /// models) calls [`Model::derivatives`] once per state.
    ///
    /// ```
    /// use autosim_runtime::{Model, ModelError};
    ///
    /// struct Decay;
    /// impl Model for Decay {
    ///     type Float = f64;
    ///     type State = [f64; 1];
    ///     type Outputs = [f64; 0];
    ///     const NAME: &'static str = "Decay";
    ///     const STATE_NAMES: &'static [&'static str] = &["x"];
    ///     const STATE_UNITS: &'static [&'static str] = &["m"];
    ///     fn derivatives(&mut self, _: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
    ///         dx[0] = -2.0 * x[0];
    ///         Ok(())
    ///     }
    /// }
    ///
    /// let x = [[1.0], [2.0], [3.0]];
    /// let mut dx = [[0.0]; 3];
    /// let mut status = [Ok(()); 3];
    /// Decay.derivatives_batch(0.0, &x, &mut dx, &mut status);
    /// assert_eq!(dx, [[-2.0], [-4.0], [-6.0]]);
    /// assert!(status.iter().all(Result::is_ok));
    /// ```
    fn derivatives_batch(
        &mut self,
        t: Self::Float,
        x: &[Self::State],
        dx: &mut [Self::State],
        status: &mut [Result<(), ModelError>],
    ) {
        crate::batch::one_by_one(self, t, x, dx, status);
    }

    /// How many values [`Model::derivatives_each`] reads from each model
    /// besides the state, which [`Model::lane_values`] gathers: for a
    /// generated model with the `lanes` option, its parameters, the
    /// constants computed from them, its inputs and discrete variables.
    /// 0 by default.
    const LANE_VALUES: usize = 0;

    /// Gathers what [`Model::derivatives_each`] reads from `models` besides
    /// the states, for each full group of [`LANES`] models
    /// (`models[g * LANES..(g + 1) * LANES]`): value `k` of the group's
    /// `l`-th model into `values[g * LANE_VALUES + k].0[l]` (as far as
    /// `values` reaches). Done once for models whose values do not change
    /// (a study's group of cases), it spares every later call the gather.
    /// The default writes nothing.
    fn lane_values(models: &[Self], values: &mut [Lanes<LANES>])
    where
        Self: Sized,
    {
        let _ = (models, values);
    }

    /// The derivatives of several models of this type, each at its own
    /// time and state: `dx[k]` and `status[k]` are what
    /// `models[k].derivatives` gives at time `t[k]` and state `x[k]` (up
    /// to the shortest of the five slices; nothing is allocated). `values` is what
    /// [`Model::lane_values`] gathered from `models` as they are now: a
    /// group of [`LANES`] models whose values it does not hold (an empty
    /// `values`, say) is evaluated one call per model. What a study's
    /// cases in lockstep call, each case on its own model (its parameters
    /// and inputs). Generated `f64` models with the `lanes` option evaluate
    /// each full group in one call of their `derivatives_lanes`, each lane
    /// reading its own model's parameters, constants and inputs from
    /// `values`, with the same bits as one call per model; user code is
    /// then called on the group's first model, for every lane (what
    /// [`Model::LOCKSTEP`] allows). The default calls
    /// [`Model::derivatives`] once per model.
    fn derivatives_each(
        models: &mut [Self],
        values: &[Lanes<LANES>],
        t: &[Self::Float],
        x: &[Self::State],
        dx: &mut [Self::State],
        status: &mut [Result<(), ModelError>],
    ) where
        Self: Sized,
    {
        let _ = values;
        crate::batch::each_alone(models, t, x, dx, status);
    }

    /// Writes the output variables at time `t` and state `x` into `y`. The
    /// default writes nothing: for models without outputs.
    fn outputs(
        &mut self,
        t: Self::Float,
        x: &Self::State,
        y: &mut Self::Outputs,
    ) -> Result<(), ModelError> {
        let _ = (t, x, y);
        Ok(())
    }

    /// Copies the current parameter values, in [`Model::PARAMETER_NAMES`]
    /// order, into `values` (which must have that length). The default
    /// copies nothing: for models without parameters.
    fn parameter_values(&self, values: &mut [Self::Float]) {
        let _ = values;
    }

    /// Sets all parameter values, in [`Model::PARAMETER_NAMES`] order, and
    /// recomputes everything that depends only on parameters. The default
    /// sets nothing: for models without parameters.
    fn set_parameter_values(&mut self, values: &[Self::Float]) {
        let _ = values;
    }

    /// Solves the position constraints for the dependent coordinates,
    /// holding the others (Newton's method from the values in `x`, see
    /// [`assembly`](crate::assembly)). Models without position constraints
    /// have nothing to do (the default). The [`run`](crate::run()) driver
    /// assembles the initial state.
    ///
    /// # Errors
    /// [`ModelError::NotAssembled`] when Newton's method does not converge;
    /// [`ModelError::SingularConstraints`] at a singular configuration.
    fn assemble(&mut self, t: Self::Float, x: &mut Self::State) -> Result<(), ModelError> {
        let _ = (t, x);
        Ok(())
    }

    /// Copies the current input values, in [`Model::INPUT_NAMES`] order,
    /// into `values` (what fits). The default copies nothing: for models
    /// without inputs.
    fn input_values(&self, values: &mut [Self::Float]) {
        let _ = values;
    }

    /// Sets the inputs, in [`Model::INPUT_NAMES`] order (what is given;
    /// the others keep their values). The default sets nothing: for models
    /// without inputs.
    fn set_input_values(&mut self, values: &[Self::Float]) {
        let _ = values;
    }

    /// Brings a state drifted by integration back onto the position
    /// constraints (solving them for the dependent coordinates) when the
    /// drift exceeds `tolerance` (relative to `1 + |q|`; 0 projects any
    /// drift above rounding), and tells whether it changed the state. The
    /// [`run`](crate::run()) driver calls it after every accepted step.
    /// Models without position constraints have nothing to do (the
    /// default).
    ///
    /// # Errors
    /// As [`Model::assemble`], and [`ModelError::LostBranch`] when the
    /// correction is too large to be drift.
    fn project(
        &mut self,
        t: Self::Float,
        x: &mut Self::State,
        tolerance: Self::Float,
    ) -> Result<bool, ModelError> {
        let _ = (t, x, tolerance);
        Ok(false)
    }

    /// The default initial state written in the model (zeros where none
    /// was given; all zeros by default).
    fn initial_state(&self) -> Self::State {
        Self::State::zeros()
    }

    /// The model's event indicators, in the order
    /// [`Model::event_indicators`] writes them (none by default: a model
    /// without events). At most
    /// [`MAX_EVENT_INDICATORS`](crate::event::MAX_EVENT_INDICATORS).
    const EVENT_INDICATORS: &'static [EventIndicator] = &[];
    /// Names of the discrete variables (modes the equations read, changed
    /// only by event actions; none by default).
    const DISCRETE_NAMES: &'static [&'static str] = &[];
    /// Units of the discrete variables.
    const DISCRETE_UNITS: &'static [&'static str] = &[];

    /// Writes the value of every event indicator `g_k(t, x, discrete)` at
    /// time `t` and state `x` into `g` ([`Model::EVENT_INDICATORS`] order;
    /// `g` has that length). An event is a sign change of `g_k` in its
    /// direction. The default writes nothing: for models without events.
    ///
    /// # Errors
    /// Any [`ModelError`] of evaluating the indicators.
    fn event_indicators(
        &mut self,
        t: Self::Float,
        x: &Self::State,
        g: &mut [Self::Float],
    ) -> Result<(), ModelError> {
        let _ = (t, x, g);
        Ok(())
    }

    /// The action of event `index` at its located instant `t`: set discrete
    /// variables, reset states in `x`, call user code; return
    /// [`EventOutcome::Stop`] to end the run there. The default does
    /// nothing.
    ///
    /// # Errors
    /// Any [`ModelError`] of the action.
    fn event(
        &mut self,
        index: usize,
        t: Self::Float,
        x: &mut Self::State,
    ) -> Result<EventOutcome, ModelError> {
        let _ = (index, t, x);
        Ok(EventOutcome::Continue)
    }

    /// Copies the discrete variables, in [`Model::DISCRETE_NAMES`] order,
    /// into `values` (what fits): with the state, what a saved run must keep.
    /// The default copies nothing.
    fn discrete_values(&self, values: &mut [Self::Float]) {
        let _ = values;
    }

    /// Sets the discrete variables, in [`Model::DISCRETE_NAMES`] order (what
    /// is given), e.g. to restore a saved run. The default sets nothing.
    fn set_discrete_values(&mut self, values: &[Self::Float]) {
        let _ = values;
    }
}

/// Operation counts of a block of generated code: what one call costs.
///
/// Generated models publish these as constants (e.g. `DERIVATIVE_OPS`), like
/// the complexity summaries of AUTOSIM and SD/FAST.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct OpCount {
    /// Additions and subtractions.
    pub adds: usize,
    /// Multiplications.
    pub muls: usize,
    /// Divisions.
    pub divs: usize,
    /// Calls of built-in functions (sin, cos, sqrt, ...).
    pub funcs: usize,
    /// Calls of user functions and subroutines.
    pub user_calls: usize,
}

impl OpCount {
    /// Arithmetic operations plus built-in function calls.
    pub const fn total(&self) -> usize {
        self.adds + self.muls + self.divs + self.funcs
    }
}

impl core::fmt::Display for OpCount {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let names = [
            (self.adds, "add", "adds"),
            (self.muls, "multiply", "multiplies"),
            (self.divs, "divide", "divides"),
            (self.funcs, "function", "functions"),
            (self.user_calls, "user call", "user calls"),
        ];
        for (k, (n, one, many)) in names.into_iter().enumerate() {
            let separator = if k == 0 { "" } else { ", " };
            let noun = if n == 1 { one } else { many };
            write!(f, "{separator}{n} {noun}")?;
        }
        Ok(())
    }
}

/// The error of a non-finite derivative (out of line: the check's hot path
/// is only the comparisons).
#[cold]
#[inline(never)]
fn non_finite_derivative<M: Model + ?Sized>(index: usize) -> ModelError {
    ModelError::NonFiniteDerivative {
        index,
        name: M::STATE_NAMES.get(index).copied().unwrap_or("?"),
    }
}

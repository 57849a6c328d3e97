//! The body of every `fmi2*` function, generic over the exported model:
//! pointer checks, the state machine, the call itself inside
//! `catch_unwind` (a panic becomes `fmi2Fatal`, never unwinds into C), and
//! the failure logged through the importer's callback.
//!
//! [`export_fmi2!`](crate::export_fmi2) writes the `extern "C"` functions
//! that call these.
//!
//! # Safety
//! Every function here takes the raw pointers of the C interface: the
//! importer must pass what the standard says (an instance from
//! `fmi2Instantiate` not yet freed, arrays of the given lengths). Null
//! pointers and wrong lengths are detected and reported as `fmi2Error`.

#![allow(clippy::missing_safety_doc)]

use crate::Export;
use crate::ffi::{
    Boolean, CallbackFunctions, Component, EventInfo, FALSE, FmiString, FmuState, FmuType, Integer,
    LAST_SUCCESSFUL_TIME, Real, Status, StatusKind, TERMINATED, TRUE, ValueReference,
};
use crate::instance::{Fail, Instance, Mode, Outcome};
use crate::log::Log;
use crate::state::Snapshot;
use std::ffi::{CStr, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

use FmuType::{CoSimulation as CS, ModelExchange as ME};
use Mode::*;

/// Every mode but `Fatal`.
const ANY: &[Mode] = &Mode::ALIVE;
/// Modes where values may be read (both kinds): all but `Instantiated`.
const READ: &[Mode] = Mode::ALIVE.split_at(1).1;
/// Modes where values may be written (both kinds): before `Terminated`.
const WRITE: &[Mode] = Mode::ALIVE.split_at(5).0;

/// Runs `f` on the instance behind `c`: checks the pointer and the modes,
/// catches a panic, logs a failure and moves the instance to `Error` or
/// `Fatal` as the standard says.
unsafe fn call<E: Export>(
    c: Component,
    what: &str,
    modes: &[Mode],
    kind: Option<FmuType>,
    f: impl FnOnce(&mut Instance<E>) -> Outcome,
) -> Status {
    if c.is_null() {
        return Status::Error;
    }
    let p = c.cast::<Instance<E>>();
    // SAFETY: `c` came from `instantiate::<E>` and is not freed (the
    // importer's obligation); no other reference to it is alive.
    let mode = unsafe { (*p).mode };
    if mode == Fatal {
        return Status::Fatal;
    }
    let result = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: as above.
        let instance = unsafe { &mut *p };
        instance.log.call(|| what.to_string());
        instance.require(what, modes, kind)?;
        f(instance)
    }));
    // SAFETY: as above; the closure's borrow has ended.
    let instance = unsafe { &mut *p };
    match result {
        Ok(Ok(())) => Status::Ok,
        Ok(Err(fail)) => {
            instance
                .log
                .error(fail.status, &format!("{what}: {}", fail.message));
            if fail.status >= Status::Error {
                instance.mode = Error;
            }
            fail.status
        }
        Err(panic) => {
            instance.mode = Fatal;
            let message = panic_message(&*panic);
            instance
                .log
                .error(Status::Fatal, &format!("{what}: internal error: {message}"));
            Status::Fatal
        }
    }
}

fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".to_string())
}

/// A slice of `n` values at `ptr` (empty for `n = 0`, whatever `ptr`).
unsafe fn slice<'a, T>(ptr: *const T, n: usize) -> Result<&'a [T], Fail> {
    if n == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(Fail::error("a null array pointer"));
    }
    // SAFETY: the importer passes an array of `n` values.
    Ok(unsafe { std::slice::from_raw_parts(ptr, n) })
}

/// A mutable slice of `n` values at `ptr`.
unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize) -> Result<&'a mut [T], Fail> {
    if n == 0 {
        return Ok(&mut []);
    }
    if ptr.is_null() {
        return Err(Fail::error("a null array pointer"));
    }
    // SAFETY: the importer passes an array of `n` values.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, n) })
}

/// Writes through an out-pointer.
unsafe fn put<T>(ptr: *mut T, value: T) -> Outcome {
    if ptr.is_null() {
        return Err(Fail::error("a null result pointer"));
    }
    // SAFETY: the importer passes a pointer to a `T`.
    unsafe { ptr.write(value) };
    Ok(())
}

/// A C string, or an empty one for null.
unsafe fn text(s: FmiString) -> String {
    if s.is_null() {
        return String::new();
    }
    // SAFETY: the importer passes a NUL-terminated string.
    unsafe { CStr::from_ptr(s) }.to_string_lossy().into_owned()
}

/// `fmi2Instantiate`: a new instance, or null (logged through the
/// callback when there is one) for a wrong GUID or a missing argument.
pub unsafe fn instantiate<E: Export>(
    name: FmiString,
    kind: FmuType,
    guid: FmiString,
    _resources: FmiString,
    functions: *const CallbackFunctions,
    _visible: Boolean,
    logging_on: Boolean,
) -> Component {
    if functions.is_null() {
        return std::ptr::null_mut();
    }
    // SAFETY: the importer passes its callback table.
    let callbacks = unsafe { *functions };
    let result = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: NUL-terminated strings from the importer.
        let (name, guid) = unsafe { (text(name), text(guid)) };
        let log = Log::new(name.clone(), callbacks, logging_on != FALSE);
        if name.is_empty() {
            log.error(Status::Error, "fmi2Instantiate: the instance name is empty");
            return std::ptr::null_mut();
        }
        if guid != E::GUID {
            log.error(
                Status::Error,
                &format!(
                    "fmi2Instantiate: GUID {guid:?} is not this FMU's ({:?}): the modelDescription.xml and the binary do not belong together",
                    E::GUID
                ),
            );
            return std::ptr::null_mut();
        }
        let instance = Instance::<E>::new(name, kind, callbacks, logging_on != FALSE);
        Box::into_raw(Box::new(instance)).cast()
    }));
    result.unwrap_or(std::ptr::null_mut())
}

/// `fmi2FreeInstance`.
pub unsafe fn free_instance<E: Export>(c: Component) {
    if !c.is_null() {
        // SAFETY: `c` came from `instantiate::<E>` and is freed once.
        let instance = unsafe { Box::from_raw(c.cast::<Instance<E>>()) };
        let _ = catch_unwind(AssertUnwindSafe(move || drop(instance)));
    }
}

/// `fmi2SetDebugLogging`.
pub unsafe fn set_debug_logging<E: Export>(
    c: Component,
    on: Boolean,
    n: usize,
    categories: *const FmiString,
) -> Status {
    unsafe {
        call::<E>(c, "fmi2SetDebugLogging", ANY, None, |i| {
            let names: Vec<String> = slice(categories, n)?.iter().map(|s| text(*s)).collect();
            i.log.configure(on != FALSE, &names).map_err(Fail::error)
        })
    }
}

/// `fmi2SetupExperiment`: the start time, and the tolerance (when given)
/// as `cs.tolerance`.
pub unsafe fn setup_experiment<E: Export>(
    c: Component,
    tolerance_defined: Boolean,
    tolerance: Real,
    start: Real,
    _stop_defined: Boolean,
    _stop: Real,
) -> Status {
    unsafe {
        call::<E>(c, "fmi2SetupExperiment", &[Instantiated], None, |i| {
            if !start.is_finite() {
                return Err(Fail::error(format!("start time {start} is not finite")));
            }
            i.t = start;
            if tolerance_defined != FALSE && tolerance > 0.0 {
                i.settings.tolerance = tolerance;
            }
            i.touch();
            Ok(())
        })
    }
}

/// `fmi2EnterInitializationMode`.
pub unsafe fn enter_initialization_mode<E: Export>(c: Component) -> Status {
    unsafe {
        call::<E>(
            c,
            "fmi2EnterInitializationMode",
            &[Instantiated],
            None,
            |i| {
                i.mode = Initialization;
                Ok(())
            },
        )
    }
}

/// `fmi2ExitInitializationMode`: assembles a constrained model's initial
/// state, checks that the model evaluates, makes the Co-Simulation
/// integrator.
pub unsafe fn exit_initialization_mode<E: Export>(c: Component) -> Status {
    unsafe {
        call::<E>(
            c,
            "fmi2ExitInitializationMode",
            &[Initialization],
            None,
            |i| {
                i.assemble()?;
                i.evaluate()?;
                match i.kind {
                    ME => i.mode = Event,
                    CS => {
                        i.make_stepper()?;
                        i.mode = StepComplete;
                    }
                }
                Ok(())
            },
        )
    }
}

/// `fmi2Terminate`.
pub unsafe fn terminate<E: Export>(c: Component) -> Status {
    let modes = &[Event, Continuous, StepComplete];
    unsafe {
        call::<E>(c, "fmi2Terminate", modes, None, |i| {
            i.mode = Terminated;
            Ok(())
        })
    }
}

/// `fmi2Reset`: back to `Instantiated` with the model's defaults.
pub unsafe fn reset<E: Export>(c: Component) -> Status {
    unsafe {
        call::<E>(c, "fmi2Reset", ANY, None, |i| {
            let fresh = Instance::<E>::new(String::new(), i.kind, CallbackFunctions::none(), false);
            let log = std::mem::replace(&mut i.log, fresh.log);
            *i = Instance { log, ..fresh };
            Ok(())
        })
    }
}

/// `fmi2Get<Type>`: each value by its reference.
unsafe fn get_values<E: Export, T>(
    c: Component,
    what: &str,
    (vr, n, values): (*const ValueReference, usize, *mut T),
    get: fn(&mut Instance<E>, u32) -> Outcome<T>,
) -> Status {
    unsafe {
        call::<E>(c, what, READ, None, |i| {
            let (vr, out) = (slice(vr, n)?, slice_mut(values, n)?);
            for (o, r) in out.iter_mut().zip(vr) {
                *o = get(i, *r)?;
            }
            Ok(())
        })
    }
}

/// `fmi2Set<Type>`: each value by its reference.
unsafe fn set_values<E: Export, T: Copy>(
    c: Component,
    what: &str,
    (vr, n, values): (*const ValueReference, usize, *const T),
    set: fn(&mut Instance<E>, u32, T) -> Outcome,
) -> Status {
    unsafe {
        call::<E>(c, what, WRITE, None, |i| {
            for (r, v) in slice(vr, n)?.iter().zip(slice(values, n)?) {
                set(i, *r, *v)?;
            }
            Ok(())
        })
    }
}

/// `fmi2GetReal`.
pub unsafe fn get_real<E: Export>(
    c: Component,
    vr: *const ValueReference,
    n: usize,
    values: *mut Real,
) -> Status {
    unsafe { get_values::<E, Real>(c, "fmi2GetReal", (vr, n, values), Instance::get_real) }
}

/// `fmi2SetReal`.
pub unsafe fn set_real<E: Export>(
    c: Component,
    vr: *const ValueReference,
    n: usize,
    values: *const Real,
) -> Status {
    unsafe { set_values::<E, Real>(c, "fmi2SetReal", (vr, n, values), Instance::set_real) }
}

/// `fmi2GetInteger`.
pub unsafe fn get_integer<E: Export>(
    c: Component,
    vr: *const ValueReference,
    n: usize,
    values: *mut Integer,
) -> Status {
    unsafe { get_values::<E, Integer>(c, "fmi2GetInteger", (vr, n, values), Instance::get_integer) }
}

/// `fmi2SetInteger`.
pub unsafe fn set_integer<E: Export>(
    c: Component,
    vr: *const ValueReference,
    n: usize,
    values: *const Integer,
) -> Status {
    unsafe { set_values::<E, Integer>(c, "fmi2SetInteger", (vr, n, values), Instance::set_integer) }
}

/// `fmi2GetBoolean`, `fmi2SetBoolean`, `fmi2GetString`, `fmi2SetString`:
/// the FMU has no such variables, so any value reference is an error.
pub unsafe fn no_variables_of_type<E: Export>(
    c: Component,
    what: &str,
    vr: *const ValueReference,
    n: usize,
    write: bool,
) -> Status {
    let modes = if write { WRITE } else { READ };
    unsafe {
        call::<E>(c, what, modes, None, |_| match slice(vr, n)?.first() {
            Some(r) => Err(Fail::error(format!(
                "value reference {r}: the FMU has no variables of this type"
            ))),
            None => Ok(()),
        })
    }
}

/// `fmi2GetFMUstate`: saves the instance into a new state, or into the one
/// given.
pub unsafe fn get_fmu_state<E: Export>(c: Component, state: *mut FmuState) -> Status {
    unsafe {
        call::<E>(c, "fmi2GetFMUstate", ANY, None, |i| {
            if state.is_null() {
                return Err(Fail::error("a null FMU state pointer"));
            }
            let snapshot = i.snapshot();
            let old = *state;
            if old.is_null() {
                *state = Box::into_raw(Box::new(snapshot)).cast();
            } else {
                *old.cast::<Snapshot>() = snapshot;
            }
            Ok(())
        })
    }
}

/// `fmi2SetFMUstate`.
pub unsafe fn set_fmu_state<E: Export>(c: Component, state: FmuState) -> Status {
    unsafe {
        call::<E>(c, "fmi2SetFMUstate", ANY, None, |i| {
            if state.is_null() {
                return Err(Fail::error("a null FMU state"));
            }
            i.restore(&*state.cast::<Snapshot>())?;
            if i.mode == Error {
                i.mode = match i.kind {
                    ME => Event,
                    CS => StepComplete,
                };
            }
            Ok(())
        })
    }
}

/// `fmi2FreeFMUstate`.
pub unsafe fn free_fmu_state<E: Export>(c: Component, state: *mut FmuState) -> Status {
    unsafe {
        call::<E>(c, "fmi2FreeFMUstate", ANY, None, |_| {
            if !state.is_null() && !(*state).is_null() {
                drop(Box::from_raw((*state).cast::<Snapshot>()));
                *state = std::ptr::null_mut();
            }
            Ok(())
        })
    }
}

/// `fmi2SerializedFMUstateSize`.
pub unsafe fn serialized_size<E: Export>(
    c: Component,
    state: FmuState,
    size: *mut usize,
) -> Status {
    unsafe {
        call::<E>(c, "fmi2SerializedFMUstateSize", ANY, None, |_| {
            if state.is_null() {
                return Err(Fail::error("a null FMU state"));
            }
            put(size, (*state.cast::<Snapshot>()).to_bytes().len())
        })
    }
}

/// `fmi2SerializeFMUstate`.
pub unsafe fn serialize<E: Export>(
    c: Component,
    state: FmuState,
    bytes: *mut c_char,
    size: usize,
) -> Status {
    unsafe {
        call::<E>(c, "fmi2SerializeFMUstate", ANY, None, |_| {
            if state.is_null() {
                return Err(Fail::error("a null FMU state"));
            }
            let data = (*state.cast::<Snapshot>()).to_bytes();
            if data.len() != size {
                return Err(Fail::error(format!(
                    "the serialized state has {} bytes, not {size}",
                    data.len()
                )));
            }
            let out = slice_mut(bytes.cast::<u8>(), size)?;
            out.copy_from_slice(&data);
            Ok(())
        })
    }
}

/// `fmi2DeSerializeFMUstate`.
pub unsafe fn deserialize<E: Export>(
    c: Component,
    bytes: *const c_char,
    size: usize,
    state: *mut FmuState,
) -> Status {
    unsafe {
        call::<E>(c, "fmi2DeSerializeFMUstate", ANY, None, |_| {
            let data = slice(bytes.cast::<u8>(), size)?;
            let snapshot = Snapshot::from_bytes(data).map_err(Fail::error)?;
            put(state, Box::into_raw(Box::new(snapshot)).cast())
        })
    }
}

/// `fmi2GetDirectionalDerivative`.
pub unsafe fn directional_derivative<E: Export>(
    c: Component,
    unknowns: *const ValueReference,
    n_unknown: usize,
    knowns: *const ValueReference,
    n_known: usize,
    dv_known: *const Real,
    dv_unknown: *mut Real,
) -> Status {
    unsafe {
        call::<E>(c, "fmi2GetDirectionalDerivative", READ, None, |i| {
            let (u, k) = (slice(unknowns, n_unknown)?, slice(knowns, n_known)?);
            let (dk, du) = (slice(dv_known, n_known)?, slice_mut(dv_unknown, n_unknown)?);
            i.directional_derivative(u, k, dk, du)
        })
    }
}

/// A function the FMU does not support: logs why and returns `fmi2Error`.
pub unsafe fn unsupported<E: Export>(c: Component, what: &str, why: &str) -> Status {
    unsafe { call::<E>(c, what, ANY, None, |_| Err(Fail::error(why))) }
}

/// `fmi2EnterEventMode`.
pub unsafe fn enter_event_mode<E: Export>(c: Component) -> Status {
    unsafe {
        call::<E>(
            c,
            "fmi2EnterEventMode",
            &[Event, Continuous],
            Some(ME),
            |i| {
                i.mode = Event;
                Ok(())
            },
        )
    }
}

/// `fmi2NewDiscreteStates`: the events at the current instant, all of
/// them in this one call ([`Instance::settle_events`]), so no further
/// iteration is needed; no time events.
pub unsafe fn new_discrete_states<E: Export>(c: Component, info: *mut EventInfo) -> Status {
    let flag = |b: bool| if b { TRUE } else { FALSE };
    unsafe {
        call::<E>(c, "fmi2NewDiscreteStates", &[Event], Some(ME), |i| {
            let settled = i.settle_events()?;
            put(
                info,
                EventInfo {
                    new_discrete_states_needed: FALSE,
                    terminate_simulation: flag(settled.terminate),
                    nominals_of_continuous_states_changed: FALSE,
                    values_of_continuous_states_changed: flag(settled.states_changed),
                    next_event_time_defined: FALSE,
                    next_event_time: 0.0,
                },
            )
        })
    }
}

/// `fmi2EnterContinuousTimeMode`.
pub unsafe fn enter_continuous_time_mode<E: Export>(c: Component) -> Status {
    unsafe {
        call::<E>(c, "fmi2EnterContinuousTimeMode", &[Event], Some(ME), |i| {
            i.mode = Continuous;
            Ok(())
        })
    }
}

/// `fmi2CompletedIntegratorStep`: no step events.
pub unsafe fn completed_integrator_step<E: Export>(
    c: Component,
    _no_set_prior: Boolean,
    enter_event_mode: *mut Boolean,
    terminate: *mut Boolean,
) -> Status {
    unsafe {
        call::<E>(
            c,
            "fmi2CompletedIntegratorStep",
            &[Continuous],
            Some(ME),
            |_| {
                put(enter_event_mode, FALSE)?;
                put(terminate, FALSE)
            },
        )
    }
}

/// `fmi2SetTime`.
pub unsafe fn set_time<E: Export>(c: Component, t: Real) -> Status {
    unsafe {
        call::<E>(c, "fmi2SetTime", &[Event, Continuous], Some(ME), |i| {
            if !t.is_finite() {
                return Err(Fail::error(format!("time {t} is not finite")));
            }
            i.t = t;
            i.touch();
            Ok(())
        })
    }
}

/// `fmi2SetContinuousStates`.
pub unsafe fn set_continuous_states<E: Export>(c: Component, x: *const Real, n: usize) -> Status {
    unsafe {
        call::<E>(c, "fmi2SetContinuousStates", &[Continuous], Some(ME), |i| {
            i.set_continuous_states(slice(x, n)?)
        })
    }
}

/// Modes where Model Exchange reads states and derivatives.
const ME_READ: &[Mode] = &[Initialization, Event, Continuous, Terminated, Error];

/// `fmi2GetDerivatives`.
pub unsafe fn get_derivatives<E: Export>(c: Component, dx: *mut Real, n: usize) -> Status {
    unsafe {
        call::<E>(c, "fmi2GetDerivatives", ME_READ, Some(ME), |i| {
            i.derivatives(slice_mut(dx, n)?)
        })
    }
}

/// `fmi2GetEventIndicators`: the model's indicators at the current time
/// and state.
pub unsafe fn get_event_indicators<E: Export>(c: Component, z: *mut Real, n: usize) -> Status {
    unsafe {
        call::<E>(c, "fmi2GetEventIndicators", ME_READ, Some(ME), |i| {
            i.event_indicators(slice_mut(z, n)?)
        })
    }
}

/// `fmi2GetContinuousStates`.
pub unsafe fn get_continuous_states<E: Export>(c: Component, x: *mut Real, n: usize) -> Status {
    unsafe {
        call::<E>(c, "fmi2GetContinuousStates", ME_READ, Some(ME), |i| {
            i.continuous_states(slice_mut(x, n)?)
        })
    }
}

/// `fmi2GetNominalsOfContinuousStates`: 1 for every state.
pub unsafe fn get_nominals<E: Export>(c: Component, x: *mut Real, n: usize) -> Status {
    let modes = &[
        Instantiated,
        Initialization,
        Event,
        Continuous,
        Terminated,
        Error,
    ];
    unsafe {
        call::<E>(
            c,
            "fmi2GetNominalsOfContinuousStates",
            modes,
            Some(ME),
            |i| {
                let out = slice_mut(x, n)?;
                i.continuous_states(out)?;
                out.fill(1.0);
                Ok(())
            },
        )
    }
}

/// `fmi2DoStep`.
pub unsafe fn do_step<E: Export>(c: Component, t: Real, h: Real, _no_set_prior: Boolean) -> Status {
    unsafe {
        call::<E>(c, "fmi2DoStep", &[StepComplete], Some(CS), |i| {
            i.do_step(t, h)
        })
    }
}

/// Modes where the Co-Simulation status may be asked.
const CS_STATUS: &[Mode] = &[StepComplete, Terminated, Error];

/// `fmi2GetRealStatus`: the last successful time.
pub unsafe fn get_real_status<E: Export>(
    c: Component,
    kind: StatusKind,
    value: *mut Real,
) -> Status {
    unsafe {
        call::<E>(
            c,
            "fmi2GetRealStatus",
            CS_STATUS,
            Some(CS),
            |i| match kind {
                LAST_SUCCESSFUL_TIME => put(value, i.t),
                _ => Err(no_status(kind)),
            },
        )
    }
}

/// `fmi2GetBooleanStatus`: whether a terminal event asked to end the
/// simulation.
pub unsafe fn get_boolean_status<E: Export>(
    c: Component,
    kind: StatusKind,
    value: *mut Boolean,
) -> Status {
    unsafe {
        call::<E>(
            c,
            "fmi2GetBooleanStatus",
            CS_STATUS,
            Some(CS),
            |i| match kind {
                TERMINATED => put(value, if i.terminated { TRUE } else { FALSE }),
                _ => Err(no_status(kind)),
            },
        )
    }
}

/// `fmi2GetStatus`, `fmi2GetIntegerStatus`, `fmi2GetStringStatus`: steps
/// are synchronous, so there is no such status (`fmi2Discard`).
pub unsafe fn no_status_of_type<E: Export>(c: Component, what: &str, kind: StatusKind) -> Status {
    unsafe { call::<E>(c, what, CS_STATUS, Some(CS), |_| Err(no_status(kind))) }
}

fn no_status(kind: StatusKind) -> Fail {
    Fail {
        status: Status::Discard,
        message: format!("status kind {kind} is not available (steps are synchronous)"),
    }
}

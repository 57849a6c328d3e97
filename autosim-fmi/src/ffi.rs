//! The C types of `fmi2FunctionTypes.h` and `fmi2TypesPlatform.h` (FMI 2.0,
//! "default" platform types), written from the standard.

use std::ffi::{c_char, c_int, c_uint, c_void};

/// `fmi2Component`: the instance pointer handed to the importer.
pub type Component = *mut c_void;
/// `fmi2ComponentEnvironment`: the importer's pointer, passed back to its
/// callbacks.
pub type ComponentEnvironment = *mut c_void;
/// `fmi2FMUstate`: a saved state.
pub type FmuState = *mut c_void;
/// `fmi2ValueReference`.
pub type ValueReference = c_uint;
/// `fmi2Real`.
pub type Real = f64;
/// `fmi2Integer`.
pub type Integer = c_int;
/// `fmi2Boolean` (0 false, anything else true).
pub type Boolean = c_int;
/// `fmi2String`.
pub type FmiString = *const c_char;
/// `fmi2Byte`.
pub type Byte = c_char;

/// `fmi2True`.
pub const TRUE: Boolean = 1;
/// `fmi2False`.
pub const FALSE: Boolean = 0;

/// `fmi2Status`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Status {
    /// All well.
    Ok = 0,
    /// Something is not quite right, but the computation can continue.
    Warning = 1,
    /// The step or call was not done; the importer may retry differently.
    Discard = 2,
    /// This instance cannot continue (until `fmi2Reset` or a restored
    /// state).
    Error = 3,
    /// No instance of the FMU can continue.
    Fatal = 4,
    /// Asynchronous step in progress (never returned here).
    Pending = 5,
}

/// `fmi2Type`: what an instance is for.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FmuType {
    /// Model Exchange: the importer integrates.
    ModelExchange = 0,
    /// Co-Simulation: the FMU integrates between communication points.
    CoSimulation = 1,
}

/// `fmi2StatusKind`: what `fmi2Get*Status` asks.
pub type StatusKind = c_int;
/// `fmi2DoStepStatus`.
pub const DO_STEP_STATUS: StatusKind = 0;
/// `fmi2PendingStatus`.
pub const PENDING_STATUS: StatusKind = 1;
/// `fmi2LastSuccessfulTime`.
pub const LAST_SUCCESSFUL_TIME: StatusKind = 2;
/// `fmi2Terminated`.
pub const TERMINATED: StatusKind = 3;

/// `fmi2CallbackLogger` (variadic: the message is a `printf` format).
pub type Logger = Option<
    unsafe extern "C" fn(ComponentEnvironment, FmiString, Status, FmiString, FmiString, ...),
>;

/// `fmi2CallbackFunctions`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct CallbackFunctions {
    /// The logger.
    pub logger: Logger,
    /// `calloc`-like allocator (not used: the FMU allocates with Rust's).
    pub allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    /// `free`-like deallocator (not used).
    pub free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    /// Asynchronous step callback (not used: steps are synchronous).
    pub step_finished: Option<unsafe extern "C" fn(ComponentEnvironment, Status)>,
    /// The importer's pointer for the callbacks.
    pub component_environment: ComponentEnvironment,
}

/// `fmi2EventInfo`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct EventInfo {
    /// Another event iteration is needed.
    pub new_discrete_states_needed: Boolean,
    /// The model asks to stop.
    pub terminate_simulation: Boolean,
    /// The nominal values of the states changed.
    pub nominals_of_continuous_states_changed: Boolean,
    /// The states were changed by the event.
    pub values_of_continuous_states_changed: Boolean,
    /// `next_event_time` holds a time event.
    pub next_event_time_defined: Boolean,
    /// The next time event.
    pub next_event_time: Real,
}

impl CallbackFunctions {
    /// No callbacks (nothing is logged).
    pub fn none() -> CallbackFunctions {
        CallbackFunctions {
            logger: None,
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: std::ptr::null_mut(),
        }
    }
}

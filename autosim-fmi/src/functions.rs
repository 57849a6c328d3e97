//! The `extern "C"` functions of FMI 2.0 with the standard's names and
//! signatures (`fmi2Functions.h`), each a call of its generic body in
//! [`entry`](crate::entry).

/// Writes the 44 `fmi2*` functions for the [`Export`](crate::Export) type
/// `$e` (used by [`export_fmi2!`](crate::export_fmi2)).
#[doc(hidden)]
#[macro_export]
macro_rules! fmi2_functions {
    ($e:ty) => {
        const _: () = {
            use $crate::entry as entry;
            use $crate::ffi::*;
            use ::std::ffi::c_char;

            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetTypesPlatform() -> FmiString {
                c"default".as_ptr()
            }
            /// Not an FMI function: the model's event indicators and
            /// discrete variables as text (`autosim_fmi::EventInterface`),
            /// read by `autosim-fmu` to write them into the description.
            /// Writes what fits into `buffer` and returns the text's length.
            ///
            /// # Safety
            /// `buffer` points to `length` writable bytes.
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn autosim_fmi_event_interface(buffer: *mut u8, length: usize) -> usize {
                unsafe { $crate::events::write_event_interface::<$e>(buffer, length) }
            }
            /// Not an FMI function: the GUID `fmi2Instantiate` accepts,
            /// read by `autosim-fmu` to check the library against the
            /// description it packages it with. Writes what fits into
            /// `buffer` and returns the GUID's length.
            ///
            /// # Safety
            /// `buffer` points to `length` writable bytes.
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn autosim_fmi_guid(buffer: *mut u8, length: usize) -> usize {
                unsafe { $crate::events::write_guid::<$e>(buffer, length) }
            }
            #[unsafe(no_mangle)]
            pub extern "C" fn fmi2GetVersion() -> FmiString {
                c"2.0".as_ptr()
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetDebugLogging(c: Component, on: Boolean, n: usize, categories: *const FmiString) -> Status {
                unsafe { entry::set_debug_logging::<$e>(c, on, n, categories) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Instantiate(name: FmiString, kind: FmuType, guid: FmiString, resources: FmiString, functions: *const CallbackFunctions, visible: Boolean, logging_on: Boolean) -> Component {
                unsafe { entry::instantiate::<$e>(name, kind, guid, resources, functions, visible, logging_on) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeInstance(c: Component) {
                unsafe { entry::free_instance::<$e>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetupExperiment(c: Component, tolerance_defined: Boolean, tolerance: Real, start: Real, stop_defined: Boolean, stop: Real) -> Status {
                unsafe { entry::setup_experiment::<$e>(c, tolerance_defined, tolerance, start, stop_defined, stop) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterInitializationMode(c: Component) -> Status {
                unsafe { entry::enter_initialization_mode::<$e>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2ExitInitializationMode(c: Component) -> Status {
                unsafe { entry::exit_initialization_mode::<$e>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Terminate(c: Component) -> Status {
                unsafe { entry::terminate::<$e>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2Reset(c: Component) -> Status {
                unsafe { entry::reset::<$e>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetReal(c: Component, vr: *const ValueReference, n: usize, values: *mut Real) -> Status {
                unsafe { entry::get_real::<$e>(c, vr, n, values) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetInteger(c: Component, vr: *const ValueReference, n: usize, values: *mut Integer) -> Status {
                unsafe { entry::get_integer::<$e>(c, vr, n, values) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetBoolean(c: Component, vr: *const ValueReference, n: usize, _values: *mut Boolean) -> Status {
                unsafe { entry::no_variables_of_type::<$e>(c, "fmi2GetBoolean", vr, n, false) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetString(c: Component, vr: *const ValueReference, n: usize, _values: *mut FmiString) -> Status {
                unsafe { entry::no_variables_of_type::<$e>(c, "fmi2GetString", vr, n, false) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetReal(c: Component, vr: *const ValueReference, n: usize, values: *const Real) -> Status {
                unsafe { entry::set_real::<$e>(c, vr, n, values) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetInteger(c: Component, vr: *const ValueReference, n: usize, values: *const Integer) -> Status {
                unsafe { entry::set_integer::<$e>(c, vr, n, values) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetBoolean(c: Component, vr: *const ValueReference, n: usize, _values: *const Boolean) -> Status {
                unsafe { entry::no_variables_of_type::<$e>(c, "fmi2SetBoolean", vr, n, true) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetString(c: Component, vr: *const ValueReference, n: usize, _values: *const FmiString) -> Status {
                unsafe { entry::no_variables_of_type::<$e>(c, "fmi2SetString", vr, n, true) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetFMUstate(c: Component, state: *mut FmuState) -> Status {
                unsafe { entry::get_fmu_state::<$e>(c, state) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetFMUstate(c: Component, state: FmuState) -> Status {
                unsafe { entry::set_fmu_state::<$e>(c, state) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2FreeFMUstate(c: Component, state: *mut FmuState) -> Status {
                unsafe { entry::free_fmu_state::<$e>(c, state) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializedFMUstateSize(c: Component, state: FmuState, size: *mut usize) -> Status {
                unsafe { entry::serialized_size::<$e>(c, state, size) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SerializeFMUstate(c: Component, state: FmuState, bytes: *mut c_char, size: usize) -> Status {
                unsafe { entry::serialize::<$e>(c, state, bytes, size) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DeSerializeFMUstate(c: Component, bytes: *const c_char, size: usize, state: *mut FmuState) -> Status {
                unsafe { entry::deserialize::<$e>(c, bytes, size, state) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetDirectionalDerivative(c: Component, unknowns: *const ValueReference, n_unknown: usize, knowns: *const ValueReference, n_known: usize, dv_known: *const Real, dv_unknown: *mut Real) -> Status {
                unsafe { entry::directional_derivative::<$e>(c, unknowns, n_unknown, knowns, n_known, dv_known, dv_unknown) }
            }

            // Model Exchange.
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterEventMode(c: Component) -> Status {
                unsafe { entry::enter_event_mode::<$e>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2NewDiscreteStates(c: Component, info: *mut EventInfo) -> Status {
                unsafe { entry::new_discrete_states::<$e>(c, info) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2EnterContinuousTimeMode(c: Component) -> Status {
                unsafe { entry::enter_continuous_time_mode::<$e>(c) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2CompletedIntegratorStep(c: Component, no_set_prior: Boolean, enter_event_mode: *mut Boolean, terminate: *mut Boolean) -> Status {
                unsafe { entry::completed_integrator_step::<$e>(c, no_set_prior, enter_event_mode, terminate) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetTime(c: Component, t: Real) -> Status {
                unsafe { entry::set_time::<$e>(c, t) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetContinuousStates(c: Component, x: *const Real, n: usize) -> Status {
                unsafe { entry::set_continuous_states::<$e>(c, x, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetDerivatives(c: Component, dx: *mut Real, n: usize) -> Status {
                unsafe { entry::get_derivatives::<$e>(c, dx, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetEventIndicators(c: Component, z: *mut Real, n: usize) -> Status {
                unsafe { entry::get_event_indicators::<$e>(c, z, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetContinuousStates(c: Component, x: *mut Real, n: usize) -> Status {
                unsafe { entry::get_continuous_states::<$e>(c, x, n) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(c: Component, x: *mut Real, n: usize) -> Status {
                unsafe { entry::get_nominals::<$e>(c, x, n) }
            }

            // Co-Simulation.
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2SetRealInputDerivatives(c: Component, _vr: *const ValueReference, _n: usize, _order: *const Integer, _values: *const Real) -> Status {
                unsafe { entry::unsupported::<$e>(c, "fmi2SetRealInputDerivatives", "input derivatives are not used (canInterpolateInputs=\"false\"): inputs are held over each step") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(c: Component, _vr: *const ValueReference, _n: usize, _order: *const Integer, _values: *mut Real) -> Status {
                unsafe { entry::unsupported::<$e>(c, "fmi2GetRealOutputDerivatives", "output derivatives are not provided (maxOutputDerivativeOrder=\"0\")") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2DoStep(c: Component, t: Real, h: Real, no_set_prior: Boolean) -> Status {
                unsafe { entry::do_step::<$e>(c, t, h, no_set_prior) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2CancelStep(c: Component) -> Status {
                unsafe { entry::unsupported::<$e>(c, "fmi2CancelStep", "steps are synchronous (canRunAsynchronuously=\"false\"): there is no step to cancel") }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetStatus(c: Component, kind: StatusKind, _value: *mut Status) -> Status {
                unsafe { entry::no_status_of_type::<$e>(c, "fmi2GetStatus", kind) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetRealStatus(c: Component, kind: StatusKind, value: *mut Real) -> Status {
                unsafe { entry::get_real_status::<$e>(c, kind, value) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetIntegerStatus(c: Component, kind: StatusKind, _value: *mut Integer) -> Status {
                unsafe { entry::no_status_of_type::<$e>(c, "fmi2GetIntegerStatus", kind) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetBooleanStatus(c: Component, kind: StatusKind, value: *mut Boolean) -> Status {
                unsafe { entry::get_boolean_status::<$e>(c, kind, value) }
            }
            #[unsafe(no_mangle)]
            pub unsafe extern "C" fn fmi2GetStringStatus(c: Component, kind: StatusKind, _value: *mut FmiString) -> Status {
                unsafe { entry::no_status_of_type::<$e>(c, "fmi2GetStringStatus", kind) }
            }
        };
    };
}

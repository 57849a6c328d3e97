//! Ctrl-C during long native work. Python runs a signal's handler (Ctrl-C's
//! raises `KeyboardInterrupt`) only when its main thread checks for
//! signals, which native code running without the GIL never does; so
//! runs check (`Python::check_signals`, the GIL taken back for a moment)
//! about every [`PERIOD`] and stop with the handler's exception:
//!
//! - a simulation runs on the calling thread: [`Poll`], asked at each
//!   derivative evaluation by [`Driven`](crate::inputs::Driven), checks
//!   every so often and then fails the evaluation, which ends the run
//!   (`native` raises the exception the check kept);
//! - a study runs on a thread of its own ([`watched`]) while the calling
//!   thread checks; on a signal it sets the study's
//!   [`Cancel`](autosim_runtime::study::Cancel), which starts no new
//!   case (a folder keeps only whole shards), and waits for the cases
//!   running to end.

use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often a run looks at Python's signals.
pub const PERIOD: Duration = Duration::from_millis(100);

/// Evaluations between two looks at the clock (reading it costs about
/// as much as a small model's derivatives).
const EVERY: u32 = 256;

/// Whether a simulation must stop, asked at every derivative evaluation
/// and answered by `check` at most once a [`PERIOD`]; once it says stop,
/// it says so to the end.
pub struct Poll {
    check: Box<dyn FnMut() -> bool + Send>,
    calls: u32,
    last: Instant,
    stopped: bool,
}

impl Poll {
    /// A poll that asks `check` (`true`: stop).
    pub fn new(check: impl FnMut() -> bool + Send + 'static) -> Poll {
        Poll {
            check: Box::new(check),
            calls: 0,
            last: Instant::now(),
            stopped: false,
        }
    }

    /// A poll that never stops the run.
    pub fn never() -> Poll {
        Poll::new(|| false)
    }

    /// Whether the run must stop.
    pub fn stopped(&mut self) -> bool {
        if !self.stopped {
            self.calls = self.calls.wrapping_add(1);
            if self.calls.is_multiple_of(EVERY) && self.last.elapsed() >= PERIOD {
                self.last = Instant::now();
                self.stopped = (self.check)();
            }
        }
        self.stopped
    }
}

/// A poll that checks Python's signals, keeping the handler's exception
/// in `slot` (unless it holds one already) when it stops the run.
pub fn signals(slot: std::sync::Arc<std::sync::Mutex<Option<PyErr>>>) -> Poll {
    Poll::new(move || {
        Python::attach(|py| match py.check_signals() {
            Ok(()) => false,
            Err(e) => {
                let mut kept = slot.lock().unwrap_or_else(|p| p.into_inner());
                kept.get_or_insert(e);
                true
            }
        })
    })
}

/// Runs `work` on a thread of its own while this one waits with the GIL
/// released, checking Python's signals every [`PERIOD`]. On a signal
/// whose handler raises, calls `stop`, waits for `work` to end and
/// returns the handler's exception. A panic in `work` (a bug) comes back
/// as its message (`Ok(Err(message))`).
pub fn watched<T: Send>(
    py: Python<'_>,
    stop: impl FnOnce() + Send,
    work: impl FnOnce() -> T + Send,
) -> PyResult<Result<T, String>> {
    std::thread::scope(|scope| {
        let (sender, receiver) = mpsc::channel();
        scope.spawn(move || {
            let _ = sender.send(crate::native::unpanicked(work));
        });
        py.detach(move || wait(receiver, stop))
    })
}

/// The value `receiver` gets, checking Python's signals while it waits
/// (see [`watched`]).
fn wait<T>(receiver: Receiver<T>, stop: impl FnOnce()) -> PyResult<T> {
    loop {
        match receiver.recv_timeout(PERIOD) {
            Ok(value) => return Ok(value),
            Err(RecvTimeoutError::Timeout) => {
                if let Err(e) = Python::attach(|py| py.check_signals()) {
                    stop();
                    let _ = receiver.recv();
                    return Err(e);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "internal error, a bug in autosim (please report it): \
                     a study's thread ended without its result",
                ));
            }
        }
    }
}

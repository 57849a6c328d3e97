//! Stopping a study early ([`Cancel`]): a flag shared between a running
//! study and whoever wants it stopped (a Ctrl-C handler, a user
//! interface, a time limit).

use core::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A flag that stops the studies given it ([`Study::cancel_with`]).
///
/// Once [`cancel`](Cancel::cancel) is called, the study starts no new
/// case; cases already running finish (a case is never cut short), and
/// [`Study::run_cases`] and [`Study::run_in`] return
/// [`StudyError::Cancelled`]. `run_in` writes no shard after that (the
/// shard in progress is dropped), so every shard in the folder is whole
/// and running the study again resumes it. Clones share the flag; it
/// stays set (make a new one for the next run).
///
/// [`Study::cancel_with`]: super::Study::cancel_with
/// [`Study::run_cases`]: super::Study::run_cases
/// [`Study::run_in`]: super::Study::run_in
/// [`StudyError::Cancelled`]: super::StudyError::Cancelled
#[derive(Clone, Debug, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// A flag not set.
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Sets the flag: the studies given it stop at the next case.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether the flag is set.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{
        CaseError, Cases, Custom, Field, Format, Parallelism, Study, StudyDir, StudyError,
    };
    use super::Cancel;
    use crate::{Model, ModelError};
    use std::boxed::Box;
    use std::sync::atomic::{AtomicU64, Ordering};
    use std::vec::Vec;

    /// `x' = 0`; the study's task keeps the case's `k` and counts runs.
    struct Still {
        k: f64,
    }

    impl Model for Still {
        type Float = f64;
        type State = [f64; 1];
        type Outputs = [f64; 0];
        const NAME: &'static str = "Still";
        const STATE_NAMES: &'static [&'static str] = &["x"];
        const STATE_UNITS: &'static [&'static str] = &["1"];
        const PARAMETER_NAMES: &'static [&'static str] = &["k"];
        fn derivatives(
            &mut self,
            _: f64,
            _: &[f64; 1],
            dx: &mut [f64; 1],
        ) -> Result<(), ModelError> {
            dx[0] = 0.0;
            Ok(())
        }
        fn parameter_values(&self, p: &mut [f64]) {
            p[0] = self.k;
        }
        fn set_parameter_values(&mut self, p: &[f64]) {
            self.k = p[0];
        }
    }

    /// The task: keeps `k`.
    type Run = dyn Fn(&mut Still, &mut [f64; 1], &mut [f64]) -> Result<(), CaseError> + Sync;

    /// A serial study of 12 cases (`k` = 0..12) whose task keeps `k`,
    /// counts its runs in `runs` and sets `cancel` at case `stop_at`.
    fn study(
        cancel: &Cancel,
        stop_at: f64,
        runs: &'static AtomicU64,
    ) -> Study<Still, fn() -> Still, Custom<Box<Run>>> {
        let cases = Cases::new()
            .grid("k", &(0..12).map(f64::from).collect::<Vec<_>>())
            .unwrap();
        let flag = cancel.clone();
        let run: Box<Run> = Box::new(
            move |model: &mut Still, _: &mut [f64; 1], out: &mut [f64]| {
                runs.fetch_add(1, Ordering::Relaxed);
                if model.k == stop_at {
                    flag.cancel();
                }
                out[0] = model.k;
                Ok(())
            },
        );
        let task = Custom::new::<Still>("keep k", &[Field::new("k", 1)], run);
        let make: fn() -> Still = || Still { k: 0.0 };
        Study::new(make, cases, task)
            .parallelism(Parallelism::Serial)
            .progress(false)
            .cancel_with(cancel.clone())
    }

    #[test]
    fn a_cancelled_run_starts_no_new_case_and_says_so() {
        static RUNS: AtomicU64 = AtomicU64::new(0);
        let cancel = Cancel::new();
        let e = study(&cancel, 3.0, &RUNS).run_cases(0..12).unwrap_err();
        assert!(matches!(e, StudyError::Cancelled), "{e}");
        assert_eq!(RUNS.load(Ordering::Relaxed), 4);
        assert!(cancel.is_cancelled());
    }

    #[test]
    fn a_cancelled_run_in_keeps_whole_shards_and_resumes() {
        static RUNS: AtomicU64 = AtomicU64::new(0);
        let dir =
            std::env::temp_dir().join(std::format!("autosim-study-cancel-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let cancel = Cancel::new();
        let e = study(&cancel, 5.0, &RUNS)
            .run_in(&dir, Format::Csv, 4)
            .unwrap_err();
        assert!(matches!(e, StudyError::Cancelled), "{e}");
        // Shard 0 (cases 0..4) is written whole; shard 1 stopped at case 5.
        let written = StudyDir::open(&dir).unwrap();
        assert_eq!(
            (0..3).map(|k| written.has_shard(k)).collect::<Vec<_>>(),
            [true, false, false]
        );
        let shard = written.read_shard(0).unwrap();
        let resumed = study(&Cancel::new(), f64::NAN, &RUNS)
            .run_in(&dir, Format::Csv, 4)
            .unwrap();
        assert_eq!((resumed.ran, resumed.skipped), (8, 4));
        let all = StudyDir::open(&dir).unwrap().read_all().unwrap();
        let whole = study(&Cancel::new(), f64::NAN, &RUNS)
            .run_cases(0..12)
            .unwrap();
        assert_eq!(all, whole);
        let first = study(&Cancel::new(), f64::NAN, &RUNS)
            .run_cases(0..4)
            .unwrap();
        assert_eq!(shard, first);
        let _ = std::fs::remove_dir_all(&dir);
    }
}

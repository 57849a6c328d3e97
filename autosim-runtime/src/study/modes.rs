//! The modes task (features `study` and `analysis`): linearize each case
//! (at a trim, if asked) and keep the eigenvalues.

use core::marker::PhantomData;
use std::format;
use std::string::{String, ToString};
use std::vec::Vec;

use super::StudyError;
use super::task::{CaseError, Field, Task};
use crate::Linearize;
use crate::analysis::{LinearSystem, Trim, trim};

/// Linearizes each case at its initial state (after a [`Trim`], if one
/// is given, which moves the state and inputs to an equilibrium or a
/// steady motion) and keeps the eigenvalues of `A` sorted by real part,
/// then imaginary part: fields `re` and `im`, one value per linear state
/// (of the restricted system, if `states` are given).
///
/// nalgebra's eigenvalue solver allocates its matrices: this task is
/// allocation-free only in the linearization, not in the eigenvalues.
pub struct Modes<M> {
    states: Option<Vec<String>>,
    trim: Option<Trim>,
    count: usize,
    model: PhantomData<fn() -> M>,
}

impl<M: Linearize<Float = f64>> Modes<M> {
    /// The task: eigenvalues of the system restricted to `states` (by
    /// name, e.g. without ignorable coordinates; `None` for every linear
    /// state), after `trim` if given.
    ///
    /// # Errors
    /// [`StudyError::UnknownQuantity`] for a name that is not a linear
    /// state of `M`.
    pub fn new(states: Option<&[&str]>, trim: Option<Trim>) -> Result<Modes<M>, StudyError> {
        let linear: Vec<&str> = M::LINEAR_STATES
            .iter()
            .map(|k| M::STATE_NAMES[*k])
            .collect();
        if let Some(names) = states {
            for name in names {
                if !linear.contains(name) {
                    return Err(StudyError::UnknownQuantity {
                        name: name.to_string(),
                        model: M::NAME,
                        known: linear.iter().map(|s| s.to_string()).collect(),
                    });
                }
            }
        }
        Ok(Modes {
            count: states.map_or(linear.len(), <[&str]>::len),
            states: states.map(|s| s.iter().map(|n| n.to_string()).collect()),
            trim,
            model: PhantomData,
        })
    }
}

impl<M: Linearize<Float = f64>> Task<M> for Modes<M> {
    fn fields(&self) -> Vec<Field> {
        Vec::from([Field::new("re", self.count), Field::new("im", self.count)])
    }

    fn run(&self, model: &mut M, x: &mut M::State, out: &mut [f64]) -> Result<(), CaseError> {
        match &self.trim {
            Some(spec) => {
                trim(model, 0.0, x, spec).map_err(|e| CaseError::Other(format!("trim: {e}")))?;
            }
            None => model.assemble(0.0, x)?,
        }
        let mut system = LinearSystem::of(model, 0.0, x)?;
        if let Some(states) = &self.states {
            let names: Vec<&str> = states.iter().map(String::as_str).collect();
            system = system.restricted(&names).map_err(CaseError::Other)?;
        }
        let (re, im) = out.split_at_mut(self.count);
        for (k, l) in system.eigenvalues().iter().enumerate() {
            re[k] = l.re;
            im[k] = l.im;
        }
        Ok(())
    }

    fn describe(&self) -> String {
        format!("modes {} {:?} {:?}", M::NAME, self.states, self.trim)
    }
}

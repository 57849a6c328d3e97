//! `fmi2GetFMUstate` and its family: a saved instance is its time, whole
//! state vector, parameters, inputs, discrete variables, settings and the
//! event indicators' known signs (the model's state is small and plain),
//! serialized as little-endian numbers behind a header.

use crate::Export;
use crate::instance::{Fail, Instance, Outcome, Settings};
use crate::layout::Method;
use autosim_runtime::{Model, StateArray};

/// What a saved state holds.
#[derive(Clone, Debug, PartialEq)]
pub struct Snapshot {
    t: f64,
    x: Vec<f64>,
    parameters: Vec<f64>,
    inputs: Vec<f64>,
    discrete: Vec<f64>,
    started: Vec<bool>,
    /// The event indicators' last known signs (-1, 0, 1).
    signs: Vec<i8>,
    terminated: bool,
    settings: Settings,
    h_next: f64,
}

/// The first bytes of a serialized state.
const MAGIC: &[u8; 8] = b"autosim3";

impl<E: Export> Instance<E> {
    /// The instance's state.
    pub fn snapshot(&self) -> Snapshot {
        let mut parameters = vec![0.0; self.layout.parameters];
        self.model.parameter_values(&mut parameters);
        let mut inputs = vec![0.0; self.layout.inputs];
        self.model.input_values(&mut inputs);
        let mut discrete = vec![0.0; self.layout.discrete];
        self.model.discrete_values(&mut discrete);
        Snapshot {
            t: self.t,
            x: self.x.as_ref().to_vec(),
            parameters,
            inputs,
            discrete,
            started: self.started.clone(),
            signs: self.signs.clone(),
            terminated: self.terminated,
            settings: self.settings,
            h_next: self.h_next,
        }
    }

    /// Restores a saved state (the integrator starts afresh from it).
    pub fn restore(&mut self, s: &Snapshot) -> Outcome {
        let n = <<E::Model as Model>::State as StateArray<f64>>::LEN;
        let fits = s.x.len() == n
            && s.parameters.len() == self.layout.parameters
            && s.inputs.len() == self.layout.inputs
            && s.discrete.len() == self.layout.discrete
            && s.signs.len() == self.signs.len()
            && s.started.len() == self.started.len();
        if !fits {
            return Err(Fail::error("the FMU state belongs to another model"));
        }
        self.t = s.t;
        self.x.as_mut().copy_from_slice(&s.x);
        self.model.set_parameter_values(&s.parameters);
        self.model.set_input_values(&s.inputs);
        self.model.set_discrete_values(&s.discrete);
        self.started.clone_from(&s.started);
        self.signs.clone_from(&s.signs);
        self.terminated = s.terminated;
        self.settings = s.settings;
        self.h_next = s.h_next;
        if let Some(stepper) = self.stepper.as_mut() {
            stepper.reset();
        }
        // The saved state was assembled (or is the start, assembled when
        // next needed).
        self.solved_once = false;
        self.touch_state();
        Ok(())
    }
}

impl Snapshot {
    /// The bytes of `fmi2SerializeFMUstate`.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = MAGIC.to_vec();
        let counts = [
            self.x.len(),
            self.parameters.len(),
            self.inputs.len(),
            self.discrete.len(),
        ];
        for n in counts {
            out.extend((n as u64).to_le_bytes());
        }
        out.extend((self.started.len() as u64).to_le_bytes());
        out.extend(self.started.iter().map(|&b| b as u8));
        out.extend((self.signs.len() as u64).to_le_bytes());
        out.extend(self.signs.iter().map(|&s| s as u8));
        out.push(self.terminated as u8);
        out.extend((self.settings.method as i32 as u64).to_le_bytes());
        let numbers = [
            self.t,
            self.settings.tolerance,
            self.settings.step,
            self.h_next,
        ];
        for v in numbers
            .iter()
            .chain(&self.x)
            .chain(&self.parameters)
            .chain(&self.inputs)
            .chain(&self.discrete)
        {
            out.extend(v.to_le_bytes());
        }
        out
    }

    /// A state from its serialized bytes, or why they are not one.
    pub fn from_bytes(bytes: &[u8]) -> Result<Snapshot, String> {
        let mut r = Reader { bytes, at: 0 };
        if r.take(MAGIC.len())? != MAGIC {
            return Err("the bytes are not a serialized autosim FMU state".into());
        }
        let (nx, np, nw, nd) = (r.count()?, r.count()?, r.count()?, r.count()?);
        let ns = r.count()?;
        let started = r.take(ns)?.iter().map(|&b| b != 0).collect();
        let nz = r.count()?;
        let signs = r.take(nz)?.iter().map(|&b| b as i8).collect();
        let terminated = r.take(1)?[0] != 0;
        let method = Method::from_value(r.count()? as i32)
            .ok_or("the serialized state names no known cs.method")?;
        let (t, tolerance, step, h_next) = (r.real()?, r.real()?, r.real()?, r.real()?);
        let mut reals = |n: usize| (0..n).map(|_| r.real()).collect::<Result<Vec<_>, _>>();
        let (x, parameters, inputs) = (reals(nx)?, reals(np)?, reals(nw)?);
        let discrete = reals(nd)?;
        if r.at != bytes.len() {
            return Err("the serialized state has trailing bytes".into());
        }
        Ok(Snapshot {
            t,
            x,
            parameters,
            inputs,
            discrete,
            started,
            signs,
            terminated,
            settings: Settings {
                method,
                tolerance,
                step,
            },
            h_next,
        })
    }
}

/// Reads a serialized state front to back.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or("the serialized state is too short")?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }

    fn word(&mut self) -> Result<[u8; 8], String> {
        let mut w = [0u8; 8];
        w.copy_from_slice(self.take(8)?);
        Ok(w)
    }

    fn count(&mut self) -> Result<usize, String> {
        let n = u64::from_le_bytes(self.word()?);
        usize::try_from(n)
            .ok()
            .filter(|&n| n <= self.bytes.len())
            .ok_or_else(|| "the serialized state has an impossible length".to_string())
    }

    fn real(&mut self) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.word()?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_snapshot_survives_its_bytes_and_bad_bytes_are_refused() {
        let s = Snapshot {
            t: 1.5,
            x: vec![0.1, -2.0, 3.0],
            parameters: vec![9.81],
            inputs: vec![],
            discrete: vec![2.0],
            started: vec![true, false, true],
            signs: vec![-1, 0, 1],
            terminated: true,
            settings: Settings {
                method: Method::Rk4,
                tolerance: 1e-9,
                step: 0.01,
            },
            h_next: 0.02,
        };
        let bytes = s.to_bytes();
        assert_eq!(Snapshot::from_bytes(&bytes), Ok(s));
        assert!(Snapshot::from_bytes(&bytes[..bytes.len() - 1]).is_err());
        assert!(Snapshot::from_bytes(b"not a state at all").is_err());
        let mut long = bytes.clone();
        long.push(0);
        assert!(Snapshot::from_bytes(&long).is_err());
    }
}

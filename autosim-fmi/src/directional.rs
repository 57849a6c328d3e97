//! `fmi2GetDirectionalDerivative` from the model's generated linearization
//! (`A`, `B`, `C`, `D` from symbolic derivatives of its equations, in the
//! FMU's states: the independent ones).

use crate::Export;
use crate::instance::{Fail, Instance, Outcome};
use crate::layout::Variable;

impl<E: Export> Instance<E> {
    /// `dv_unknown = J dv_known` with `J` the partial derivatives of the
    /// unknowns (state derivatives, outputs) with respect to the knowns
    /// (states, inputs) at the current point.
    pub fn directional_derivative(
        &mut self,
        unknowns: &[u32],
        knowns: &[u32],
        dv_known: &[f64],
        dv_unknown: &mut [f64],
    ) -> Outcome {
        self.assemble()?;
        let (nl, nw, ny) = (
            self.independent.len(),
            self.layout.inputs,
            self.layout.outputs,
        );
        let (mut a, mut b) = (vec![0.0; nl * nl], vec![0.0; nl * nw]);
        let (mut c, mut d) = (vec![0.0; ny * nl], vec![0.0; ny * nw]);
        let x = self.x;
        match E::linearize(
            &mut self.model,
            self.t,
            &x,
            [&mut a, &mut b, &mut c, &mut d],
        ) {
            None => {
                return Err(Fail::error(
                    "this FMU has no directional derivatives (providesDirectionalDerivative=\"false\")",
                ));
            }
            Some(result) => result?,
        }
        for (out, &u) in dv_unknown.iter_mut().zip(unknowns) {
            let (row_x, row_w) = match self.layout.variable(u) {
                Some(Variable::Derivative(k)) => (&a[k * nl..][..nl], &b[k * nw..][..nw]),
                Some(Variable::Output(k)) => (&c[k * nl..][..nl], &d[k * nw..][..nw]),
                _ => {
                    return Err(Fail::error(format!(
                        "unknown {u} is not a state derivative or an output"
                    )));
                }
            };
            let mut sum = 0.0;
            for (&k, dv) in knowns.iter().zip(dv_known) {
                sum += dv
                    * match self.layout.variable(k) {
                        Some(Variable::State(s)) => row_x[s],
                        Some(Variable::Input(w)) => row_w[w],
                        _ => {
                            return Err(Fail::error(format!(
                                "known {k} is not a continuous state or an input"
                            )));
                        }
                    };
            }
            *out = sum;
        }
        Ok(())
    }
}

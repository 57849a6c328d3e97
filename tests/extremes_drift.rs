//! Stability at the extremes: 10⁶ steps of an undamped oscillator per
//! integrator, each drifting in energy as its stability function predicts
//! (see `extremes/mod.rs`).
//!
//! | case | expected behaviour |
//! | --- | --- |
//! | 10⁶ steps, energy drift per integrator | the drift each method's stability function predicts for ωh = 0.01 (table at `drift`) |

mod extremes;

use autosim::runtime::integrate::{
    AbmOrder, AdamsBashforthMoulton, DormandPrince, Euler, Heun, Rk4, Sdirk3, SdirkSettings,
};
use autosim::runtime::{Model, Stepper};
use extremes::run_to;

mod models {
    autosim::model!(file = "tests/models/extremes/oscillator.sim");
}

/// A million steps of h = 0.01 s (ωh = 0.01, 1592 periods) of the
/// undamped oscillator, per integrator. For x'' = -ω²x the energy after n
/// steps is |R(iωh)|²ⁿ E₀, with R the method's stability function (for
/// the multistep pairs, the principal root of the PECE recurrence), so
/// each method's drift is known in advance:
///
/// | method | predicted ln(E/E₀) after 10⁶ steps | meaning | measured − predicted |
/// | --- | --- | --- | --- |
/// | Euler | +99.995 | grows ×10⁴³: unusable for long undamped runs | 3e-13 |
/// | Heun | +2.5000e-3 | grows 0.25 % | −3e-14 |
/// | RK4 | −1.3889e-8 | decays 1.4e-8 | 1.4e-13 |
/// | ABM2 (PECE) | −4.9995e-3 | decays 0.5 % | 5e-9 (RK4 start-up) |
/// | ABM4 (PECE) | +3.2286e-7 | grows 3e-7 | −1e-12 |
/// | Dormand–Prince (steps capped at h) | −5.555e-10 | decays 6e-10 | 2e-13 |
/// | SDIRK3 | −5.1792e-4 | decays 0.05 % (L-stable: always decays) | 3e-14 |
///
/// Each measured drift is asserted to match its prediction to about ten
/// times the difference above: bounded, of the sign and size the method
/// implies, never a random walk or a blow-up. (The Dormand–Prince and
/// SDIRK3 runs are the slowest cases here, a few seconds in a debug build.)
fn drift(name: &str, stepper: &mut dyn Stepper<models::oscillator::Oscillator>) -> f64 {
    let mut model = models::oscillator::Oscillator::new();
    let mut x = model.initial_state();
    let (mut y0, mut y1) = ([0.0], [0.0]);
    model.outputs(0.0, &x, &mut y0).unwrap();
    let s = run_to(&mut model, stepper, &mut x, 1e4, 0.01, 2_000_000)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(
        (999_990..=1_000_010).contains(&s.steps),
        "{name}: {} steps",
        s.steps
    );
    model.outputs(1e4, &x, &mut y1).unwrap();
    (y1[0] / y0[0]).ln()
}

macro_rules! drift_test {
    ($test:ident, $stepper:expr, $theory:expr, $tolerance:expr) => {
        #[test]
        fn $test() {
            let mut stepper = $stepper;
            let measured = drift(stringify!($test), &mut stepper);
            let theory: f64 = $theory;
            assert!(
                (measured - theory).abs() <= $tolerance,
                "ln(E/E0) = {measured:e}, predicted {theory:e}"
            );
        }
    };
}

drift_test!(energy_drift_euler, Euler::new(), 99.995_000_333_308, 1e-9);
drift_test!(energy_drift_heun, Heun::new(), 2.499_999_996_875e-3, 1e-12);
drift_test!(energy_drift_rk4, Rk4::new(), -1.388_871_527_8e-8, 2e-12);
drift_test!(
    energy_drift_abm2,
    AdamsBashforthMoulton::new(AbmOrder::Two),
    -4.999_500_084_36e-3,
    5e-8
);
drift_test!(
    energy_drift_abm4,
    AdamsBashforthMoulton::new(AbmOrder::Four),
    3.228_610_438_5e-7,
    1e-11
);
drift_test!(
    energy_drift_dormand_prince,
    {
        let mut settings = autosim::runtime::integrate::DopriSettings::new(1e-3, 1e-3);
        settings.max_step = 0.01;
        DormandPrince::new(settings).unwrap()
    },
    -5.554_930_562_5e-10,
    5e-12
);
drift_test!(
    energy_drift_sdirk3,
    // The Jacobian in closed form (the model is linear): two evaluations a
    // step fewer than finite differences, so the run stays short in debug.
    Sdirk3::<models::oscillator::Oscillator, 2, _>::with_jacobian(
        SdirkSettings::default(),
        autosim::runtime::integrate::Analytic(
            |m: &models::oscillator::Oscillator, _t: f64, _x: &[f64; 2], j: &mut [[f64; 2]; 2]| {
                let p = m.parameters();
                *j = [[0.0, 1.0], [-p.k / p.m, 0.0]];
                Ok(())
            }
        )
    ),
    -5.179_190_311_6e-4,
    1e-12
);

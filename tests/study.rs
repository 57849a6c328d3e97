//! Studies (`runtime::study`): results bit for bit the same serially, on
//! 2 threads and in chunks; each case equal to a single run made by hand;
//! diverging and panicking cases recorded with their errors while the
//! others stay exact; shards in CSV and Parquet read back equal to the
//! results in memory; a resumed study equal to an uninterrupted one.

use std::path::PathBuf;

use autosim::runtime::integrate::{DormandPrince, Rk4};
use autosim::runtime::study::{
    CaseError, Cases, Distribution, Format, Keep, Method, Parallelism, Results, Simulate,
    Statistic, Study, StudyDir, StudyError,
};
use autosim::runtime::{Model, ModelError, RunSettings, Stepper, run};

autosim::model!(file = "examples/models/pendulum.sim");
use pendulum::Pendulum;

/// `x' = k x²`, `x(0) = x0`: blows up at `t = 1/(k x0)`.
#[derive(Default)]
struct Blowup {
    k: f64,
}

impl Model for Blowup {
    type Float = f64;
    type State = [f64; 1];
    type Outputs = [f64; 1];
    const NAME: &'static str = "Blowup";
    const STATE_NAMES: &'static [&'static str] = &["x"];
    const STATE_UNITS: &'static [&'static str] = &["1"];
    const PARAMETER_NAMES: &'static [&'static str] = &["k"];
    const OUTPUT_NAMES: &'static [&'static str] = &["x2"];
    fn derivatives(&mut self, _: f64, x: &[f64; 1], dx: &mut [f64; 1]) -> Result<(), ModelError> {
        dx[0] = self.k * x[0] * x[0];
        Ok(())
    }
    fn outputs(&mut self, _: f64, x: &[f64; 1], y: &mut [f64; 1]) -> Result<(), ModelError> {
        y[0] = x[0] * x[0];
        Ok(())
    }
    fn parameter_values(&self, p: &mut [f64]) {
        p[0] = self.k;
    }
    fn set_parameter_values(&mut self, p: &[f64]) {
        self.k = p[0];
    }
    fn initial_state(&self) -> [f64; 1] {
        [1.0]
    }
}

/// Pendulum cases: random mass, length and initial angle, a grid of
/// torques (an input).
fn pendulum_cases(draws: u64) -> Cases {
    let u = Distribution::uniform;
    Cases::new()
        .grid("torque", &[0.0, 0.5])
        .unwrap()
        .random(
            draws,
            2026,
            &[
                ("m", u(0.5, 2.0)),
                ("L", Distribution::normal(0.7, 0.05)),
                ("q", u(-1.0, 1.0)),
            ],
        )
        .unwrap()
}

fn pendulum_keep() -> Keep {
    Keep::new()
        .final_state()
        .at(&[0.5, 1.0], &["q", "height"])
        .statistic("height", Statistic::Max)
        .statistic("u", Statistic::Rms)
        .history(&["q"])
}

fn pendulum_study(
    method: Method,
    draws: u64,
) -> Study<Pendulum, fn() -> Pendulum, Simulate<Pendulum>> {
    let settings = RunSettings::new(0.0, 2.0, 0.01, 0.1);
    let task = Simulate::new(settings, method, pendulum_keep()).unwrap();
    Study::new(
        Pendulum::new as fn() -> Pendulum,
        pendulum_cases(draws),
        task,
    )
    .progress(false)
}

fn dopri() -> Method {
    Method::DormandPrince {
        rtol: 1e-9,
        atol: 1e-12,
    }
}

#[test]
fn serial_two_threads_and_chunks_give_the_same_bits() {
    for method in [Method::Rk4, dopri()] {
        let study = pendulum_study(method, 50);
        let n = study.cases().len();
        assert_eq!(n, 100);
        let serial = study.run_cases(0..n).unwrap();
        let study = study.parallelism(Parallelism::Threads(2));
        let threads = study.run_cases(0..n).unwrap();
        assert_eq!(serial.failures(), 0);
        assert!(
            serial == threads,
            "{method:?}: 2 threads differ from serial"
        );
        // Chunks of uneven sizes, run apart, concatenated.
        let mut chunks = study.run_cases(0..7).unwrap();
        for range in [7..40, 40..41, 41..100] {
            chunks.append(study.run_cases(range).unwrap()).unwrap();
        }
        assert!(serial == chunks, "{method:?}: chunks differ from the whole");
    }
}

#[test]
fn every_case_equals_a_single_run_made_by_hand() {
    let study = pendulum_study(dopri(), 20);
    let results = study.run_cases(0..40).unwrap();
    let times: Vec<f64> = (0..=20).map(|k| k as f64 * 0.1).collect();
    let settings = RunSettings::new(0.0, 2.0, 0.01, 0.1);
    for i in 0..40 {
        let mut row = [0.0; 4];
        study.cases().case(i, &mut row);
        let [torque, m, l, q] = row;
        assert_eq!(
            &results.case_values()[4 * i as usize..4 * i as usize + 4],
            &row
        );
        let mut model = Pendulum::new();
        model.set_parameter_values(&[m, l, 9.81]);
        model.set_input_values(&[torque]);
        let mut x = [q, 0.0];
        let mut stepper = DormandPrince::with_tolerances(1e-9, 1e-12).unwrap();
        let mut samples = vec![];
        run(
            &mut model,
            &mut stepper,
            &mut x,
            &settings,
            &mut |t: f64, x: &[f64; 2], y: &[f64; 1]| {
                samples.push((t, *x, y[0]));
            },
        )
        .unwrap();
        let field = |name: &str| results.field(name).unwrap();
        let one = |name: &str| field(name)[i as usize];
        assert_eq!(one("final:q").to_bits(), x[0].to_bits());
        assert_eq!(one("final:u").to_bits(), x[1].to_bits());
        assert_eq!(one("q@0.5").to_bits(), samples[5].1[0].to_bits());
        assert_eq!(one("height@1").to_bits(), samples[10].2.to_bits());
        let max_height = samples
            .iter()
            .map(|s| s.2)
            .fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(one("max:height").to_bits(), max_height.to_bits());
        let rms = (samples.iter().map(|s| s.1[1] * s.1[1]).sum::<f64>() / 21.0).sqrt();
        assert_eq!(one("rms:u").to_bits(), rms.to_bits());
        let history = &field("history:q")[21 * i as usize..21 * (i as usize + 1)];
        for (k, h) in history.iter().enumerate() {
            assert_eq!(samples[k].0, times[k]);
            assert_eq!(h.to_bits(), samples[k].1[0].to_bits());
        }
    }
}

/// Blowup cases over k from 0.25 to 5 (x reaches infinity at t = 1/k,
/// before the stop time 1 for k > 1), one case panicking in its setup.
fn blowup_study(method: Method) -> Study<Blowup, fn() -> Blowup, Simulate<Blowup>> {
    let ks = [0.25, 0.5, 0.75, 0.9, 1.25, 1.5, 2.0, 3.0, 4.0, 5.0];
    let cases = Cases::new()
        .grid("k", &ks)
        .unwrap()
        .grid("tag", &[0.0, 1.0])
        .unwrap();
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.25);
    let keep = Keep::new().final_state().statistic("x2", Statistic::Max);
    let task = Simulate::new(settings, method, keep).unwrap();
    Study::new(Blowup::default as fn() -> Blowup, cases, task)
        .setup(&["tag"], |values, model: &mut Blowup, _x| {
            if values[0] == 1.0 && model.k == 0.5 {
                panic!("a deliberate panic for k = 0.5");
            }
            Ok::<(), CaseError>(())
        })
        .progress(false)
        .parallelism(Parallelism::Threads(2))
}

#[test]
fn diverging_cases_are_recorded_and_the_others_are_exact() {
    for method in [Method::Rk4, dopri()] {
        let results = blowup_study(method).run_cases(0..20).unwrap();
        let ks = results.case_column("k").unwrap();
        let tags = results.case_column("tag").unwrap();
        let finals = results.field("final:x").unwrap();
        let mut failed = 0;
        for i in 0..20 {
            let (k, error) = (ks[i], &results.errors()[i]);
            if k == 0.5 && tags[i] == 1.0 {
                let e = error.as_deref().unwrap();
                assert!(
                    e.contains("panicked: a deliberate panic for k = 0.5"),
                    "{e}"
                );
            } else if k > 1.0 {
                let e = error
                    .as_deref()
                    .unwrap_or_else(|| panic!("k = {k} did not fail"));
                assert!(
                    e.contains("non-finite") || e.contains("step size underflow"),
                    "{method:?} k = {k}: {e}"
                );
            } else {
                assert!(error.is_none(), "k = {k}: {error:?}");
                // Exact: the same bits as a run by hand.
                let mut model = Blowup { k };
                let mut x = [1.0];
                let settings = RunSettings::new(0.0, 1.0, 0.01, 0.25);
                let mut stepper: Box<dyn Stepper<Blowup>> = match method {
                    Method::Rk4 => Box::new(Rk4::new()),
                    _ => Box::new(DormandPrince::with_tolerances(1e-9, 1e-12).unwrap()),
                };
                run(
                    &mut model,
                    &mut *stepper,
                    &mut x,
                    &settings,
                    &mut |_: f64, _: &[f64; 1], _: &[f64; 1]| {},
                )
                .unwrap();
                assert_eq!(finals[i].to_bits(), x[0].to_bits(), "k = {k}");
                // and the analytic solution 1/(1 - k t) at t = 1.
                assert!(
                    (x[0] - 1.0 / (1.0 - k)).abs() < 1e-3 * x[0],
                    "k = {k}: {}",
                    x[0]
                );
                continue;
            }
            failed += 1;
            assert!(finals[i].is_nan());
        }
        assert_eq!(failed, 13);
        assert_eq!(results.failures(), 13);
    }
}

#[test]
fn bad_columns_and_quantities_are_named() {
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.1);
    let keep = |k: Keep| Simulate::<Pendulum>::new(settings, Method::Rk4, k).map(|_| ());
    let e = keep(Keep::new().history(&["speed"])).unwrap_err();
    assert!(
        e.to_string()
            .contains("`speed` is not a state, output or discrete variable of model Pendulum"),
        "{e}"
    );
    let e = keep(Keep::new().at(&[0.25], &["q"])).unwrap_err();
    assert!(
        matches!(e, StudyError::NotAnOutputTime { t } if t == 0.25),
        "{e}"
    );
    let task = Simulate::new(settings, Method::Rk4, Keep::new().final_state()).unwrap();
    let cases = Cases::new().grid("mass", &[1.0]).unwrap();
    let e = Study::new(Pendulum::new, cases, task)
        .run_cases(0..1)
        .unwrap_err();
    assert!(e.to_string().contains("column `mass`"), "{e}");
    let task = Simulate::new(settings, Method::Rk4, Keep::new().final_state()).unwrap();
    let cases = Cases::new().grid("l", &[1.0]).unwrap();
    let e = Study::new(Pendulum::new, cases, task)
        .run_cases(0..1)
        .unwrap_err();
    assert!(e.to_string().contains("; did you mean `L`?"), "{e}");
    let task = Simulate::new(settings, Method::Rk4, Keep::new().final_state()).unwrap();
    let cases = Cases::new().grid("_g", &[1.0]).unwrap();
    let e = Study::new(Pendulum::new, cases, task)
        .run_cases(0..1)
        .unwrap_err();
    assert!(e.to_string().contains("; did you mean `g`?"), "{e}");
    let task = Simulate::new(settings, Method::Rk4, Keep::new()).unwrap();
    let cases = Cases::new().grid("state:m", &[1.0]).unwrap();
    let e = Study::new(Pendulum::new, cases, task)
        .run_cases(0..1)
        .unwrap_err();
    assert!(e.to_string().contains("the model has no state `m`"), "{e}");
    let e = blowup_study(Method::Rk4).run_cases(5..21).unwrap_err();
    assert!(matches!(e, StudyError::OutOfRange { len: 20, .. }), "{e}");
}

fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("study-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

#[test]
fn shards_read_back_equal_the_results_in_memory() {
    for format in [Format::Csv, Format::Parquet] {
        let study = blowup_study(dopri());
        let dir = scratch(&format!("blowup-{format:?}"));
        let summary = study.run_in(&dir, format, 6).unwrap();
        assert_eq!(
            (summary.cases, summary.ran, summary.skipped, summary.failed),
            (20, 20, 0, 13)
        );
        let on_disk = StudyDir::open(&dir).unwrap();
        assert_eq!(on_disk.description(), study.describe());
        assert_eq!(on_disk.shard_count(), 4);
        assert!(on_disk.is_complete());
        let read = on_disk.read_all().unwrap();
        assert!(read == study.run_cases(0..20).unwrap(), "{format:?}");
        // A history (a field of 21 values) too.
        let study = pendulum_study(Method::Rk4, 5);
        let dir = scratch(&format!("pendulum-{format:?}"));
        study.run_in(&dir, format, 4).unwrap();
        let read = StudyDir::open(&dir).unwrap().read_all().unwrap();
        assert!(read == study.run_cases(0..10).unwrap(), "{format:?}");
    }
}

#[test]
fn a_resumed_study_skips_written_shards_and_equals_an_uninterrupted_one() {
    let study = pendulum_study(dopri(), 25);
    let dir = scratch("resume");
    study.run_in(&dir, Format::Parquet, 8).unwrap();
    let whole = StudyDir::open(&dir).unwrap().read_all().unwrap();
    // Lose two shards and leave a half-written temporary file, as a crash
    // would; the resumed run redoes exactly those.
    let on_disk = StudyDir::open(&dir).unwrap();
    std::fs::remove_file(on_disk.shard_path(1)).unwrap();
    std::fs::remove_file(on_disk.shard_path(6)).unwrap();
    std::fs::write(dir.join(".part-000006.tmp"), b"PAR1 half").unwrap();
    let summary = study.run_in(&dir, Format::Parquet, 8).unwrap();
    assert_eq!((summary.ran, summary.skipped), (10, 40));
    assert!(!dir.join(".part-000006.tmp").exists());
    assert!(StudyDir::open(&dir).unwrap().read_all().unwrap() == whole);
    // A different study in the same folder is refused.
    let other = pendulum_study(Method::Rk4, 25);
    let e = other.run_in(&dir, Format::Parquet, 8).unwrap_err();
    assert!(e.to_string().contains("holds a different study"), "{e}");
    let e = study.run_in(&dir, Format::Csv, 8).unwrap_err();
    assert!(e.to_string().contains("format"), "{e}");
}

/// The pendulum again under the same name, with Mars's gravity: another
/// build of the model, as after editing its file or updating autosim.
mod rebuilt {
    autosim::model! {
        model Pendulum;
        settings { linearize: true }
        parameters { m = 1.3 [kg], L = 0.7 [m], g = 3.71 [m/s^2] }
        input torque [N m];
        body Rod { rotate: 1, q: [q], u: [u], mass: m, cm: [0, 0, -L], inertia: 0 }
        moment drive { on: Rod, reaction: N, about: n1, magnitude: torque }
        gravity = -g*n3;
        output height [m] = dot(pos(Rod.cm), n3);
    }
}

#[test]
fn a_folder_refuses_a_study_of_another_build_of_its_model() {
    let dir = scratch("rebuilt");
    pendulum_study(Method::Rk4, 3)
        .run_in(&dir, Format::Csv, 4)
        .unwrap();
    let settings = RunSettings::new(0.0, 2.0, 0.01, 0.1);
    let task = Simulate::new(settings, Method::Rk4, pendulum_keep()).unwrap();
    let rebuilt =
        Study::new(rebuilt::pendulum::Pendulum::new, pendulum_cases(3), task).progress(false);
    assert_eq!(rebuilt.layout(), pendulum_study(Method::Rk4, 3).layout());
    let e = rebuilt.run_in(&dir, Format::Csv, 4).unwrap_err();
    assert!(
        matches!(&e, StudyError::Mismatch { what, .. } if what.contains("generated code")),
        "{e}"
    );
    assert_ne!(pendulum::FINGERPRINT, rebuilt::pendulum::FINGERPRINT);
    assert_eq!(<Pendulum as Model>::FINGERPRINT, pendulum::FINGERPRINT);
}

/// The models a study makes are part of it: the same study of a pendulum
/// made with another gravity is refused, and so is one made with another
/// torque (an input the cases do not set).
#[test]
fn a_folder_refuses_a_study_of_models_made_otherwise() {
    let dir = scratch("made");
    let study = pendulum_study(Method::Rk4, 3);
    study.run_in(&dir, Format::Csv, 4).unwrap();
    let settings = RunSettings::new(0.0, 2.0, 0.01, 0.1);
    let moon = || {
        let mut m = Pendulum::new();
        m.set_parameter_values(&[1.3, 0.7, 1.62]);
        m
    };
    let task = Simulate::new(settings, Method::Rk4, pendulum_keep()).unwrap();
    let e = Study::new(moon, pendulum_cases(3), task)
        .progress(false)
        .run_in(&dir, Format::Csv, 4)
        .unwrap_err();
    assert!(
        e.to_string().contains("the model as made: its parameters"),
        "{e}"
    );
    let pushed = || {
        let mut m = Pendulum::new();
        m.set_input_values(&[0.25]);
        m
    };
    let cases = || Cases::new().grid("q", &[0.1, 0.2, 0.3]).unwrap();
    let task = || Simulate::new(settings, Method::Rk4, Keep::new().final_state()).unwrap();
    let reference = Study::new(Pendulum::new, cases(), task()).progress(false);
    let dir = scratch("made-inputs");
    reference.run_in(&dir, Format::Csv, 4).unwrap();
    let e = Study::new(pushed, cases(), task())
        .progress(false)
        .run_in(&dir, Format::Csv, 4)
        .unwrap_err();
    assert!(e.to_string().contains("inputs"), "{e}");
    assert_eq!(reference.run_in(&dir, Format::Csv, 4).unwrap().skipped, 3);
}

/// A study's results compared with `Results::eq`, which compares bits.
#[test]
fn results_compare_bits_so_nan_equals_nan() {
    let a = blowup_study(Method::Rk4).run_cases(18..20).unwrap();
    assert!(a.failures() > 0 && a == a.clone());
    let b: Results = blowup_study(Method::Rk4).run_cases(16..18).unwrap();
    assert!(a != b);
}

mod bike {
    autosim::model!(file = "examples/models/bicycle.sim", linearize = true);
}
use bike::bicycle::Bicycle;

/// The modes task on the bicycle: each case's eigenvalues are those of
/// `LinearSystem::of` by hand, bit for bit, and at the benchmark's
/// parameters the largest real part changes sign between the grid speeds
/// that bracket the published weave and capsize speeds.
#[test]
fn modes_of_the_bicycle_bracket_the_published_weave_and_capsize_speeds() {
    use autosim::runtime::analysis::LinearSystem;
    use autosim::runtime::study::Modes;
    const ROLL_STEER: [&str; 4] = ["phi", "delta", "u_phi", "u_delta"];
    let wheel = Bicycle::STATE_NAMES
        .iter()
        .position(|n| *n == "u_thetaR")
        .unwrap();
    // Published: weave 4.29238253634111, capsize 6.02426201538837 m/s.
    let speeds = [4.2, 4.29, 4.295, 6.02, 6.03, 7.0];
    let cases = Cases::new().grid("v", &speeds).unwrap();
    let modes = Modes::<Bicycle>::new(Some(&ROLL_STEER), None).unwrap();
    let study = Study::new(Bicycle::new, cases, modes)
        .setup(&["v"], move |v, _, x| {
            x[wheel] = v[0] / 0.3;
            Ok(())
        })
        .progress(false);
    let results = study.run_cases(0..6).unwrap();
    let (re, im) = (results.field("re").unwrap(), results.field("im").unwrap());
    let mut max_re = vec![];
    for (k, v) in speeds.iter().enumerate() {
        let mut x = [0.0; 11];
        x[wheel] = v / 0.3;
        let by_hand = LinearSystem::of(&mut Bicycle::new(), 0.0, &x)
            .unwrap()
            .restricted(&ROLL_STEER)
            .unwrap();
        for (j, l) in by_hand.eigenvalues().iter().enumerate() {
            assert_eq!(
                (re[4 * k + j].to_bits(), im[4 * k + j].to_bits()),
                (l.re.to_bits(), l.im.to_bits())
            );
        }
        max_re.push(
            re[4 * k..4 * k + 4]
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max),
        );
    }
    let stable: Vec<bool> = max_re.iter().map(|r| *r < 0.0).collect();
    assert_eq!(
        stable,
        [false, false, true, true, false, false],
        "max Re λ: {max_re:?}"
    );
}

//! Parameter files, CSV output and SVG plots.
#![cfg(all(feature = "csv", feature = "plot"))]

mod common;

use std::path::PathBuf;

use autosim_runtime::integrate::{Rk4, Sdirk3, SdirkSettings};
use autosim_runtime::io::{
    CsvWriter, OutputError, ParameterError, Recording, load_parameters, parameters_to_string,
    read_parameters, save_parameters,
};
use autosim_runtime::{IntegrationError, Model, RunError, RunSettings, run};
use common::{Oscillator, StiffLinear, VanDerPol};

/// A fresh path in Cargo's per-test scratch directory.
fn scratch(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("autosim-runtime-io");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    let _ = std::fs::remove_file(&path);
    path
}

#[test]
fn parameter_file_lists_every_parameter_with_unit_and_value() {
    let model = VanDerPol {
        mu: 1000.0,
        stiffness: 0.1,
    };
    let text = parameters_to_string(&model);
    assert_eq!(
        text,
        "# Parameters of model VanDerPol.\n\
         # Units are in the comments; edit values only.\n\
         mu = 1000.0 # [1]\n\
         stiffness = 0.1 # [1/s2]\n"
    );
}

#[test]
fn parameter_file_round_trips_exactly() {
    let path = scratch("vdp.toml");
    let original = VanDerPol {
        mu: 1.0 / 3.0,
        stiffness: 6.02214076e23,
    };
    save_parameters(&original, &path).unwrap();
    let mut read_back = VanDerPol {
        mu: 0.0,
        stiffness: 0.0,
    };
    load_parameters(&mut read_back, &path).unwrap();
    assert_eq!(read_back.mu.to_bits(), original.mu.to_bits());
    assert_eq!(read_back.stiffness.to_bits(), original.stiffness.to_bits());
}

#[test]
fn partial_files_and_integers_are_accepted() {
    let mut model = Oscillator::default();
    read_parameters(&mut model, "mass = 5 # [kg]\n").unwrap();
    assert_eq!((model.omega, model.mass), (1.0, 5.0));
}

#[test]
fn a_misspelled_key_names_the_key_and_the_closest_parameter() {
    let mut model = VanDerPol::with_mu(2.0);
    let err = read_parameters(&mut model, "mu = 3.0\nstifness = 4.0\n").unwrap_err();
    assert!(
        matches!(&err, ParameterError::UnknownParameter { key, suggestion: Some("stiffness"), .. } if key == "stifness"),
        "{err:?}"
    );
    assert_eq!(
        err.to_string(),
        "`stifness` is not a parameter of model VanDerPol; did you mean `stiffness`?"
    );
    // Nothing was applied.
    assert_eq!((model.mu, model.stiffness), (2.0, 1.0));

    let err = read_parameters(&mut model, "gravity = 9.81").unwrap_err();
    assert_eq!(
        err.to_string(),
        "`gravity` is not a parameter of model VanDerPol; its parameters are: mu, stiffness"
    );
}

#[test]
fn wrong_types_and_bad_toml_are_reported() {
    let mut model = Oscillator::default();
    let err = read_parameters(&mut model, "omega = \"fast\"").unwrap_err();
    assert_eq!(
        err.to_string(),
        "parameter `omega` must be a number, but the file gives a string"
    );
    let err = read_parameters(&mut model, "omega = = 1").unwrap_err();
    assert!(matches!(err, ParameterError::Syntax { .. }), "{err:?}");
    assert!(err.to_string().contains("line 1"), "{err}");
    let err = load_parameters(&mut model, scratch("does-not-exist.toml")).unwrap_err();
    assert!(matches!(err, ParameterError::Io { .. }));
}

#[test]
fn csv_has_a_unit_header_and_one_row_per_output_time() {
    let mut model = Oscillator::default();
    let mut x = model.initial_state();
    let mut csv = CsvWriter::<Oscillator, _>::new(Vec::new()).unwrap();
    let settings = RunSettings::new(0.0, 0.5, 0.01, 0.25);
    run(&mut model, &mut Rk4::new(), &mut x, &settings, &mut csv).unwrap();
    assert_eq!(csv.rows(), 3);
    let text = String::from_utf8(csv.into_inner().unwrap()).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "time [s],x [m],v [m/s],energy [J]");
    assert_eq!(lines.len(), 4);
    assert_eq!(lines[1], "0.0,1.0,0.0,1.0");
    for (line, t) in lines[1..].iter().zip([0.0, 0.25, 0.5]) {
        let values: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        assert_eq!(values[0], t);
        assert!((values[1] - f64::cos(t)).abs() < 1e-9, "{line}");
        assert!((values[2] + f64::sin(t)).abs() < 1e-9, "{line}");
    }
}

#[test]
fn csv_rows_up_to_a_failure_are_on_disk() {
    let path = scratch("stiff-rk4.csv");
    let mut model = StiffLinear::default();
    let mut x = model.initial_state();
    let mut csv = CsvWriter::<StiffLinear, _>::create(&path).unwrap();
    let settings = RunSettings::new(0.0, 1.0, 0.01, 0.02);
    let err = run(&mut model, &mut Rk4::new(), &mut x, &settings, &mut csv).unwrap_err();
    let RunError::Integration(IntegrationError::NonFinite { t, .. }) = err else {
        panic!("expected a non-finite state, got {err:?}");
    };
    // Read the file while the writer is still alive: rows were flushed.
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "time [s],y1 [1],y2 [1],y3 [1]");
    assert_eq!(lines.len() as u64, 1 + csv.rows());
    let last_t: f64 = lines
        .last()
        .unwrap()
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        last_t < t && t - last_t <= 0.02 + 1e-12,
        "last row {last_t}, failure {t}"
    );
}

#[test]
fn svg_plot_has_labelled_axes_and_a_legend() {
    let mut model = VanDerPol::with_mu(1.0);
    let mut x = model.initial_state();
    let mut rec = Recording::<VanDerPol>::new();
    let settings = RunSettings::new(0.0, 10.0, 0.01, 0.05);
    run(
        &mut model,
        &mut Sdirk3::new(SdirkSettings::default()),
        &mut x,
        &settings,
        &mut rec,
    )
    .unwrap();
    assert_eq!(rec.time().len(), 201);
    assert_eq!(rec.column("x_squared").unwrap().values.len(), 201);

    let path = scratch("vdp.svg");
    rec.plot_svg(&path, &["x", "v"]).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg"), "{}", &svg[..100]);
    let texts = svg_texts(&svg);
    // Title, x-axis label, and for each unit its own panel: the y-axis
    // label and the legend entry of x [1] and of v [1/s] (different units
    // never share an axis).
    for (text, times) in [
        ("VanDerPol", 1),
        ("time [s]", 2),
        ("x [1]", 2),
        ("v [1/s]", 2),
    ] {
        let found = texts.iter().filter(|t| *t == text).count();
        assert_eq!(found, times, "{text:?} in {texts:?}");
    }
    assert!(!texts.iter().any(|t| t.contains(", ")), "{texts:?}");
    assert!(svg.matches("<polyline").count() >= 2);

    let err = rec
        .plot_svg(scratch("bad.svg"), &["velocity", "vv"])
        .unwrap_err();
    assert!(matches!(err, OutputError::UnknownColumn { .. }));
    assert_eq!(err.to_string(), "no column `velocity` in the recording");
    let err = rec.plot_svg(scratch("bad.svg"), &["x_sqared"]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "no column `x_sqared` in the recording; did you mean `x_squared`?"
    );
}

/// The text content of every `<text>` element, trimmed.
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|rest| {
            let body = &rest[rest.find('>')? + 1..];
            Some(body[..body.find("</text>")?].trim().to_string())
        })
        .collect()
}

#[test]
fn columns_without_a_unit_have_no_brackets() {
    use autosim_runtime::io::{Series, svg_plot};
    let time = [0.0, 1.0];
    let series = [
        Series {
            name: "h",
            unit: "",
            values: &[0.0, 1.0],
        },
        Series {
            name: "g",
            unit: "",
            values: &[1.0, 0.0],
        },
    ];
    let svg = svg_plot("M", &time, &series).unwrap();
    let texts = svg_texts(&svg);
    assert!(texts.iter().any(|t| t == "h, g"), "{texts:?}");
    assert!(!texts.iter().any(|t| t.contains("[]")), "{texts:?}");
}

//! `autosim-fmu MODEL.sim [OUT_DIR] [--crate DIR] [--stop T] [--step H]
//! [--opt-level N]`: builds `<Model>.fmu` (FMI 2.0, Model Exchange and
//! Co-Simulation) from a model file into `OUT_DIR` (default `target/fmu`).
//! With `--crate`, the library is the user's crate (a model with user
//! code); `--opt-level` compiles the model's code at that level (0 to 3)
//! instead of 3.

use autosim_fmu::{Experiment, Fmu};
use std::process::ExitCode;

const USAGE: &str =
    "usage: autosim-fmu MODEL.sim [OUT_DIR] [--crate DIR] [--stop T] [--step H] [--opt-level N]";

fn main() -> ExitCode {
    match run(std::env::args().skip(1).collect()) {
        Ok(path) => {
            println!("{path}");
            ExitCode::SUCCESS
        }
        Err(message) => {
            eprintln!("{message}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: Vec<String>) -> Result<String, String> {
    let mut positional = Vec::new();
    let mut experiment = Experiment::default();
    let mut user_crate = None;
    let mut opt_level = None;
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value\n{USAGE}"));
        let number = |text: String, name: &str| {
            text.parse::<f64>()
                .map_err(|_| format!("{name}: {text:?} is not a number"))
        };
        match a.as_str() {
            "--crate" => user_crate = Some(value("--crate")?),
            "--stop" => experiment.stop = number(value("--stop")?, "--stop")?,
            "--step" => experiment.step = number(value("--step")?, "--step")?,
            "--opt-level" => {
                let text = value("--opt-level")?;
                let level = text.parse::<u8>().ok().filter(|l| *l <= 3);
                opt_level =
                    Some(level.ok_or(format!("--opt-level: {text:?} is not 0, 1, 2 or 3"))?);
            }
            "-h" | "--help" => return Err(USAGE.to_string()),
            _ => positional.push(a),
        }
    }
    let (model, out) = match positional.as_slice() {
        [m] => (m.clone(), "target/fmu".to_string()),
        [m, o] => (m.clone(), o.clone()),
        _ => return Err(USAGE.to_string()),
    };
    let mut fmu = Fmu::new(model).out_dir(out).experiment(experiment);
    if let Some(dir) = user_crate {
        fmu = fmu.user_crate(dir);
    }
    if let Some(level) = opt_level {
        fmu = fmu.opt_level(level);
    }
    let built = fmu.build().map_err(|e| e.to_string())?;
    Ok(built.fmu.display().to_string())
}

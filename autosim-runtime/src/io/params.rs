//! Parameter files in TOML: every parameter with its current value and its
//! unit as a comment.
//!
//! ```toml
//! # Parameters of model Satellite.
//! KB = 2000.0 # [N m/rad]
//! DB = 10.0 # [N m s/rad]
//! ```

use std::prelude::rust_2024::*;
use std::{format, vec};

use std::fmt::Write as _;
use std::path::Path;

use super::error::ParameterError;
use super::names::closest;
use crate::{Float, Model};

/// The parameter file of `model`'s current parameter values, as text.
///
/// Use it to show or store a parameter set; [`save_parameters`] writes it
/// to a file. Values are written so they read back exactly.
pub fn parameters_to_string<M: Model>(model: &M) -> String {
    let names = M::PARAMETER_NAMES;
    let mut values = vec![M::Float::ZERO; names.len()];
    model.parameter_values(&mut values);
    let mut out = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(out, "# Parameters of model {}.", M::NAME);
    let _ = writeln!(out, "# Units are in the comments; edit values only.");
    for (i, (name, value)) in names.iter().zip(&values).enumerate() {
        let unit = M::PARAMETER_UNITS.get(i).copied().unwrap_or("");
        let (key, value) = (toml_key(name), toml_float(*value));
        let _ = match unit {
            "" => writeln!(out, "{key} = {value}"),
            unit => writeln!(out, "{key} = {value} # [{unit}]"),
        };
    }
    out
}

/// Writes `model`'s parameter file to `path` (see [`parameters_to_string`]).
///
/// # Errors
/// [`ParameterError::Io`] if the file cannot be written.
pub fn save_parameters<M: Model>(model: &M, path: impl AsRef<Path>) -> Result<(), ParameterError> {
    let path = path.as_ref();
    std::fs::write(path, parameters_to_string(model)).map_err(|source| ParameterError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Sets `model`'s parameters from the TOML text of a parameter file.
///
/// Keys not in the file keep their current values, so a file may list only
/// what it changes. Integers are accepted as values. Nothing is changed if
/// the file has an error.
///
/// # Errors
/// [`ParameterError::Syntax`] for invalid TOML,
/// [`ParameterError::UnknownParameter`] for a key the model does not have
/// (naming the closest parameter), [`ParameterError::NotANumber`] for a
/// value that is not a number. The first problem in key order is reported.
pub fn read_parameters<M: Model>(model: &mut M, text: &str) -> Result<(), ParameterError> {
    let table: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| ParameterError::Syntax {
            message: e.to_string().trim_end().to_string(),
        })?;
    let names = M::PARAMETER_NAMES;
    let mut values = vec![M::Float::ZERO; names.len()];
    model.parameter_values(&mut values);
    for (key, value) in &table {
        let Some(index) = names.iter().position(|n| n == key) else {
            return Err(ParameterError::UnknownParameter {
                model: M::NAME,
                key: key.clone(),
                suggestion: closest(key, names),
                known: names,
            });
        };
        let number = match value {
            toml::Value::Float(v) => *v,
            // Parameter values fit in f64 far beyond any physical use.
            toml::Value::Integer(v) => *v as f64,
            other => {
                return Err(ParameterError::NotANumber {
                    key: key.clone(),
                    found: other.type_str(),
                });
            }
        };
        if let Some(slot) = values.get_mut(index) {
            *slot = M::Float::from_f64(number);
        }
    }
    model.set_parameter_values(&values);
    Ok(())
}

/// Reads a parameter file from `path` into `model` (see [`read_parameters`]).
///
/// # Errors
/// [`ParameterError::Io`] if the file cannot be read, otherwise as
/// [`read_parameters`].
pub fn load_parameters<M: Model>(
    model: &mut M,
    path: impl AsRef<Path>,
) -> Result<(), ParameterError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| ParameterError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_parameters(model, &text)
}

/// A TOML float that reads back as the same value.
fn toml_float<F: Float>(v: F) -> String {
    if v.to_f64().is_nan() {
        return "nan".to_string();
    }
    // `Debug` of f32/f64 is the shortest text that reads back exactly, and
    // always a valid TOML float ("1.0", "1e-7", "inf", "-inf").
    let s = format!("{v:?}");
    if s.contains(['.', 'e', 'E', 'n']) {
        s
    } else {
        format!("{s}.0")
    }
}

/// A bare TOML key when the name allows it, a quoted one otherwise.
fn toml_key(name: &str) -> String {
    let bare = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        name.to_string()
    } else {
        toml::Value::String(name.to_string()).to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_are_valid_toml_and_exact() {
        for v in [
            0.0,
            -0.0,
            1.0,
            0.1,
            1e-7,
            2.5e300,
            -3.25,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
        ] {
            let text = format!("x = {}", toml_float(v));
            let table: toml::Table = text.parse().unwrap();
            assert_eq!(
                table["x"].as_float().unwrap().to_bits(),
                v.to_bits(),
                "{text}"
            );
        }
        let table: toml::Table = format!("x = {}", toml_float(f64::NAN)).parse().unwrap();
        assert!(table["x"].as_float().unwrap().is_nan());
        assert_eq!(toml_float(0.1f32), "0.1");
    }

    #[test]
    fn odd_names_are_quoted() {
        assert_eq!(toml_key("k_b-2"), "k_b-2");
        assert_eq!(toml_key("a b"), "\"a b\"");
        assert_eq!(toml_key(""), "\"\"");
    }
}

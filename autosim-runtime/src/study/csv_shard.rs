//! CSV shards: a header, then a row per case (see [`Format::Csv`](super::Format::Csv)).

use std::path::Path;
use std::string::{String, ToString};
use std::vec::Vec;
use std::{format, vec};

use super::store::csv_header;
use super::{Layout, Results, StudyError};

fn csv_error(path: &Path) -> impl Fn(csv::Error) -> StudyError + '_ {
    move |e| StudyError::Corrupt(format!("{}: {e}", path.display()))
}

/// Writes `results` to `path`.
pub(super) fn write(path: &Path, results: &Results) -> Result<(), StudyError> {
    let err = csv_error(path);
    let mut w = csv::Writer::from_path(path).map_err(&err)?;
    let layout = results.layout();
    w.write_record(csv_header(layout)).map_err(&err)?;
    let (nc, width) = (layout.case_columns.len(), layout.width());
    let mut record: Vec<String> = Vec::with_capacity(nc + width + 3);
    for (i, error) in results.errors().iter().enumerate() {
        record.clear();
        record.push((results.first_case() + i as u64).to_string());
        let row = |v: &[f64], w: usize| {
            v[i * w..(i + 1) * w]
                .iter()
                .map(f64::to_string)
                .collect::<Vec<_>>()
        };
        record.extend(row(results.case_values(), nc));
        record.extend(row(results.values(), width));
        record.push(if error.is_none() { "true" } else { "false" }.to_string());
        record.push(error.clone().unwrap_or_default());
        w.write_record(&record).map_err(&err)?;
    }
    w.flush().map_err(StudyError::io(path))
}

/// Reads a shard written by [`write`] whose first case is `first_case`.
pub(super) fn read(path: &Path, layout: &Layout, first_case: u64) -> Result<Results, StudyError> {
    let err = csv_error(path);
    let bad = |what: String| StudyError::Corrupt(format!("{}: {what}", path.display()));
    let mut r = csv::Reader::from_path(path).map_err(&err)?;
    let expected = csv_header(layout);
    let header: Vec<String> = r
        .headers()
        .map_err(&err)?
        .iter()
        .map(str::to_string)
        .collect();
    if header != expected {
        return Err(bad(
            "the header does not match the study's columns".to_string()
        ));
    }
    let (nc, width) = (layout.case_columns.len(), layout.width());
    let (mut case_values, mut values, mut errors) = (vec![], vec![], vec![]);
    for (i, record) in r.records().enumerate() {
        let record = record.map_err(&err)?;
        let number = |k: usize| -> Result<f64, StudyError> {
            record[k]
                .parse()
                .map_err(|_| bad(format!("`{}` is not a number", &record[k])))
        };
        if record[0] != (first_case + i as u64).to_string() {
            return Err(bad(format!(
                "row {i} is case {}, not {}",
                &record[0],
                first_case + i as u64
            )));
        }
        for k in 0..nc {
            case_values.push(number(1 + k)?);
        }
        for k in 0..width {
            values.push(number(1 + nc + k)?);
        }
        errors.push(match &record[1 + nc + width] {
            "true" => None,
            _ => Some(record[2 + nc + width].to_string()),
        });
    }
    Results::from_parts(layout.clone(), first_case, case_values, values, errors)
}

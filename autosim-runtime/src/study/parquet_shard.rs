//! Parquet shards (feature `parquet`; see [`Format::Parquet`](super::Format::Parquet)).

use std::fs::File;
use std::path::Path;
use std::string::{String, ToString};
use std::sync::Arc;
use std::vec::Vec;
use std::{format, vec};

use arrow_array::cast::AsArray;
use arrow_array::types::{Float64Type, UInt64Type};
use arrow_array::{
    Array, ArrayRef, BooleanArray, FixedSizeListArray, Float64Array, RecordBatch, StringArray,
    UInt64Array,
};
use arrow_schema::{DataType, Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
use parquet::basic::Compression;
use parquet::file::properties::WriterProperties;

use super::{Layout, Results, StudyError};

fn parquet_error(path: &Path) -> impl Fn(parquet::errors::ParquetError) -> StudyError + '_ {
    move |e| StudyError::Corrupt(format!("{}: {e}", path.display()))
}

fn arrow_error(path: &Path) -> impl Fn(arrow_schema::ArrowError) -> StudyError + '_ {
    move |e| StudyError::Corrupt(format!("{}: {e}", path.display()))
}

fn item() -> Arc<Field> {
    Arc::new(Field::new("item", DataType::Float64, false))
}

/// The Arrow schema of a study's shards.
fn schema(layout: &Layout) -> Schema {
    let mut fields = vec![Field::new("case", DataType::UInt64, false)];
    fields.extend(
        layout
            .case_columns
            .iter()
            .map(|c| Field::new(c, DataType::Float64, false)),
    );
    for f in &layout.fields {
        let data_type = if f.len == 1 {
            DataType::Float64
        } else {
            DataType::FixedSizeList(item(), f.len as i32)
        };
        fields.push(Field::new(&f.name, data_type, false));
    }
    fields.push(Field::new("ok", DataType::Boolean, false));
    fields.push(Field::new("error", DataType::Utf8, true));
    Schema::new(fields)
}

/// Column `k` of a row-major table of width `width`.
fn column(values: &[f64], width: usize, start: usize, len: usize) -> Vec<f64> {
    values
        .chunks(width.max(1))
        .flat_map(|row| &row[start..start + len])
        .copied()
        .collect()
}

/// Writes `results` to `path`.
pub(super) fn write(path: &Path, results: &Results) -> Result<(), StudyError> {
    let layout = results.layout();
    let schema = Arc::new(schema(layout));
    let n = results.len();
    let first = results.first_case();
    let mut columns: Vec<ArrayRef> = vec![Arc::new(UInt64Array::from_iter_values(
        first..first + n as u64,
    ))];
    let nc = layout.case_columns.len();
    for k in 0..nc {
        columns.push(Arc::new(Float64Array::from(column(
            results.case_values(),
            nc,
            k,
            1,
        ))));
    }
    let width = layout.width();
    let mut start = 0;
    for f in &layout.fields {
        let values = Float64Array::from(column(results.values(), width, start, f.len));
        start += f.len;
        columns.push(if f.len == 1 {
            Arc::new(values)
        } else {
            Arc::new(
                FixedSizeListArray::try_new(item(), f.len as i32, Arc::new(values), None)
                    .map_err(arrow_error(path))?,
            )
        });
    }
    let errors = results.errors();
    columns.push(Arc::new(BooleanArray::from_iter(
        errors.iter().map(|e| Some(e.is_none())),
    )));
    columns.push(Arc::new(StringArray::from_iter(
        errors.iter().map(Option::as_deref),
    )));
    let batch = RecordBatch::try_new(schema.clone(), columns).map_err(arrow_error(path))?;
    let file = File::create(path).map_err(StudyError::io(path))?;
    let properties = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .build();
    let mut writer =
        ArrowWriter::try_new(file, schema, Some(properties)).map_err(parquet_error(path))?;
    writer.write(&batch).map_err(parquet_error(path))?;
    writer.close().map_err(parquet_error(path))?;
    Ok(())
}

/// Reads a shard written by [`write`] whose first case is `first_case`.
pub(super) fn read(path: &Path, layout: &Layout, first_case: u64) -> Result<Results, StudyError> {
    let bad = |what: String| StudyError::Corrupt(format!("{}: {what}", path.display()));
    let file = File::open(path).map_err(StudyError::io(path))?;
    let reader = ParquetRecordBatchReaderBuilder::try_new(file)
        .map_err(parquet_error(path))?
        .build()
        .map_err(parquet_error(path))?;
    let expected = schema(layout);
    let (nc, width) = (layout.case_columns.len(), layout.width());
    let (mut case_values, mut values, mut errors) = (vec![], vec![], vec![]);
    let mut next_case = first_case;
    for batch in reader {
        let batch = batch.map_err(arrow_error(path))?;
        if batch.schema().fields() != expected.fields() {
            return Err(bad("the columns do not match the study's".to_string()));
        }
        let n = batch.num_rows();
        let cases = batch.column(0).as_primitive::<UInt64Type>();
        if cases
            .values()
            .iter()
            .zip(next_case..)
            .any(|(c, expected)| *c != expected)
        {
            return Err(bad(format!(
                "the cases do not run on from case {next_case}"
            )));
        }
        next_case += n as u64;
        let floats =
            |k: usize| -> &[f64] { batch.column(k).as_primitive::<Float64Type>().values() };
        let mut rows_of_cases = vec![0.0; n * nc];
        for k in 0..nc {
            for (row, v) in floats(1 + k).iter().enumerate() {
                rows_of_cases[row * nc + k] = *v;
            }
        }
        let mut rows = vec![0.0; n * width];
        let mut start = 0;
        for (j, f) in layout.fields.iter().enumerate() {
            let array = batch.column(1 + nc + j);
            let flat: &[f64] = if f.len == 1 {
                array.as_primitive::<Float64Type>().values()
            } else {
                let list = array.as_fixed_size_list();
                let inner = list.values().as_primitive::<Float64Type>().values();
                &inner[list.offset() * f.len..]
            };
            for row in 0..n {
                rows[row * width + start..row * width + start + f.len]
                    .copy_from_slice(&flat[row * f.len..(row + 1) * f.len]);
            }
            start += f.len;
        }
        let ok = batch.column(1 + nc + layout.fields.len()).as_boolean();
        let text = batch
            .column(2 + nc + layout.fields.len())
            .as_string::<i32>();
        for row in 0..n {
            errors.push(if ok.value(row) {
                None
            } else {
                Some(text.value(row).to_string())
            });
        }
        case_values.extend(rows_of_cases);
        values.extend(rows);
    }
    Results::from_parts(layout.clone(), first_case, case_values, values, errors)
}

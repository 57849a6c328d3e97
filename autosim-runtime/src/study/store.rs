//! A study in a folder: a manifest (`study.toml`) and the results in
//! shards of consecutive cases (`part-000000.csv`, ... or `.parquet`),
//! each written whole to a temporary file and renamed, so a crash loses
//! at most the shard being computed and a resumed study skips the shards
//! already there.

use core::ops::Range;
use std::fs;
use std::path::{Path, PathBuf};
use std::string::{String, ToString};
use std::time::{Duration, Instant};
use std::vec::Vec;
use std::{format, vec};

use super::execute::Runner;
use super::{Field, Layout, Results, Study, StudyError, Task};
use crate::Model;

/// The file format of a study's shards.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// CSV with a header: `case`, the table's columns, the fields (a field
    /// of `n` values as `name[0]` … `name[n-1]`), `ok`, `error`. Numbers
    /// are written in Rust's shortest round-trip form, so every finite
    /// value reads back with the same bits.
    Csv,
    /// Parquet (feature `parquet`): `case` (UInt64), a Float64 column per
    /// table column and per field of one value, a FixedSizeList of
    /// Float64 per longer field, `ok` (Boolean), `error` (Utf8, null when
    /// ok); Snappy compression.
    Parquet,
}

impl Format {
    fn extension(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::Parquet => "parquet",
        }
    }

    fn parse(name: &str) -> Result<Format, StudyError> {
        match name {
            "csv" => Ok(Format::Csv),
            "parquet" => Ok(Format::Parquet),
            other => Err(StudyError::Corrupt(format!(
                "unknown shard format `{other}`"
            ))),
        }
    }

    fn write(self, path: &Path, results: &Results) -> Result<(), StudyError> {
        match self {
            Format::Csv => super::csv_shard::write(path, results),
            #[cfg(feature = "parquet")]
            Format::Parquet => super::parquet_shard::write(path, results),
            #[cfg(not(feature = "parquet"))]
            Format::Parquet => Err(no_parquet()),
        }
    }

    fn read(self, path: &Path, layout: &Layout, first_case: u64) -> Result<Results, StudyError> {
        match self {
            Format::Csv => super::csv_shard::read(path, layout, first_case),
            #[cfg(feature = "parquet")]
            Format::Parquet => super::parquet_shard::read(path, layout, first_case),
            #[cfg(not(feature = "parquet"))]
            Format::Parquet => Err(no_parquet()),
        }
    }
}

#[cfg(not(feature = "parquet"))]
fn no_parquet() -> StudyError {
    StudyError::Unsupported("Parquet shards need the runtime's feature `parquet`".to_string())
}

/// What [`Study::run_in`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct StudySummary {
    /// Cases in the study.
    pub cases: u64,
    /// Cases run by this call.
    pub ran: u64,
    /// Cases skipped because their shard was already written (a resumed
    /// study).
    pub skipped: u64,
    /// Cases run by this call that failed.
    pub failed: u64,
    /// Wall-clock time of this call.
    pub elapsed: Duration,
}

impl StudySummary {
    /// Cases run per second of wall-clock time.
    pub fn cases_per_second(&self) -> f64 {
        self.ran as f64 / self.elapsed.as_secs_f64().max(1e-9)
    }
}

const MANIFEST: &str = "study.toml";

/// A study's folder: its manifest and its shards.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyDir {
    path: PathBuf,
    layout: Layout,
    cases: u64,
    shard_size: u64,
    format: Format,
    description: String,
}

impl StudyDir {
    fn manifest(&self) -> String {
        let mut t = toml::Table::new();
        let strings =
            |v: &[String]| toml::Value::Array(v.iter().map(|s| s.clone().into()).collect());
        t.insert("format".into(), self.format.extension().into());
        t.insert("cases".into(), (self.cases as i64).into());
        t.insert("shard_size".into(), (self.shard_size as i64).into());
        t.insert("case_columns".into(), strings(&self.layout.case_columns));
        let names: Vec<String> = self.layout.fields.iter().map(|f| f.name.clone()).collect();
        t.insert("field_names".into(), strings(&names));
        let lens = self
            .layout
            .fields
            .iter()
            .map(|f| (f.len as i64).into())
            .collect();
        t.insert("field_lengths".into(), toml::Value::Array(lens));
        t.insert("description".into(), self.description.clone().into());
        t.to_string()
    }

    fn parse(path: &Path, text: &str) -> Result<StudyDir, StudyError> {
        let bad =
            |what: &str| StudyError::Corrupt(format!("{}: {what}", path.join(MANIFEST).display()));
        let t: toml::Table = text.parse().map_err(|e| bad(&format!("{e}")))?;
        let int = |k: &str| {
            t.get(k)
                .and_then(toml::Value::as_integer)
                .ok_or_else(|| bad(k))
        };
        let array = |k: &str| {
            t.get(k)
                .and_then(toml::Value::as_array)
                .ok_or_else(|| bad(k))
        };
        let strings = |k: &str| -> Result<Vec<String>, StudyError> {
            array(k)?
                .iter()
                .map(|v| v.as_str().map(str::to_string).ok_or_else(|| bad(k)))
                .collect()
        };
        let lens: Vec<usize> = array("field_lengths")?
            .iter()
            .map(|v| {
                v.as_integer()
                    .and_then(|n| usize::try_from(n).ok())
                    .ok_or_else(|| bad("field_lengths"))
            })
            .collect::<Result<_, _>>()?;
        let names = strings("field_names")?;
        if names.len() != lens.len() {
            return Err(bad("field_names and field_lengths differ in length"));
        }
        let fields = names
            .into_iter()
            .zip(lens)
            .map(|(name, len)| Field { name, len })
            .collect();
        let format = t
            .get("format")
            .and_then(toml::Value::as_str)
            .ok_or_else(|| bad("format"))?;
        let shard_size = u64::try_from(int("shard_size")?).map_err(|_| bad("shard_size"))?;
        if shard_size == 0 {
            return Err(bad("shard_size is 0"));
        }
        Ok(StudyDir {
            path: path.to_path_buf(),
            layout: Layout {
                case_columns: strings("case_columns")?,
                fields,
            },
            cases: u64::try_from(int("cases")?).map_err(|_| bad("cases"))?,
            shard_size,
            format: Format::parse(format)?,
            description: t
                .get("description")
                .and_then(toml::Value::as_str)
                .ok_or_else(|| bad("description"))?
                .to_string(),
        })
    }

    /// Opens the study in folder `path` (written by [`Study::run_in`]).
    ///
    /// # Errors
    /// [`StudyError::Io`] if there is no manifest, [`StudyError::Corrupt`]
    /// if it cannot be parsed.
    pub fn open(path: impl AsRef<Path>) -> Result<StudyDir, StudyError> {
        let path = path.as_ref();
        let file = path.join(MANIFEST);
        let text = fs::read_to_string(&file).map_err(StudyError::io(&file))?;
        StudyDir::parse(path, &text)
    }

    /// The columns of the results.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The description of the study written there
    /// ([`Study::describe`]): a program that reads a folder checks it is
    /// the study it expects.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The number of cases of the study.
    pub fn cases(&self) -> u64 {
        self.cases
    }

    /// The shards' format.
    pub fn format(&self) -> Format {
        self.format
    }

    /// The number of shards of the whole study.
    pub fn shard_count(&self) -> u64 {
        self.cases.div_ceil(self.shard_size)
    }

    /// The cases of shard `k`.
    pub fn shard_cases(&self, k: u64) -> Range<u64> {
        let start = k * self.shard_size;
        start..(start + self.shard_size).min(self.cases)
    }

    /// The file of shard `k`.
    pub fn shard_path(&self, k: u64) -> PathBuf {
        self.path
            .join(format!("part-{k:06}.{}", self.format.extension()))
    }

    /// Whether shard `k` is written.
    pub fn has_shard(&self, k: u64) -> bool {
        self.shard_path(k).is_file()
    }

    /// Whether every shard is written.
    pub fn is_complete(&self) -> bool {
        (0..self.shard_count()).all(|k| self.has_shard(k))
    }

    /// Reads shard `k` (a study too large for memory reads shard by
    /// shard).
    ///
    /// # Errors
    /// [`StudyError::Io`] if it is not written yet, [`StudyError::Corrupt`]
    /// if it does not match the manifest.
    pub fn read_shard(&self, k: u64) -> Result<Results, StudyError> {
        let range = self.shard_cases(k);
        let results = self
            .format
            .read(&self.shard_path(k), &self.layout, range.start)?;
        if results.len() as u64 != range.end - range.start {
            return Err(StudyError::Corrupt(format!(
                "{} holds {} cases, not {}",
                self.shard_path(k).display(),
                results.len(),
                range.end - range.start
            )));
        }
        Ok(results)
    }

    /// Reads every shard into one table.
    ///
    /// # Errors
    /// As [`StudyDir::read_shard`] for the first shard that fails (a
    /// missing one if the study is not finished).
    pub fn read_all(&self) -> Result<Results, StudyError> {
        let mut all = self.read_shard(0)?;
        for k in 1..self.shard_count() {
            all.append(self.read_shard(k)?)?;
        }
        Ok(all)
    }

    /// Writes shard `k` to a temporary file, flushes it to disk, and
    /// renames it into place.
    fn write_shard(&self, k: u64, results: &Results) -> Result<(), StudyError> {
        let path = self.shard_path(k);
        let temporary = self.path.join(format!(".part-{k:06}.tmp"));
        self.format.write(&temporary, results)?;
        fs::File::open(&temporary)
            .and_then(|f| f.sync_all())
            .map_err(StudyError::io(&temporary))?;
        fs::rename(&temporary, &path).map_err(StudyError::io(&path))
    }

    /// Creates the folder and its manifest, or checks that the manifest
    /// there describes the same study; removes temporary files a crash
    /// left behind.
    fn prepare(&self) -> Result<(), StudyError> {
        fs::create_dir_all(&self.path).map_err(StudyError::io(&self.path))?;
        let file = self.path.join(MANIFEST);
        match fs::read_to_string(&file) {
            Ok(text) => {
                let found = StudyDir::parse(&self.path, &text)?;
                if let Some(what) = self.difference(&found) {
                    return Err(StudyError::Mismatch {
                        path: self.path.clone(),
                        what,
                    });
                }
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                let temporary = self.path.join(".study.toml.tmp");
                fs::write(&temporary, self.manifest()).map_err(StudyError::io(&temporary))?;
                fs::rename(&temporary, &file).map_err(StudyError::io(&file))?;
            }
            Err(e) => return Err(StudyError::io(&file)(e)),
        }
        let entries = fs::read_dir(&self.path).map_err(StudyError::io(&self.path))?;
        for entry in entries.flatten() {
            let name = entry.file_name();
            if name.to_string_lossy().ends_with(".tmp") {
                fs::remove_file(entry.path()).map_err(StudyError::io(entry.path()))?;
            }
        }
        Ok(())
    }

    fn difference(&self, found: &StudyDir) -> Option<String> {
        let checks = [
            (self.format == found.format, "format"),
            (self.cases == found.cases, "number of cases"),
            (self.shard_size == found.shard_size, "shard size"),
            (self.layout == found.layout, "columns"),
            (
                self.description.lines().next() == found.description.lines().next(),
                "the model: its name, or its generated code (another build of it: \
                 another model text, load options, or version of autosim)",
            ),
            (
                self.description.lines().nth(1) == found.description.lines().nth(1),
                "the model as made: its parameters, inputs, discrete variables \
                 or initial state",
            ),
            (self.description == found.description, "description"),
        ];
        checks.iter().find(|c| !c.0).map(|c| c.1.to_string())
    }
}

impl<M, F, T> Study<M, F, T>
where
    M: Model,
    F: Fn() -> M + Sync,
    T: Task<M>,
{
    /// Runs the study into folder `path`: a manifest, then shards of
    /// `shard_size` consecutive cases in `format`, each computed (in
    /// parallel), written whole and renamed into place before the next,
    /// so memory holds one shard and a crash loses at most the shard in
    /// progress. Run it again on the same folder to resume: shards already
    /// written are skipped (the manifest must describe the same study).
    /// A study stopped by its [`Cancel`](super::Cancel) writes no shard
    /// after the stop, so it resumes the same way.
    ///
    /// # Errors
    /// A column that sets nothing, a folder that holds a different study,
    /// or an I/O error. Failed cases are not errors: they are counted in
    /// the summary and recorded in the shards.
    pub fn run_in(
        &self,
        path: impl AsRef<Path>,
        format: Format,
        shard_size: u64,
    ) -> Result<StudySummary, StudyError> {
        let start = Instant::now();
        self.targets()?;
        let dir = StudyDir {
            path: path.as_ref().to_path_buf(),
            layout: self.layout(),
            cases: self.cases.len(),
            shard_size: shard_size.max(1),
            format,
            description: self.describe(),
        };
        dir.prepare()?;
        let todo: Vec<u64> = (0..dir.shard_count())
            .filter(|k| !dir.has_shard(*k))
            .collect();
        let ran: u64 = todo
            .iter()
            .map(|k| dir.shard_cases(*k))
            .map(|r| r.end - r.start)
            .sum();
        let runner = Runner::new(self.parallelism, self.progress, dir.cases)?;
        runner.bar.set_position(dir.cases - ran);
        runner.bar.reset_eta();
        let mut failed = 0;
        for k in todo {
            let results = self.execute(dir.shard_cases(k), &runner)?;
            failed += results.failures() as u64;
            dir.write_shard(k, &results)?;
        }
        runner.bar.finish_and_clear();
        Ok(StudySummary {
            cases: dir.cases,
            ran,
            skipped: dir.cases - ran,
            failed,
            elapsed: start.elapsed(),
        })
    }
}

/// The header of a CSV shard (also the order of Parquet's columns, with
/// fields unflattened).
pub(super) fn csv_header(layout: &Layout) -> Vec<String> {
    let mut header = vec!["case".to_string()];
    header.extend(layout.case_columns.iter().cloned());
    for f in &layout.fields {
        if f.len == 1 {
            header.push(f.name.clone());
        } else {
            header.extend((0..f.len).map(|k| format!("{}[{k}]", f.name)));
        }
    }
    header.push("ok".to_string());
    header.push("error".to_string());
    header
}

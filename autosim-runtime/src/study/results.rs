//! The results of a study (or of a chunk of its cases) in memory: a row
//! per case, columnar access by name.

use std::string::String;
use std::vec;
use std::vec::Vec;

use super::StudyError;
use super::task::Field;

/// The columns of a study's results: the case table's columns, then the
/// task's fields (each `len` values wide), then the case's status.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    /// The case table's columns ([`Cases::names`](super::Cases::names)).
    pub case_columns: Vec<String>,
    /// The kept quantities ([`Task::fields`](super::Task::fields)).
    pub fields: Vec<Field>,
}

impl Layout {
    /// Values kept per case (the sum of the fields' lengths).
    pub fn width(&self) -> usize {
        self.fields.iter().map(|f| f.len).sum()
    }

    /// Where field `name` starts in a case's row of values, and its length.
    pub fn field_span(&self, name: &str) -> Option<(usize, usize)> {
        let mut start = 0;
        for f in &self.fields {
            if f.name == name {
                return Some((start, f.len));
            }
            start += f.len;
        }
        None
    }
}

/// The results of consecutive cases `first_case..first_case + len()`:
/// for each case its index, its values in the case table, the kept values
/// (NaN for a failed case) and its error (`None` if it succeeded).
///
/// Values are stored row-major (a case's values side by side), ready to
/// become a NumPy array of shape `(cases, width)`. Two results are equal
/// (`==`) when their layouts, cases and errors are equal and every value
/// has the same bits (NaN included): the comparison the study's
/// reproducibility promise is about.
#[derive(Clone, Debug)]
pub struct Results {
    layout: Layout,
    first_case: u64,
    case_values: Vec<f64>,
    values: Vec<f64>,
    errors: Vec<Option<String>>,
}

impl PartialEq for Results {
    fn eq(&self, other: &Results) -> bool {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        self.layout == other.layout
            && self.first_case == other.first_case
            && self.errors == other.errors
            && bits(&self.case_values) == bits(&other.case_values)
            && bits(&self.values) == bits(&other.values)
    }
}

impl Results {
    /// Results of `len` cases from `first_case`, every value NaN and every
    /// case successful, to be filled in.
    pub(super) fn blank(layout: Layout, first_case: u64, len: usize) -> Results {
        Results {
            case_values: vec![f64::NAN; len * layout.case_columns.len()],
            values: vec![f64::NAN; len * layout.width()],
            errors: vec![None; len],
            layout,
            first_case,
        }
    }

    /// Results from their parts (a shard read back).
    ///
    /// # Errors
    /// [`StudyError::Corrupt`] if the lengths do not match the layout.
    pub(super) fn from_parts(
        layout: Layout,
        first_case: u64,
        case_values: Vec<f64>,
        values: Vec<f64>,
        errors: Vec<Option<String>>,
    ) -> Result<Results, StudyError> {
        let len = errors.len();
        if case_values.len() != len * layout.case_columns.len()
            || values.len() != len * layout.width()
        {
            return Err(StudyError::Corrupt(
                "column lengths do not match the layout".into(),
            ));
        }
        Ok(Results {
            layout,
            first_case,
            case_values,
            values,
            errors,
        })
    }

    /// The rows to fill: each case's table values, kept values and error.
    #[allow(clippy::type_complexity)]
    pub(super) fn rows_mut(&mut self) -> Vec<(&mut [f64], &mut [f64], &mut Option<String>)> {
        let (nc, width) = (self.layout.case_columns.len(), self.layout.width());
        let len = self.errors.len();
        fn chunks(v: &mut [f64], w: usize, len: usize) -> Vec<&mut [f64]> {
            if w == 0 {
                (0..len).map(|_| &mut [][..]).collect()
            } else {
                v.chunks_mut(w).collect()
            }
        }
        let cases = chunks(&mut self.case_values, nc, len);
        let values = chunks(&mut self.values, width, len);
        cases
            .into_iter()
            .zip(values)
            .zip(self.errors.iter_mut())
            .map(|((c, v), e)| (c, v, e))
            .collect()
    }

    /// The columns.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// The index of the first case.
    pub fn first_case(&self) -> u64 {
        self.first_case
    }

    /// The number of cases.
    pub fn len(&self) -> usize {
        self.errors.len()
    }

    /// `true` if there are no cases.
    pub fn is_empty(&self) -> bool {
        self.errors.is_empty()
    }

    /// The case table's values, row-major (`len() × case_columns.len()`).
    pub fn case_values(&self) -> &[f64] {
        &self.case_values
    }

    /// The kept values, row-major (`len() × layout().width()`); NaN for a
    /// failed case.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Each case's error (`None` for a case that succeeded).
    pub fn errors(&self) -> &[Option<String>] {
        &self.errors
    }

    /// How many cases failed.
    pub fn failures(&self) -> usize {
        self.errors.iter().filter(|e| e.is_some()).count()
    }

    /// The values of case-table column `name`, one per case.
    pub fn case_column(&self, name: &str) -> Option<Vec<f64>> {
        let n = self.layout.case_columns.len();
        let k = self.layout.case_columns.iter().position(|c| c == name)?;
        Some(
            self.case_values
                .iter()
                .skip(k)
                .step_by(n)
                .copied()
                .collect(),
        )
    }

    /// The values of field `name`, row-major (`len()` rows of the field's
    /// length).
    pub fn field(&self, name: &str) -> Option<Vec<f64>> {
        let (start, len) = self.layout.field_span(name)?;
        let width = self.layout.width();
        Some(
            self.values
                .chunks(width.max(1))
                .take(self.len())
                .flat_map(|row| &row[start..start + len])
                .copied()
                .collect(),
        )
    }

    /// Appends the results of the cases that follow (chunks run apart
    /// and concatenated equal the whole run).
    ///
    /// # Errors
    /// [`StudyError::Corrupt`] if the layouts differ or `next` does not
    /// start where these results end.
    pub fn append(&mut self, next: Results) -> Result<(), StudyError> {
        if next.layout != self.layout || next.first_case != self.first_case + self.len() as u64 {
            return Err(StudyError::Corrupt(std::format!(
                "cases {}.. do not follow cases {}..{} of the same layout",
                next.first_case,
                self.first_case,
                self.first_case + self.len() as u64
            )));
        }
        self.case_values.extend(next.case_values);
        self.values.extend(next.values);
        self.errors.extend(next.errors);
        Ok(())
    }
}

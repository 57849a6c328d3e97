//! Closest-name suggestions for misspelled keys and column names, and
//! names labelled with their units.

use std::prelude::rust_2024::*;

/// `name [unit]`, or the bare name when it has no unit (a column or an
/// axis of a dimensionless quantity is not headed `h []`).
#[cfg(any(feature = "csv", feature = "plot"))]
pub(crate) fn labelled(name: &str, unit: &str) -> String {
    match unit.trim() {
        "" => name.to_string(),
        unit => std::format!("{name} [{unit}]"),
    }
}

/// Levenshtein distance between `a` and `b`, counted in characters.
pub(crate) fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != *cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

/// The known name closest to `key`, if it is close enough to be a likely
/// typo: a case-insensitive match, or at most a third of the characters
/// (and at least 1, at most 3) edited. Ties go to the first known name.
pub(crate) fn closest<'a>(key: &str, known: &[&'a str]) -> Option<&'a str> {
    let lower = key.to_lowercase();
    if let Some(name) = known.iter().find(|n| n.to_lowercase() == lower) {
        return Some(name);
    }
    let limit = (key.chars().count() / 3).clamp(1, 3);
    known
        .iter()
        .map(|n| (edit_distance(&lower, &n.to_lowercase()), *n))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, n)| n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_of_textbook_pairs() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("abc", ""), 3);
        assert_eq!(edit_distance("flaw", "lawn"), 2);
        assert_eq!(edit_distance("same", "same"), 0);
        assert_eq!(edit_distance("ä", "a"), 1);
    }

    #[test]
    fn suggestions_are_close_or_absent() {
        let known = ["stiffness", "mu", "damping"];
        assert_eq!(closest("stifness", &known), Some("stiffness"));
        assert_eq!(closest("Stiffness", &known), Some("stiffness"));
        assert_eq!(closest("mv", &known), Some("mu"));
        assert_eq!(closest("dampnig", &known), Some("damping"));
        assert_eq!(closest("gravity", &known), None);
    }
}

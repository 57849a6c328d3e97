//! Arrays of short literals packed several to a line, as rustfmt lays them
//! out. prettyplease writes every element of a long array on its own line;
//! rustfmt instead fills lines ("mixed" layout) when every element is a
//! simple literal of at most ten characters
//! (`short_array_element_width_threshold`), which is what the name and unit
//! tables of a large model are: a 50-link chain's 100 state names take 9
//! lines instead of 100.

/// rustfmt's `max_width`: a packed line stays shorter than this, as
/// rustfmt's do.
const MAX_WIDTH: usize = 100;

/// rustfmt's `short_array_element_width_threshold`.
const SHORT_ELEMENT: usize = 10;

/// `text` with every vertically written array of short literals packed.
pub fn pack_short_arrays(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < lines.len() {
        out.push_str(lines[i]);
        out.push('\n');
        if let Some(elements) = short_elements_after(&lines, i) {
            let indent = indentation(lines[i + 1]);
            for row in packed_rows(indent, &elements) {
                out.push_str(&row);
                out.push('\n');
            }
            i += elements.len();
        }
        i += 1;
    }
    if !text.ends_with('\n') {
        out.pop();
    }
    out
}

/// The elements of the array opened at line `open`, if it is written one
/// element per line, every element a short literal, and closed at the
/// opener's indentation.
fn short_elements_after<'a>(lines: &[&'a str], open: usize) -> Option<Vec<&'a str>> {
    if !lines[open].ends_with('[') {
        return None;
    }
    let outer = indentation(lines[open]);
    let (inner, close) = (format!("{outer}    "), format!("{outer}]"));
    let mut elements = Vec::new();
    for line in &lines[open + 1..] {
        if line.starts_with(&close) {
            return (elements.len() > 1).then_some(elements);
        }
        let element = line.strip_prefix(&inner)?.strip_suffix(',')?;
        if !is_short_literal(element) {
            return None;
        }
        elements.push(element);
    }
    None
}

/// A string literal without quotes or escapes inside, or a plain number,
/// of at most [`SHORT_ELEMENT`] characters.
fn is_short_literal(element: &str) -> bool {
    let string = element.len() >= 2
        && element.starts_with('"')
        && element.ends_with('"')
        && !element[1..element.len() - 1].contains(['"', '\\']);
    let number = element
        .strip_prefix('-')
        .unwrap_or(element)
        .starts_with(|c: char| c.is_ascii_digit())
        && element[1..]
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '+' | '-'));
    (string || number) && element.chars().count() <= SHORT_ELEMENT
}

/// The leading spaces of `line`.
fn indentation(line: &str) -> &str {
    &line[..line.len() - line.trim_start().len()]
}

/// `elements` at `indent`, as many to a row as fit in [`MAX_WIDTH`], each
/// followed by a comma.
fn packed_rows(indent: &str, elements: &[&str]) -> Vec<String> {
    let mut rows = Vec::new();
    let mut row = String::from(indent);
    for element in elements {
        let fresh = row.len() == indent.len();
        let needed = element.len() + 1 + usize::from(!fresh);
        if !fresh && row.len() + needed >= MAX_WIDTH {
            rows.push(std::mem::replace(&mut row, String::from(indent)));
        }
        if row.len() > indent.len() {
            row.push(' ');
        }
        row.push_str(element);
        row.push(',');
    }
    rows.push(row);
    rows
}

#[cfg(test)]
mod tests {
    use super::pack_short_arrays;

    /// The expected layout is rustfmt's (1.95, edition 2024, default
    /// settings) for the same items.
    #[test]
    fn short_literals_fill_rows_as_rustfmt_does() {
        let names: Vec<String> = (1..=30).map(|k| format!("        \"q{k}\",")).collect();
        let vertical = format!(
            "    const STATE_NAMES: &'static [&'static str] = &[\n{}\n    ];\n",
            names.join("\n")
        );
        let expected = "    const STATE_NAMES: &'static [&'static str] = &[
        \"q1\", \"q2\", \"q3\", \"q4\", \"q5\", \"q6\", \"q7\", \"q8\", \"q9\", \"q10\", \"q11\", \"q12\", \"q13\", \"q14\",
        \"q15\", \"q16\", \"q17\", \"q18\", \"q19\", \"q20\", \"q21\", \"q22\", \"q23\", \"q24\", \"q25\", \"q26\", \"q27\",
        \"q28\", \"q29\", \"q30\",
    ];
";
        assert_eq!(pack_short_arrays(&vertical), expected);
    }

    #[test]
    fn arrays_with_a_long_or_compound_element_stay_vertical() {
        for odd in ["\"N m s/rad\"", "a + b", "\"a\\\"b\"", "x"] {
            let text = format!("let v = [\n    \"a\",\n    {odd},\n    \"b\",\n];\n");
            assert_eq!(pack_short_arrays(&text), text, "{odd}");
        }
    }

    #[test]
    fn numbers_pack_and_other_text_is_untouched() {
        let text = "fn f() {\n    let v = [\n        1.0,\n        -2.5,\n        3,\n    ];\n}";
        assert_eq!(
            pack_short_arrays(text),
            "fn f() {\n    let v = [\n        1.0, -2.5, 3,\n    ];\n}"
        );
    }
}

//! Arrays of short literals packed several to a line, as rustfmt lays them
//! out. prettyplease writes every element of a long array on its own line;
//! rustfmt instead fills lines ("mixed" layout) when every element is a
//! simple literal of at most ten characters
//! (`short_array_element_width_threshold`), which is what the name and unit
//! tables of a large model are: a 50-link chain's 100 state names take 9
//! lines instead of 100. The field lists of the parameter and input
//! accessors (`[p.m1, p.L1, …]`, `[&mut p.m1, …]`) are packed the same way,
//! where rustfmt would keep them vertical: 252 parameters take 26 lines.

/// rustfmt's `max_width`: a packed line stays shorter than this, as
/// rustfmt's do.
const MAX_WIDTH: usize = 100;

/// rustfmt's `short_array_element_width_threshold`.
const SHORT_ELEMENT: usize = 10;

/// The longest field place (`&mut self.inputs.name`) packed.
const SHORT_PLACE: usize = 32;

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
        if !is_short_literal(element) && !is_short_place(element) {
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

/// A field of a local (`p.m1`, `self.inputs.torque`), or `&mut` of one, of
/// at most [`SHORT_PLACE`] characters.
fn is_short_place(element: &str) -> bool {
    let path = element.strip_prefix("&mut ").unwrap_or(element);
    let parts: Vec<&str> = path.split('.').collect();
    let identifier = |s: &str| {
        let s = s.strip_prefix("r#").unwrap_or(s);
        s.starts_with(|c: char| c.is_alphabetic() || c == '_')
            && s.chars().all(|c| c.is_alphanumeric() || c == '_')
    };
    parts.len() >= 2 && parts.iter().all(|p| identifier(p)) && element.len() <= SHORT_PLACE
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
        for odd in ["\"N m s/rad\"", "a + b", "\"a\\\"b\"", "x", "p.f(x)", "&p"] {
            let text = format!("let v = [\n    \"a\",\n    {odd},\n    \"b\",\n];\n");
            assert_eq!(pack_short_arrays(&text), text, "{odd}");
        }
    }

    #[test]
    fn field_places_pack() {
        let text = "    for (v, field) in values.iter_mut().zip([\n        p.m1,\n        &mut p.L1,\n        self.inputs.r#type,\n    ]) {\n";
        assert_eq!(
            pack_short_arrays(text),
            "    for (v, field) in values.iter_mut().zip([\n        p.m1, &mut p.L1, self.inputs.r#type,\n    ]) {\n"
        );
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

//! Arrays of short literals packed several to a line, as rustfmt lays them
//! out. prettyplease writes every element of a long array on its own line;
//! rustfmt instead fills lines ("mixed" layout) when every element is a
//! simple literal of at most ten characters
//! (`short_array_element_width_threshold`), which is what the name and unit
//! tables of a large model are: a 50-link chain's 100 state names take 9
//! lines instead of 100. The field lists of the parameter and input
//! accessors (`[p.m1, p.L1, …]`, `[&mut p.m1, …]`) are packed the same way,
//! where rustfmt would keep them vertical: 252 parameters take 26 lines.
//! An array prettyplease split although the whole statement fits in 100
//! characters goes back on one line, as rustfmt keeps it
//! (`math::sin_cos_lanes([q10, q11])`).

/// rustfmt's `max_width`: a packed line stays shorter than this, as
/// rustfmt's do.
const MAX_WIDTH: usize = 100;

/// rustfmt's `short_array_element_width_threshold`.
const SHORT_ELEMENT: usize = 10;

/// The longest field place (`&mut self.inputs.name`) packed.
const SHORT_PLACE: usize = 32;

/// `text` with every vertically written array of short elements on one
/// line where the whole statement fits (`sin_cos_lanes([q10, q11])`), and
/// every other one of short literals or places packed in rows.
pub fn pack_short_arrays(text: &str) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < lines.len() {
        let array = elements_after(&lines, i);
        if let Some(a) = &array
            && let Some(one_line) = joined(lines[i], a)
        {
            out.push_str(&one_line);
            out.push('\n');
            i += a.elements.len() + 2;
            continue;
        }
        out.push_str(lines[i]);
        out.push('\n');
        if let Some(a) = array.filter(|a| a.packable) {
            let indent = indentation(lines[i + 1]);
            for row in packed_rows(indent, &a.elements) {
                out.push_str(&row);
                out.push('\n');
            }
            i += a.elements.len();
        }
        i += 1;
    }
    if !text.ends_with('\n') {
        out.pop();
    }
    out
}

/// An array written one element per line.
struct VerticalArray<'a> {
    /// Its elements, without their commas.
    elements: Vec<&'a str>,
    /// Its closing line (`]`, `]);`, `]) {`, …).
    close: &'a str,
    /// Whether every element is a short literal or place (packed in rows
    /// when the array does not fit on one line).
    packable: bool,
}

/// The array opened at line `open`, if it is written one element per line,
/// every element short (a literal, a place or an identifier), and closed
/// at the opener's indentation.
fn elements_after<'a>(lines: &[&'a str], open: usize) -> Option<VerticalArray<'a>> {
    if !lines[open].ends_with('[') {
        return None;
    }
    let outer = indentation(lines[open]);
    let (inner, close) = (format!("{outer}    "), format!("{outer}]"));
    let mut elements = Vec::new();
    let mut packable = true;
    for line in &lines[open + 1..] {
        if line.starts_with(&close) {
            return (elements.len() > 1).then_some(VerticalArray {
                elements,
                close: line,
                packable,
            });
        }
        let element = line.strip_prefix(&inner)?.strip_suffix(',')?;
        let short = is_short_literal(element) || is_short_place(element);
        if !short && !is_identifier(element) {
            return None;
        }
        packable &= short;
        elements.push(element);
    }
    None
}

/// The array's opening line, elements and closing line as one line, if
/// that is shorter than [`MAX_WIDTH`] (as rustfmt writes it).
fn joined(open_line: &str, array: &VerticalArray<'_>) -> Option<String> {
    let line = format!(
        "{open_line}{}{}",
        array.elements.join(", "),
        array.close.trim_start()
    );
    (line.len() < MAX_WIDTH).then_some(line)
}

/// A plain identifier of at most [`SHORT_PLACE`] characters.
fn is_identifier(element: &str) -> bool {
    element.starts_with(|c: char| c.is_alphabetic() || c == '_')
        && element.chars().all(|c| c.is_alphanumeric() || c == '_')
        && element.len() <= SHORT_PLACE
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
        let many = "    \"a\",\n".repeat(30);
        for odd in ["\"N m s/rad\"", "a + b", "\"a\\\"b\"", "x", "p.f(x)", "&p"] {
            let text = format!("let v = [\n{many}    {odd},\n    \"b\",\n];\n");
            assert_eq!(pack_short_arrays(&text), text, "{odd}");
        }
    }

    #[test]
    fn field_places_pack() {
        let text = "    for (v, field) in values.iter_mut().zip([\n        p.mass_of_the_first_link,\n        &mut p.length_of_the_link,\n        self.inputs.r#type,\n    ]) {\n";
        assert_eq!(
            pack_short_arrays(text),
            "    for (v, field) in values.iter_mut().zip([\n        p.mass_of_the_first_link, &mut p.length_of_the_link, self.inputs.r#type,\n    ]) {\n"
        );
    }

    #[test]
    fn arrays_that_fit_go_on_one_line_and_other_text_is_untouched() {
        let text = "fn f() {\n    let v = [\n        1.0,\n        -2.5,\n        3,\n    ];\n}";
        assert_eq!(
            pack_short_arrays(text),
            "fn f() {\n    let v = [1.0, -2.5, 3];\n}"
        );
        let pair = "            let ([sin_q10, sin_q11], [cos_q10, cos_q11]) = math::sin_cos_lanes([\n                q10,\n                q11,\n            ]);\n";
        assert_eq!(
            pack_short_arrays(pair),
            "            let ([sin_q10, sin_q11], [cos_q10, cos_q11]) = math::sin_cos_lanes([q10, q11]);\n"
        );
        // 100 characters or more: left as it is.
        let long = pair.replace("sin_q", "sine_of_angle_q");
        assert_eq!(pack_short_arrays(&long), long);
    }
}

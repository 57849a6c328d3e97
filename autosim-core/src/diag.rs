//! Diagnostics: spans, error messages with help, a collector, and the two
//! ways out — `syn::Error` for the macro and `path:line:col` text for files.
//!
//! Every phase reports through [`Diagnostics`] rather than stopping at the
//! first error, so a user sees every mistake of a model at once. A
//! diagnostic's [`Span`] is either a token span (model written inline in
//! `autosim::model! { ... }`) or a file location (model read from a `.sim`
//! file); see [`Span`] for why the two are kept apart.

use std::fmt;
use std::path::{Path, PathBuf};

/// A position in a source file: 1-based line, 1-based column counted in
/// characters (not bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct LineCol {
    /// Line number, starting at 1.
    pub line: usize,
    /// Column number in characters, starting at 1.
    pub col: usize,
}

impl fmt::Display for LineCol {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.col)
    }
}

/// Where a piece of model text came from.
///
/// A model written inline carries the compiler's token spans, so errors and
/// generated code point into the user's Rust file. A model read from a `.sim`
/// file carries line/column locations instead and **no** `proc_macro2::Span`:
/// the tokens of a file are lexed by proc-macro2's fallback lexer, and a
/// fallback span mixed into compiler tokens inside a proc macro panics. For a
/// file span, [`Span::to_proc_macro`] therefore gives `Span::call_site()`,
/// evaluated when it is called (i.e. after the file parse has ended).
#[derive(Clone, Copy, Default)]
pub struct Span {
    /// First and last token spans, for models written as Rust tokens.
    tokens: Option<(proc_macro2::Span, proc_macro2::Span)>,
    /// Start (inclusive) and end (exclusive) in a file, for models read from files.
    file: Option<(LineCol, LineCol)>,
}

impl Span {
    /// A span of one token of a model written as Rust tokens.
    pub fn from_token(span: proc_macro2::Span) -> Span {
        Span {
            tokens: Some((span, span)),
            file: None,
        }
    }

    /// A span in a model file, from `start` (inclusive) to `end` (exclusive).
    pub fn from_file(start: LineCol, end: LineCol) -> Span {
        Span {
            tokens: None,
            file: Some((start, end)),
        }
    }

    /// A span with no location: reported at the macro call site, or without
    /// a line number for files.
    pub fn unknown() -> Span {
        Span::default()
    }

    /// The span from the start of `self` to the end of `other`.
    pub fn to(self, other: Span) -> Span {
        let tokens = match (self.tokens, other.tokens) {
            (Some((first, _)), Some((_, last))) => Some((first, last)),
            (a, b) => a.or(b),
        };
        let file = match (self.file, other.file) {
            (Some((start, _)), Some((_, end))) if end >= start => Some((start, end)),
            (a, b) => a.or(b),
        };
        Span { tokens, file }
    }

    /// A span just after this one (where a missing `;` or `,` belongs): one
    /// column past the end in a file, the last token otherwise.
    pub fn after(self) -> Span {
        Span {
            tokens: self.tokens.map(|(_, last)| (last, last)),
            file: self.file.map(|(_, end)| {
                (
                    end,
                    LineCol {
                        line: end.line,
                        col: end.col + 1,
                    },
                )
            }),
        }
    }

    /// The compiler span to attach to generated tokens and `syn::Error`s: the
    /// first token's span, or `Span::call_site()` for a file span.
    pub fn to_proc_macro(self) -> proc_macro2::Span {
        match self.tokens {
            Some((first, _)) => first,
            None => proc_macro2::Span::call_site(),
        }
    }

    /// First and last token spans (for `syn::Error::new_spanned`-style ranges).
    pub fn token_range(self) -> Option<(proc_macro2::Span, proc_macro2::Span)> {
        self.tokens
    }

    /// Start of the span in its file, if it came from a file.
    pub fn start(self) -> Option<LineCol> {
        self.file.map(|(start, _)| start)
    }

    /// The line the span starts on: in its file, or in the Rust file of a
    /// model written as tokens (when the compiler tells; not in unit tests).
    pub fn line(self) -> Option<usize> {
        self.position().map(|at| at.line)
    }

    /// Where the span starts: in its file, or in the Rust file of a model
    /// written as tokens (when the compiler tells; not in unit tests).
    fn position(self) -> Option<LineCol> {
        match (self.file, self.tokens) {
            (Some((start, _)), _) => Some(start),
            (None, Some((first, _))) => {
                let at = first.start();
                (at.line > 0).then_some(LineCol {
                    line: at.line,
                    col: at.column + 1,
                })
            }
            (None, None) => None,
        }
    }

    /// End (exclusive) of the span in its file, if it came from a file.
    pub fn end(self) -> Option<LineCol> {
        self.file.map(|(_, end)| end)
    }
}

impl fmt::Debug for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.file, self.tokens) {
            (Some((start, end)), _) => write!(f, "@{start}-{end}"),
            (None, Some(_)) => f.write_str("@tokens"),
            (None, None) => f.write_str("@?"),
        }
    }
}

/// One error: where, what, and how to fix it.
#[derive(Clone, Debug)]
pub struct Diagnostic {
    /// The text the error is about.
    pub span: Span,
    /// The main message, lower case, no final period (`unknown body option `rotat``).
    pub message: String,
    /// Extra facts (`valid options are: ...`), rendered as `= note: ...`.
    pub notes: Vec<String>,
    /// Suggested fixes (`did you mean `rotate`?`), rendered as `= help: ...`.
    pub help: Vec<String>,
}

impl Diagnostic {
    /// An error at `span`.
    pub fn error(span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            span,
            message: message.into(),
            notes: Vec::new(),
            help: Vec::new(),
        }
    }

    /// Adds a note.
    pub fn note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    /// Adds a help line.
    pub fn help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help.push(help.into());
        self
    }

    /// The message followed by its notes and help, as one string (the form a
    /// `syn::Error` carries).
    pub fn full_message(&self) -> String {
        let mut text = self.message.clone();
        for help in &self.help {
            text.push_str("\n= help: ");
            text.push_str(help);
        }
        for note in &self.notes {
            text.push_str("\n= note: ");
            text.push_str(note);
        }
        text
    }

    /// This diagnostic as a `syn::Error` at its token span (the first to the
    /// last token when the span covers several), or at the call site for a
    /// file span.
    pub fn to_syn_error(&self) -> syn::Error {
        let message = self.full_message();
        match self.span.token_range() {
            Some((first, last)) => {
                let mut start = proc_macro2::Punct::new('.', proc_macro2::Spacing::Alone);
                start.set_span(first);
                let mut end = start.clone();
                end.set_span(last);
                let tokens: proc_macro2::TokenStream =
                    [proc_macro2::TokenTree::from(start), end.into()]
                        .into_iter()
                        .collect();
                syn::Error::new_spanned(tokens, message)
            }
            None => syn::Error::new(proc_macro2::Span::call_site(), message),
        }
    }
}

/// A collector of diagnostics: phases push every error they find and check
/// [`Diagnostics::is_empty`] (or use [`Diagnostics::finish`]) at the end.
#[derive(Clone, Debug, Default)]
pub struct Diagnostics {
    list: Vec<Diagnostic>,
}

impl Diagnostics {
    /// An empty collector.
    pub fn new() -> Diagnostics {
        Diagnostics::default()
    }

    /// Records a diagnostic.
    pub fn push(&mut self, diagnostic: Diagnostic) {
        self.list.push(diagnostic);
    }

    /// Records an error with just a message.
    pub fn error(&mut self, span: Span, message: impl Into<String>) {
        self.push(Diagnostic::error(span, message));
    }

    /// Moves all of `other`'s diagnostics into `self`.
    pub fn append(&mut self, other: Diagnostics) {
        self.list.extend(other.list);
    }

    /// True when nothing was reported.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Number of diagnostics.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// The diagnostics in the order they were reported.
    pub fn iter(&self) -> std::slice::Iter<'_, Diagnostic> {
        self.list.iter()
    }

    /// `Ok(value)` when nothing was reported, else all the diagnostics.
    pub fn finish<T>(self, value: T) -> Result<T, Diagnostics> {
        if self.is_empty() {
            Ok(value)
        } else {
            Err(self)
        }
    }

    /// All diagnostics as one combined `syn::Error` (one message per
    /// diagnostic, each at its own span, in source order), for the macro to
    /// return. `None` when there is nothing to report.
    pub fn to_syn_error(&self) -> Option<syn::Error> {
        let mut iter = self.sorted().into_iter();
        let mut error = iter.next()?.to_syn_error();
        for diagnostic in iter {
            error.combine(diagnostic.to_syn_error());
        }
        Some(error)
    }

    /// Renders every diagnostic against `file`, sorted by position:
    ///
    /// ```text
    /// sat.sim:3:30: error: unknown body option `rotat`
    ///   |
    /// 3 | body C "clock" { parent: B, rotat: 3 }
    ///   |                             ^^^^^
    ///   = help: did you mean `rotate`?
    /// ```
    pub fn render(&self, file: &SourceFile) -> String {
        let mut out = String::new();
        for diagnostic in self.sorted() {
            render_one(&mut out, diagnostic, file, Header::Compact);
        }
        out
    }

    /// The diagnostics of a model file as one combined `syn::Error` at `at`
    /// (for the macro: the `file = "..."` literal), one message per
    /// diagnostic, sorted by position, each followed by its place in the
    /// file the way rustc shows its own (rustc adds the `error: `):
    ///
    /// ```text
    /// unknown body option `rotat`
    ///  --> sat.sim:3:30
    ///   |
    /// 3 | body C "clock" { parent: B, rotat: 3 }
    ///   |                             ^^^^^
    ///   = help: did you mean `rotate`?
    /// ```
    ///
    /// `None` when there is nothing to report.
    ///
    /// A diagnostic at the macro's own tokens (a scene option naming
    /// something the model lacks) is shown there instead.
    pub fn to_syn_error_in(&self, file: &SourceFile, at: proc_macro2::Span) -> Option<syn::Error> {
        let mut errors = self.sorted().into_iter().map(|diagnostic| {
            if diagnostic.span.file.is_none() && diagnostic.span.token_range().is_some() {
                return diagnostic.to_syn_error();
            }
            let mut text = String::new();
            render_one(&mut text, diagnostic, file, Header::Rustc);
            syn::Error::new(at, text.trim_end())
        });
        let mut error = errors.next()?;
        for other in errors {
            error.combine(other);
        }
        Some(error)
    }

    /// The diagnostics in source order (stable: reported order among equal
    /// positions; those without a position first).
    fn sorted(&self) -> Vec<&Diagnostic> {
        let mut sorted: Vec<&Diagnostic> = self.list.iter().collect();
        sorted.sort_by_key(|d| d.span.position());
        sorted
    }
}

impl IntoIterator for Diagnostics {
    type Item = Diagnostic;
    type IntoIter = std::vec::IntoIter<Diagnostic>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.into_iter()
    }
}

impl From<Diagnostic> for Diagnostics {
    fn from(diagnostic: Diagnostic) -> Diagnostics {
        Diagnostics {
            list: vec![diagnostic],
        }
    }
}

impl Extend<Diagnostic> for Diagnostics {
    fn extend<I: IntoIterator<Item = Diagnostic>>(&mut self, iter: I) {
        self.list.extend(iter);
    }
}

/// The text of a model file and the path it is shown under in diagnostics.
#[derive(Clone, Debug)]
pub struct SourceFile {
    /// The path as the user should see it (e.g. relative to the crate root).
    pub path: PathBuf,
    /// The whole text of the file.
    pub text: String,
}

impl SourceFile {
    /// A source file from a path and its text.
    pub fn new(path: impl Into<PathBuf>, text: impl Into<String>) -> SourceFile {
        SourceFile {
            path: path.into(),
            text: text.into(),
        }
    }

    /// Reads `path` from disk (as UTF-8), showing it as `shown_as` in
    /// diagnostics. A missing or unreadable file is a diagnostic at `at`
    /// (for the macro: the span of the `file = "..."` literal).
    pub fn read(
        path: &Path,
        shown_as: impl Into<PathBuf>,
        at: Span,
    ) -> Result<SourceFile, Diagnostics> {
        match std::fs::read_to_string(path) {
            Ok(text) => Ok(SourceFile::new(shown_as, text)),
            Err(error) => {
                // The path as the user wrote it: the full path depends on the
                // machine (and is not what they wrote).
                let shown = shown_as.into();
                let diagnostic = if error.kind() == std::io::ErrorKind::NotFound {
                    Diagnostic::error(at, format!("model file `{}` not found", shown.display()))
                        .help(
                            "the path is relative to the crate root (the directory of Cargo.toml)",
                        )
                } else {
                    Diagnostic::error(
                        at,
                        format!("cannot read model file `{}`: {error}", shown.display()),
                    )
                };
                Err(diagnostic.into())
            }
        }
    }

    /// Line `line` (1-based) without its line ending, or `None` past the end.
    pub fn line(&self, line: usize) -> Option<&str> {
        let text = self.text.strip_prefix('\u{feff}').unwrap_or(&self.text);
        let found = text.split('\n').nth(line.checked_sub(1)?)?;
        Some(found.strip_suffix('\r').unwrap_or(found))
    }
}

/// How a rendered diagnostic begins.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Header {
    /// `path:line:col: error: message` (terminals, build scripts).
    Compact,
    /// `message`, then ` --> path:line:col` (inside a compiler error, which
    /// adds its own `error: `).
    Rustc,
}

fn render_one(out: &mut String, diagnostic: &Diagnostic, file: &SourceFile, header: Header) {
    use std::fmt::Write as _;
    let path = file.path.display();
    let message = &diagnostic.message;
    let (start, end) = match (diagnostic.span.start(), diagnostic.span.end()) {
        (Some(start), Some(end)) => (start, end),
        _ => {
            let _ = match header {
                Header::Compact => writeln!(out, "{path}: error: {message}"),
                Header::Rustc => writeln!(out, "{message}\n--> {path}"),
            };
            render_footer(out, diagnostic, 0);
            return;
        }
    };
    let gutter = start.line.to_string().len();
    let _ = match header {
        Header::Compact => writeln!(out, "{path}:{start}: error: {message}"),
        Header::Rustc => writeln!(out, "{message}\n{:gutter$}--> {path}:{start}", ""),
    };
    if let Some(line) = file.line(start.line) {
        let line = line.trim_end();
        let _ = writeln!(out, "{:gutter$} |", "");
        let _ = writeln!(out, "{} | {line}", start.line);
        // Copy tabs so the caret lines up; everything else becomes a space.
        let prefix: String = line
            .chars()
            .take(start.col.saturating_sub(1))
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        let line_chars = line.chars().count();
        let stop = if end.line == start.line {
            end.col
        } else {
            line_chars + 1
        };
        let width = stop.saturating_sub(start.col).max(1);
        let _ = writeln!(out, "{:gutter$} | {prefix}{}", "", "^".repeat(width));
    }
    render_footer(out, diagnostic, gutter);
}

fn render_footer(out: &mut String, diagnostic: &Diagnostic, gutter: usize) {
    use std::fmt::Write as _;
    for help in &diagnostic.help {
        let _ = writeln!(out, "{:gutter$} = help: {help}", "");
    }
    for note in &diagnostic.notes {
        let _ = writeln!(out, "{:gutter$} = note: {note}", "");
    }
}

/// The closest of `candidates` to `word`, if it is close enough to be a
/// likely misspelling (for "did you mean" help): one edit per three
/// letters, at least one; a name of one or two letters is not matched to
/// one that only replaces a letter (`Q` is no misspelling of `N`, nor
/// `w1` of `n1`; `kk` may be one of `k`).
pub fn did_you_mean<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let word = word.to_lowercase();
    let letters = word.chars().count();
    let limit = (letters / 3).max(1);
    candidates
        .into_iter()
        .map(|candidate| (edit_distance(&word, &candidate.to_lowercase()), candidate))
        .filter(|&(distance, candidate)| {
            distance <= limit
                && !(letters < 3 && distance > 0 && replaces_a_letter(&word, candidate))
        })
        // Of equally close names, the one that starts most like the word
        // (`ph` is `phi` more likely than `P`).
        .min_by_key(|&(distance, candidate)| {
            let common = word
                .chars()
                .zip(candidate.to_lowercase().chars())
                .take_while(|(a, b)| a == b)
                .count();
            (distance, std::cmp::Reverse(common))
        })
        .map(|(_, candidate)| candidate)
}

/// Whether `candidate` is `word` with a letter replaced (not inserted,
/// removed or swapped): as long, other letters.
fn replaces_a_letter(word: &str, candidate: &str) -> bool {
    let sorted = |s: &str| {
        let mut c: Vec<char> = s.to_lowercase().chars().collect();
        c.sort_unstable();
        c
    };
    word.chars().count() == candidate.chars().count() && sorted(word) != sorted(candidate)
}

/// Optimal-string-alignment distance (Levenshtein plus adjacent swaps).
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut rows = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in rows.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in rows[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (rows[i - 1][j] + 1)
                .min(rows[i][j - 1] + 1)
                .min(rows[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(rows[i - 2][j - 2] + 1);
            }
            rows[i][j] = best;
        }
    }
    rows[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(line: usize, col: usize, len: usize) -> Span {
        Span::from_file(
            LineCol { line, col },
            LineCol {
                line,
                col: col + len,
            },
        )
    }

    /// `body C { rotat: 3 }` and its one error, with a help.
    fn misspelled_option() -> (SourceFile, Diagnostics) {
        let file = SourceFile::new("sat.sim", "model S;\nbody C { rotat: 3 }\n");
        let mut diags = Diagnostics::new();
        diags.push(
            Diagnostic::error(at(2, 10, 5), "unknown body option `rotat`")
                .help("did you mean `rotate`?"),
        );
        (file, diags)
    }

    #[test]
    fn renders_caret_under_span_with_help() {
        let (file, diags) = misspelled_option();
        let expect = "sat.sim:2:10: error: unknown body option `rotat`\n  |\n2 | body C { rotat: 3 }\n  |          ^^^^^\n  = help: did you mean `rotate`?\n";
        assert_eq!(diags.render(&file), expect);
    }

    #[test]
    fn renders_for_the_compiler_without_a_second_error_prefix() {
        let (file, mut diags) = misspelled_option();
        diags.error(Span::unknown(), "nowhere");
        let messages: Vec<String> = diags
            .to_syn_error_in(&file, proc_macro2::Span::call_site())
            .into_iter()
            .flatten()
            .map(|e| e.to_string())
            .collect();
        let expect = "unknown body option `rotat`\n --> sat.sim:2:10\n  |\n2 | body C { rotat: 3 }\n  |          ^^^^^\n  = help: did you mean `rotate`?";
        assert_eq!(
            messages,
            vec!["nowhere\n--> sat.sim".to_string(), expect.to_string()]
        );
    }

    #[test]
    fn renders_sorted_and_without_location() {
        let file = SourceFile::new("m.sim", "a\n\tb c\n");
        let mut diags = Diagnostics::new();
        diags.error(at(2, 4, 1), "second");
        diags.error(Span::unknown(), "nowhere");
        let out = diags.render(&file);
        assert!(out.starts_with("m.sim: error: nowhere\n"), "{out}");
        assert!(out.ends_with("2 | \tb c\n  | \t  ^\n"), "{out}");
    }

    #[test]
    fn suggestions() {
        let keys = [
            "parent",
            "joint",
            "translate",
            "rotate",
            "initial",
            "initial_speeds",
        ];
        assert_eq!(did_you_mean("rotat", keys), Some("rotate"));
        assert_eq!(did_you_mean("parnet", keys), Some("parent"));
        assert_eq!(did_you_mean("Joint", keys), Some("joint"));
        assert_eq!(did_you_mean("xyz", keys), None);
        assert_eq!(did_you_mean("Q", ["N", "B"]), None);
        assert_eq!(did_you_mean("w1", ["n1", "u1"]), None);
        assert_eq!(did_you_mean("B", ["b"]), Some("b"));
        assert_eq!(did_you_mean("wlx", ["w1x", "n1"]), Some("w1x"));
        assert_eq!(did_you_mean("kk", ["k", "m"]), Some("k"));
        assert_eq!(did_you_mean("1u", ["u1"]), Some("u1"));
        assert_eq!(did_you_mean("ph", ["P", "phi", "s"]), Some("phi"));
        assert_eq!(edit_distance("", "ab"), 2);
    }

    #[test]
    fn missing_file_is_a_diagnostic() {
        let result = SourceFile::read(Path::new("/nonexistent/x.sim"), "x.sim", Span::unknown());
        let diags = result
            .err()
            .map(|d| d.iter().map(|d| d.message.clone()).collect::<Vec<_>>());
        assert_eq!(
            diags,
            Some(vec!["model file `x.sim` not found".to_string()])
        );
    }

    #[test]
    fn syn_error_combines_all() {
        let mut diags = Diagnostics::new();
        diags.push(
            Diagnostic::error(Span::from_token(proc_macro2::Span::call_site()), "one").help("fix"),
        );
        diags.error(Span::unknown(), "two");
        let error = diags
            .to_syn_error()
            .map(|e| e.into_iter().map(|e| e.to_string()).collect::<Vec<_>>());
        // In source order: the one without a place first.
        assert_eq!(
            error,
            Some(vec!["two".to_string(), "one\n= help: fix".to_string()])
        );
    }

    #[test]
    fn token_spans_are_sorted_by_position() {
        use std::str::FromStr;
        let tokens = proc_macro2::TokenStream::from_str(
            "first
second",
        )
        .unwrap_or_default();
        let spans: Vec<Span> = tokens
            .into_iter()
            .map(|t| Span::from_token(t.span()))
            .collect();
        let mut diags = Diagnostics::new();
        diags.error(spans[1], "second");
        diags.error(spans[0], "first");
        let messages: Vec<String> = diags
            .to_syn_error()
            .into_iter()
            .flatten()
            .map(|e| e.to_string())
            .collect();
        assert_eq!(messages, ["first", "second"]);
        assert_eq!(spans[1].line(), Some(2));
    }
}

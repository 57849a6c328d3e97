//! The resolver's state: the system under construction, the names in scope,
//! lazily evaluated `let`s and points, and the diagnostics collected so far.

use super::value::Value;
use crate::diag::{Diagnostic, Diagnostics, Span, did_you_mean};
use crate::expr::{SymId, UserFnId};
use crate::mech::{BodyId, PointId, System};
use crate::syntax::ast;
use rustc_hash::FxHashMap;

/// What a name in a model refers to.
#[derive(Clone, Debug)]
pub(crate) enum Named {
    /// A scalar symbol (parameter, input, coordinate, speed, state, time,
    /// subroutine output).
    Symbol(SymId),
    /// A body (after bodies are added) or its AST index (before).
    Body(Option<BodyId>),
    /// A point, by index into the lazily resolved points.
    Point(usize),
    /// A `let`, by index.
    Let(usize),
    /// A user function.
    Function(UserFnId),
    /// An output (not referable in expressions).
    Output,
    /// A force or moment (not referable in expressions).
    Load,
    /// A user subroutine (its outputs are the names to use).
    Subroutine,
    /// A scalar fixed at compile time (the speed of a locked degree of
    /// freedom, zero).
    Constant(crate::expr::ExprId),
}

/// Lazy evaluation state of a `let` or a point.
#[derive(Clone, Debug)]
pub(crate) enum Lazy<T> {
    Pending,
    InProgress,
    Done(Option<T>),
}

/// The resolver.
pub(crate) struct Resolver<'a> {
    pub sys: System,
    pub diags: Diagnostics,
    pub names: FxHashMap<String, (Named, Span)>,
    pub lets: Vec<(&'a ast::Let, Lazy<Value>)>,
    pub points: Vec<(&'a ast::Point, Lazy<PointId>)>,
    /// Unit-vector shorthands like `b1` (lower-case body name and axis).
    pub uv_short: FxHashMap<String, (BodyId, crate::mech::Axis)>,
    /// The coordinate and speed names of bodies that could not be added
    /// (their error is reported): a use of one is no second mistake.
    pub names_of_failed_bodies: Vec<String>,
    /// A body that could not be added left its coordinates' and speeds'
    /// names to the defaults (`q<k>`, `u<k>`, `<Body>_e0`), whose numbers
    /// are unknown: a use of a name of that form is no second mistake.
    pub failed_body_with_default_names: bool,
    /// How many `let`s and points are being evaluated, one inside another
    /// (each evaluates what it uses first: see [`MAX_PENDING`]).
    pub pending: usize,
    /// Whether [`MAX_PENDING`] was reached (reported once).
    pub too_many_pending: bool,
    /// The use site's options.
    pub scene: super::Scene,
    /// Scene `small`/`lock` names that matched a body or coordinate.
    pub scene_matched: Vec<String>,
    /// Parameters declared by the compiler (a body's default mass and
    /// inertia), with the span of the body that needs them.
    pub implicit_parameters: Vec<(String, Span)>,
    /// The model's float type (constants must fit it).
    pub float: super::FloatType,
    /// Placeholders of the quantities known only once every item is
    /// resolved (reactions, potential energy, power).
    pub deferred: Vec<super::quantities::Deferred>,
    /// The expression of each constraint added to the system, as written
    /// (where its load acts is read from it when reactions need it).
    pub constraint_exprs: Vec<&'a ast::Expr>,
}

pub(crate) use crate::limits::{MAX_NESTING, MAX_PENDING};

/// Variants of Rust's prelude: a generated `let Some = ...` would be a
/// pattern, not a binding, so no model name may be one of them.
pub(crate) const PRELUDE_VARIANTS: [&str; 4] = ["Some", "None", "Ok", "Err"];

impl<'a> Resolver<'a> {
    pub fn new(name: &str) -> Resolver<'a> {
        let sys = System::new(name);
        let mut names = FxHashMap::default();
        names.insert(
            "t".to_string(),
            (Named::Symbol(sys.time()), Span::unknown()),
        );
        names.insert(
            "N".to_string(),
            (Named::Body(Some(BodyId::N)), Span::unknown()),
        );
        Resolver {
            sys,
            diags: Diagnostics::new(),
            names,
            lets: Vec::new(),
            points: Vec::new(),
            uv_short: FxHashMap::default(),
            names_of_failed_bodies: Vec::new(),
            failed_body_with_default_names: false,
            pending: 0,
            too_many_pending: false,
            scene: super::Scene::default(),
            scene_matched: Vec::new(),
            implicit_parameters: Vec::new(),
            float: super::FloatType::F64,
            deferred: Vec::new(),
            constraint_exprs: Vec::new(),
        }
    }

    pub fn error(&mut self, span: Span, message: impl Into<String>) {
        self.diags.push(Diagnostic::error(span, message));
    }

    pub fn push(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    /// Reports a name that is a variant of Rust's prelude.
    pub fn reserved_variant(&mut self, name: &ast::Name) {
        self.push(
            Diagnostic::error(
                name.span,
                format!(
                    "`{}` is reserved (a variant of Rust's `Option` or `Result`: generated code could not name a value so)",
                    name.text
                ),
            )
            .help(format!("choose another name, such as `{}`", name.text.to_lowercase())),
        );
    }

    /// Declares a name; reports a duplicate (pointing at both places).
    pub fn declare(&mut self, name: &ast::Name, what: Named) -> bool {
        if name.text == "t" || name.text == "N" || name.text == "pi" {
            self.push(
                Diagnostic::error(
                    name.span,
                    format!(
                        "`{}` is reserved ({})",
                        name.text,
                        match name.text.as_str() {
                            "t" => "time",
                            "pi" => "the constant π",
                            _ => "the inertial frame",
                        }
                    ),
                )
                .help("choose another name"),
            );
            return false;
        }
        if PRELUDE_VARIANTS.contains(&name.text.as_str()) {
            self.reserved_variant(name);
            return false;
        }
        if let Some((_, first)) = self.names.get(&name.text) {
            let first = *first;
            let mut d = Diagnostic::error(
                name.span,
                format!("the name `{}` is defined more than once", name.text),
            )
            .help("rename one of the definitions");
            if let Some(line) = first.line() {
                d = d.note(format!("first defined at line {line}"));
            }
            self.push(d);
            return false;
        }
        self.names.insert(name.text.clone(), (what, name.span));
        true
    }

    /// All names a user could have meant (for "did you mean").
    pub fn known_names(&self) -> Vec<String> {
        let mut v: Vec<String> = self
            .names
            .iter()
            .filter(|(_, (k, _))| !matches!(k, Named::Output | Named::Load | Named::Subroutine))
            .map(|(n, _)| n.clone())
            .collect();
        v.extend(self.uv_short.keys().cloned());
        v.sort();
        v
    }

    /// Whether `name` may be a coordinate or speed of a body that could
    /// not be added (its error says what is wrong).
    pub fn declared_by_failed_body(&self, name: &str) -> bool {
        let numbered = |prefix: char| {
            name.strip_prefix(prefix)
                .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
        };
        self.names_of_failed_bodies.iter().any(|n| n == name)
            || (self.failed_body_with_default_names
                && (numbered('q') || numbered('u') || name.ends_with("_e0")))
    }

    /// An "unknown name" diagnostic with a suggestion (none for a name a
    /// body declares that failed: that body's error says what is wrong).
    pub fn unknown(&mut self, name: &ast::Name, what: &str) {
        if self.declared_by_failed_body(&name.text) {
            return;
        }
        let known = self.known_names();
        let mut d = Diagnostic::error(name.span, format!("unknown {what} `{}`", name.text));
        if super::operations::is_function(&name.text) {
            d = d.help(format!(
                "`{0}` is a function: call it with its arguments, `{0}(...)` (the language reference's \"Expressions\")",
                name.text
            ));
        } else if let Some(s) = did_you_mean(&name.text, known.iter().map(String::as_str)) {
            d = d.help(format!("did you mean `{s}`?"));
        }
        if what == "name" && !super::operations::is_function(&name.text) {
            d = d.note(format!(
                "a name is declared (anywhere in the model) in `parameters {{ ... }}`, as `input {} [unit];`, or with `let`",
                name.text
            ));
        }
        self.push(d);
    }

    /// The body a name refers to, reporting if it is not one.
    pub fn body_by_name(&mut self, name: &ast::Name) -> Option<BodyId> {
        match self.names.get(&name.text).cloned() {
            Some((Named::Body(Some(b)), _)) => Some(b),
            Some((Named::Body(None), _)) => None,
            Some((other, _)) => {
                let what = describe(&other);
                self.push(
                    Diagnostic::error(name.span, format!("`{}` is {what}, not a body", name.text))
                        .help("name a body declared with `body`, or `N`"),
                );
                None
            }
            None => {
                self.unknown_of_kind(
                    name,
                    "body",
                    |k| matches!(k, Named::Body(_)),
                    format!(
                        "declare it with `body {} {{ ... }}`, or use `N` for the inertial frame",
                        name.text
                    ),
                );
                None
            }
        }
    }

    /// True when `name` refers to nothing: not declared, not a unit vector.
    pub fn is_undeclared(&self, name: &ast::Name) -> bool {
        !self.names.contains_key(&name.text) && !self.uv_short.contains_key(&name.text)
    }

    /// "unknown {what} `x`" where a `what` is expected, suggesting only names
    /// that `fits` accepts (a point is not suggested where a body is
    /// needed), else giving `otherwise` as help.
    pub fn unknown_of_kind(
        &mut self,
        name: &ast::Name,
        what: &str,
        fits: fn(&Named) -> bool,
        otherwise: String,
    ) {
        if self.declared_by_failed_body(&name.text) {
            return;
        }
        let mut candidates: Vec<&str> = self
            .names
            .iter()
            .filter(|(_, (k, _))| fits(k))
            .map(|(n, _)| n.as_str())
            .collect();
        candidates.sort_unstable();
        let d = Diagnostic::error(name.span, format!("unknown {what} `{}`", name.text));
        let d = match did_you_mean(&name.text, candidates) {
            Some(s) => d.help(format!("did you mean `{s}`?")),
            None => d.help(otherwise),
        };
        self.push(d);
    }
}

/// "a parameter", "a point", ... for messages.
pub(crate) fn describe(n: &Named) -> &'static str {
    match n {
        Named::Symbol(_) | Named::Constant(_) => "a scalar",
        Named::Body(_) => "a body",
        Named::Point(_) => "a point",
        Named::Let(_) => "a `let` value",
        Named::Function(_) => "a function",
        Named::Output => "an output",
        Named::Load => "a force or moment",
        Named::Subroutine => "a subroutine",
    }
}

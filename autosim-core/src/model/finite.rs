//! Constants that are not finite: reported where they are written.
//!
//! Folding numbers is exact while it can be, but `2^100000` overflows,
//! `sqrt(-1)` and `ln(0)` have no real value, and a value beyond `f32`'s
//! range becomes infinity in an `f32` model. Each value the resolver builds
//! is checked as it is built, so the innermost such constant is reported,
//! with its span, before it can reach the generated code.

use super::FloatType;
use super::scope::Resolver;
use super::value::Value;
use crate::diag::{Diagnostic, Span};
use crate::expr::{ExprId, Node};

impl Resolver<'_> {
    /// `v`, or `None` after reporting it at `span` if it is a constant whose
    /// value is not finite (or not finite in the model's float type).
    pub(super) fn finite(&mut self, span: Span, v: Option<Value>) -> Option<Value> {
        let Some(Value::Scalar(e)) = v else {
            return v;
        };
        let Some(x) = self.sys.arena.numeric_value(e) else {
            return v;
        };
        if x.is_finite() {
            if self.float == FloatType::F32 && (x as f32).is_infinite() {
                self.push(
                    Diagnostic::error(
                        span,
                        format!(
                            "this constant, {x:e}, is beyond the range of `f32` (about 3.4e38)"
                        ),
                    )
                    .note("the model computes in `f32` (`float: f32`), where it would be infinite")
                    .help("rescale the quantity (other units), or compute in `f64`"),
                );
                return None;
            }
            return v;
        }
        let arena = &self.sys.arena;
        let what = match (x.is_nan(), arena.node(e)) {
            (true, _) => "is not a real number",
            (false, Node::Func(..)) => "is infinite",
            (false, _) => "is infinite (beyond the largest float, about 1.8e308)",
        };
        let subject = match arena.node(e) {
            Node::Func(f, _) => format!(
                "`{}` of {}",
                f.builtin_name().unwrap_or("the function"),
                self.argument_text(e)
            ),
            Node::Pow(b, p) => match arena.numeric_value(*p) {
                Some(0.5) => format!("`sqrt` of {}", self.value_text(*b)),
                Some(p) => format!("{} to the power {p}", self.value_text(*b)),
                None => format!("a power of {}", self.value_text(*b)),
            },
            _ => "this constant".to_string(),
        };
        self.push(
            Diagnostic::error(span, format!("{subject} {what}"))
                .note("constants are folded at compile time; generated code would compute NaN or infinity here")
                .help("check the argument's sign and size: sqrt and ln of negative numbers, ln(0), asin and acos outside [-1, 1], powers too large"),
        );
        None
    }

    /// The arguments of a call of numbers, as written in a message.
    fn argument_text(&self, e: ExprId) -> String {
        let Node::Func(_, args) = self.sys.arena.node(e) else {
            return String::new();
        };
        let values: Vec<String> = args.iter().map(|a| self.value_text(*a)).collect();
        values.join(" and ")
    }

    /// A constant's value as written in a message.
    fn value_text(&self, e: ExprId) -> String {
        match self.sys.arena.numeric_value(e) {
            Some(x) => format!("{x}"),
            None => "?".to_string(),
        }
    }
}

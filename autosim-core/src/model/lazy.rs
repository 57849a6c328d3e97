//! `let`s and points are evaluated on first use (names may be used before
//! they are declared), within limits: how many may wait on one another,
//! and how deep their values may nest.

use super::scope::{Lazy, MAX_NESTING, MAX_PENDING, Resolver};
use super::value::Value;
use crate::diag::{Diagnostic, Span};
use crate::mech::PointId;
use crate::syntax::ast;

impl Resolver<'_> {
    /// The value of `let` number `i`, evaluated on first use.
    pub fn let_value(&mut self, i: usize, at: Span) -> Option<Value> {
        match &self.lets[i].1 {
            Lazy::Done(v) => v.clone(),
            Lazy::InProgress => {
                let name = self.lets[i].0.name.text.clone();
                self.push(
                    Diagnostic::error(at, format!("`{name}` is defined in terms of itself"))
                        .help("a `let` cannot refer to itself, directly or through other `let`s"),
                );
                self.lets[i].1 = Lazy::Done(None);
                None
            }
            Lazy::Pending => {
                let item = self.lets[i].0;
                if !self.may_wait(&item.name, at) {
                    self.lets[i].1 = Lazy::Done(None);
                    return None;
                }
                self.lets[i].1 = Lazy::InProgress;
                self.pending += 1;
                let v = self.eval(&item.value);
                self.pending -= 1;
                let v = v.filter(|v| {
                    let depth = value_depth(&self.sys.arena, v);
                    self.shallow_enough(depth, &item.name)
                });
                self.lets[i].1 = Lazy::Done(v.clone());
                v
            }
        }
    }

    /// The point number `i`, created on first use.
    pub fn point_value(&mut self, i: usize, at: Span) -> Option<PointId> {
        match &self.points[i].1 {
            Lazy::Done(p) => *p,
            Lazy::InProgress => {
                let name = self.points[i].0.name.text.clone();
                self.push(
                    Diagnostic::error(
                        at,
                        format!("the coordinates of point `{name}` depend on the point itself"),
                    )
                    .help("a point's coordinates cannot refer to that point"),
                );
                self.points[i].1 = Lazy::Done(None);
                None
            }
            Lazy::Pending => {
                let item = self.points[i].0;
                if !self.may_wait(&item.name, at) {
                    self.points[i].1 = Lazy::Done(None);
                    return None;
                }
                self.points[i].1 = Lazy::InProgress;
                self.pending += 1;
                let p = self.make_point(item);
                self.pending -= 1;
                self.points[i].1 = Lazy::Done(p);
                p
            }
        }
    }

    /// False (reported at `at`, where `name` is used) when too many `let`s
    /// and points already wait on one another.
    fn may_wait(&mut self, name: &ast::Name, at: Span) -> bool {
        if self.pending < MAX_PENDING {
            return true;
        }
        if std::mem::replace(&mut self.too_many_pending, true) {
            return false;
        }
        self.push(
            Diagnostic::error(
                at,
                format!(
                    "`{}` is used through more than {MAX_PENDING} `let`s or points that are defined after their first use",
                    name.text
                ),
            )
            .help("define each `let` and point before the items that use it"),
        );
        false
    }

    /// False (reported at `name`) when the value of `name` nests deeper
    /// than [`MAX_NESTING`].
    fn shallow_enough(&mut self, depth: u32, name: &ast::Name) -> bool {
        if depth <= MAX_NESTING {
            return true;
        }
        self.push(
            Diagnostic::error(
                name.span,
                format!(
                    "`{}` nests operations more than {MAX_NESTING} deep, through the `let`s and points it uses",
                    name.text
                ),
            )
            .help("shorten the chain of `let`s and points that defines it, or compute it in user code (`extern fn`)"),
        );
        false
    }

    fn make_point(&mut self, item: &ast::Point) -> Option<PointId> {
        let body = self.body_by_name(&item.body);
        let coords = self.list3(&item.at, "the coordinates of a point", false);
        let (body, coords) = (body?, coords?);
        let depth = coords.iter().map(|c| self.sys.arena.depth(*c)).max();
        if !self.shallow_enough(depth.unwrap_or(0), &item.name) {
            return None;
        }
        match self.sys.add_point(&item.name.text, body, coords) {
            Ok(p) => {
                if let Some(label) = &item.label {
                    self.sys.describe_point(p, &label.text);
                }
                Some(p)
            }
            Err(e) => {
                self.error(item.name.span, e.to_string());
                None
            }
        }
    }
}

/// The deepest expression in a value (see `Arena::depth`).
fn value_depth(arena: &crate::expr::Arena, v: &Value) -> u32 {
    match v {
        Value::Scalar(s) => arena.depth(*s),
        Value::Vector(v) => v
            .terms()
            .iter()
            .map(|(_, c)| arena.depth(*c))
            .max()
            .unwrap_or(0),
        Value::Dyadic(d) => d
            .terms()
            .iter()
            .map(|(_, c)| arena.depth(*c))
            .max()
            .unwrap_or(0),
        Value::List(items) => items
            .iter()
            .map(|x| value_depth(arena, x))
            .max()
            .unwrap_or(0),
        Value::Point(_) | Value::Body(_) => 0,
    }
}

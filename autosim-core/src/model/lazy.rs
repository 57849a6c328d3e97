//! `let`s and points are evaluated on first use (names may be used before
//! they are declared), within limits: how many may wait on one another,
//! and how deep their values may nest.

use super::scope::{Lazy, MAX_NESTING, MAX_PENDING, Resolver};
use super::value::Value;
use crate::diag::{Diagnostic, Span};
use crate::mech::PointId;
use crate::syntax::ast;

/// Where a lazily evaluated item stands, read before acting on it.
enum Step<T> {
    Done(Option<T>),
    Cycle,
    Start,
}

/// Items of one kind with their state.
type LazyList<'a, I, T> = Vec<(&'a I, Lazy<T>)>;

/// One kind of lazily evaluated item (`let`s, points): where its list is,
/// its name, and the message and fix when it is used in its own definition.
struct LazyKind<'a, I, T> {
    list: for<'r> fn(&'r mut Resolver<'a>) -> &'r mut LazyList<'a, I, T>,
    name: fn(&I) -> &ast::Name,
    cycle: fn(&str) -> (String, &'static str),
}

impl<'a> Resolver<'a> {
    /// The value of `let` number `i`, evaluated on first use.
    pub fn let_value(&mut self, i: usize, at: Span) -> Option<Value> {
        let lets = LazyKind {
            list: |r| &mut r.lets,
            name: |item: &ast::Let| &item.name,
            cycle: |name| {
                (
                    format!("`{name}` is defined in terms of itself"),
                    "a `let` cannot refer to itself, directly or through other `let`s",
                )
            },
        };
        self.lazily(i, at, lets, |r, item| {
            let v = r.eval(&item.value);
            v.filter(|v| {
                let depth = value_depth(&r.sys.arena, v);
                r.shallow_enough(depth, &item.name)
            })
        })
    }

    /// The point number `i`, created on first use.
    pub fn point_value(&mut self, i: usize, at: Span) -> Option<PointId> {
        let points = LazyKind {
            list: |r| &mut r.points,
            name: |item: &ast::Point| &item.name,
            cycle: |name| {
                (
                    format!("the coordinates of point `{name}` depend on the point itself"),
                    "a point's coordinates cannot refer to that point",
                )
            },
        };
        self.lazily(i, at, points, Self::make_point)
    }

    /// Item `i` of `kind`, made by `make` on first use (used at `at`): a
    /// use inside its own definition is reported, and so is a use through
    /// too many items waiting on one another.
    fn lazily<I, T: Clone>(
        &mut self,
        i: usize,
        at: Span,
        kind: LazyKind<'a, I, T>,
        make: impl FnOnce(&mut Self, &'a I) -> Option<T>,
    ) -> Option<T> {
        let (item, step) = {
            let (item, state) = &(kind.list)(self)[i];
            let step = match state {
                Lazy::Done(v) => Step::Done(v.clone()),
                Lazy::InProgress => Step::Cycle,
                Lazy::Pending => Step::Start,
            };
            (*item, step)
        };
        let name = (kind.name)(item);
        let value = match step {
            Step::Done(v) => return v,
            Step::Cycle => {
                let (message, help) = (kind.cycle)(&name.text);
                self.push(Diagnostic::error(at, message).help(help));
                None
            }
            Step::Start if !self.may_wait(name, at) => None,
            Step::Start => {
                (kind.list)(self)[i].1 = Lazy::InProgress;
                self.pending += 1;
                let v = make(self, item);
                self.pending -= 1;
                v
            }
        };
        (kind.list)(self)[i].1 = Lazy::Done(value.clone());
        value
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

    fn make_point(&mut self, item: &'a ast::Point) -> Option<PointId> {
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

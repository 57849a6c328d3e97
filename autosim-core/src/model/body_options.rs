//! Reading body options written in the language into the typed values of
//! a [`BodySpec`](crate::mech::BodySpec): axis numbers, translation
//! directions, inertia matrices, lists of constants and names, and the
//! `small`/`lock` flags. What can only be said of the text (an axis `4`, a
//! `diag` with two arguments) is reported here, with its span; everything
//! about the body itself is checked once, by `mech`.

use super::scope::Resolver;
use crate::diag::{Diagnostic, did_you_mean};
use crate::expr::ExprId;
use crate::mech::{Axis, Direction, Joint, Mat3};
use crate::syntax::ast::Expr;

/// The items of a list value, or the value alone.
pub(super) fn items(v: &Expr) -> Vec<&Expr> {
    match v {
        Expr::List { items, .. } => items.iter().collect(),
        other => vec![other],
    }
}

impl Resolver<'_> {
    /// Rotation axes `3` or `[1, 2, 3]`, each 1, 2 or 3.
    pub(super) fn axes(&mut self, v: &Expr, what: &str) -> Option<Vec<Axis>> {
        let mut out = Vec::new();
        let mut ok = true;
        for it in items(v) {
            match self.axis(it, what, "axes are 1, 2 or 3") {
                Some(axis) => out.push(axis),
                None => ok = false,
            }
        }
        ok.then_some(out)
    }

    /// An axis number, 1, 2 or 3 (`help` says what the others mean).
    fn axis(&mut self, it: &Expr, what: &str, help: &str) -> Option<Axis> {
        // `x`, `y`, `z` (any case): the number it means; a misspelt
        // `quaternion`: that.
        if let Expr::Name(n) = it {
            let letter = ["x", "y", "z"]
                .iter()
                .position(|a| n.text.eq_ignore_ascii_case(a));
            if let Some(k) = letter {
                let message = format!("{what} is a number: `{}` is axis {}", n.text, k + 1);
                self.push(Diagnostic::error(it.span(), message).help(help));
                return None;
            }
            if did_you_mean(&n.text, ["quaternion"]).is_some() {
                let message = format!("unknown rotation `{}`", n.text);
                let d = Diagnostic::error(it.span(), message).help("did you mean `quaternion`?");
                self.push(d);
                return None;
            }
        }
        let a = self.integer(it, what)?;
        let axis = Axis::number(a);
        if axis.is_none() {
            self.push(Diagnostic::error(it.span(), format!("axis {a} is out of range")).help(help));
        }
        axis
    }

    /// Translations: axis numbers of the parent or constant directions
    /// `[x, y, z]`.
    pub(super) fn translations(&mut self, v: &Expr) -> Option<Vec<Direction>> {
        let mut out = Vec::new();
        let mut ok = true;
        for it in items(v) {
            match it {
                Expr::List { .. } => match self.list3(it, "a translation direction", true) {
                    Some(c) => out.push(Direction::Vector(c)),
                    None => ok = false,
                },
                other => {
                    let help = "translate along axis 1, 2 or 3, or a direction `[x, y, z]`";
                    match self.axis(other, "a translation axis", help) {
                        Some(axis) => out.push(Direction::Axis(axis)),
                        None => ok = false,
                    }
                }
            }
        }
        ok.then_some(out)
    }

    /// `0`, `diag(a, b, c)`, `[a, b, c]` or a 3×3 matrix of constants.
    pub(super) fn inertia(&mut self, v: &Expr) -> Option<Mat3> {
        let zero = self.sys.arena.zero();
        let diagonal =
            |d: Vec<ExprId>| [[d[0], zero, zero], [zero, d[1], zero], [zero, zero, d[2]]];
        match v {
            Expr::Call { func, args, .. } if func.text == "diag" => {
                if args.len() != 3 {
                    self.push(
                        Diagnostic::error(
                            func.span,
                            format!(
                                "`diag` takes 3 arguments, but {} {} given",
                                args.len(),
                                if args.len() == 1 { "was" } else { "were" }
                            ),
                        )
                        .help("write `diag(I11, I22, I33)`, the moments of inertia about the body's axes 1, 2 and 3"),
                    );
                    return None;
                }
                self.constants(args, "an inertia").map(diagonal)
            }
            Expr::List { items, span } => {
                if items.len() != 3 {
                    self.push(
                        Diagnostic::error(*span, "an inertia matrix needs 3 rows (or 3 diagonal entries)")
                            .help("write `diag(I11, I22, I33)` or `[[I11, I12, I13], [I12, I22, I23], [I13, I23, I33]]`"),
                    );
                    return None;
                }
                if items.iter().all(|r| matches!(r, Expr::List { .. })) {
                    let mut m = [[zero; 3]; 3];
                    for (i, row) in items.iter().enumerate() {
                        m[i] = self.list3(row, "a row of the inertia matrix", true)?;
                    }
                    Some(m)
                } else {
                    self.constants(items, "an inertia").map(diagonal)
                }
            }
            other => {
                let s = self.constant(other, "the inertia")?;
                if self.sys.arena.is_zero(s) {
                    Some([[zero; 3]; 3])
                } else {
                    self.push(Diagnostic::error(
                        other.span(),
                        "the inertia must be `0`, `diag(a, b, c)`, `[a, b, c]` or a 3×3 matrix",
                    ));
                    None
                }
            }
        }
    }

    /// Constants, all evaluated (every mistake reported).
    pub(super) fn constants(&mut self, items: &[Expr], what: &str) -> Option<Vec<ExprId>> {
        let mut out = Vec::new();
        let mut ok = true;
        for it in items {
            match self.constant(it, what) {
                Some(x) => out.push(x),
                None => ok = false,
            }
        }
        ok.then_some(out)
    }

    /// A list of constants, or one.
    pub(super) fn constants_list(&mut self, v: &Expr, what: &str) -> Option<Vec<ExprId>> {
        match v {
            Expr::List { items, .. } => self.constants(items, what),
            other => self.constant(other, what).map(|x| vec![x]),
        }
    }

    /// A list of new names (coordinate or speed names).
    pub(super) fn names_list(&mut self, v: &Expr, what: &str) -> Option<Vec<String>> {
        let mut out = Vec::new();
        let mut ok = true;
        for it in items(v) {
            match it {
                Expr::Name(n) if n.text == "t" || n.text == "N" => {
                    self.push(
                        Diagnostic::error(n.span, format!("`{}` is reserved", n.text))
                            .help("choose another name"),
                    );
                    ok = false;
                }
                Expr::Name(n) if super::scope::PRELUDE_VARIANTS.contains(&n.text.as_str()) => {
                    self.reserved_variant(n);
                    ok = false;
                }
                Expr::Name(n) => {
                    if self.names.contains_key(&n.text) || out.contains(&n.text) {
                        self.push(
                            Diagnostic::error(
                                n.span,
                                format!("the name `{}` is defined more than once", n.text),
                            )
                            .help("rename one of the definitions"),
                        );
                        ok = false;
                    }
                    out.push(n.text.clone());
                }
                other => {
                    self.error(other.span(), format!("{what} must be plain names"));
                    ok = false;
                }
            }
        }
        ok.then_some(out)
    }

    /// `small` or `lock`: `all | none | translations | rotations | [...,
    /// coordinate names]`, one flag per degree of freedom of `joint`.
    pub(super) fn dof_flags(
        &mut self,
        v: &Expr,
        body: &str,
        joint: &Joint,
        coordinate_names: &[String],
    ) -> Option<Vec<bool>> {
        let nt = joint.translations.len();
        let mut flags = vec![false; joint.dofs()];
        let mut ok = true;
        for it in items(v) {
            let Expr::Name(n) = it else {
                self.error(
                    it.span(),
                    "`small` and `lock` take `all`, `none`, `translations`, `rotations` or coordinate names",
                );
                ok = false;
                continue;
            };
            match n.text.as_str() {
                "all" => flags.iter_mut().for_each(|f| *f = true),
                "none" => {}
                "translations" => flags[..nt].iter_mut().for_each(|f| *f = true),
                "rotations" | "angles" => flags[nt..].iter_mut().for_each(|f| *f = true),
                other => match coordinate_names
                    .iter()
                    .position(|x| x == other)
                    .and_then(|k| joint.speed_of_coordinate(k))
                {
                    Some(k) => flags[k] = true,
                    None => {
                        self.push(
                            Diagnostic::error(n.span, format!("`{other}` is not a coordinate of body `{body}`"))
                                .help("use `all`, `none`, `translations`, `rotations`, or a name from the body's `q: [...]`"),
                        );
                        ok = false;
                    }
                },
            }
        }
        ok.then_some(flags)
    }
}

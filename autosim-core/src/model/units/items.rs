//! What each item's expressions must be: a body's mass in kg, a force in
//! N, a moment in N m, gravity in m/s^2, a state's derivative in its unit
//! per second, an output or constraint in its declared unit; and the
//! units declared (a unit with a factor only where a number is written).

use super::check::{Checker, Measure, Signature, unit_dim};
use super::dim::Dim;
use super::infer::Affine;
use crate::model::scope::Named;
use crate::syntax::ast::{
    self, BodyKey, ConstraintKey, Expr, ForceKey, Item, MomentKey, MotionKey, StateKey,
};

/// The dimension needed, and how messages name the place.
struct Need<'a>(&'a str, &'a str);

impl Checker<'_, '_> {
    /// Reads the user functions' declared units.
    pub fn signatures(&mut self, model: &ast::Model) {
        for item in &model.items {
            let Item::ExternFn(f) = item else { continue };
            let args = f
                .param_units
                .iter()
                .map(|u| u.as_ref().and_then(|u| self.meaning(u, false)))
                .collect();
            let result = match &f.result_unit {
                Some(u) => self.meaning(u, false).unwrap_or(Dim::ONE),
                None => Dim::ONE,
            };
            self.signatures
                .insert(f.name.text.clone(), Signature { args, result });
        }
    }

    /// Checks one item; `inferred` receives the dimension of an output or
    /// constraint declared without a unit.
    pub fn item(&mut self, item: &Item, inferred: &mut Vec<(String, Affine)>) {
        match item {
            Item::Parameters(ps) => {
                for p in &ps.params {
                    if let Some(u) = &p.unit {
                        self.meaning(u, true);
                    }
                }
            }
            Item::Inputs(is) | Item::Discrete(is) => {
                for i in is.inputs.iter().filter_map(|i| i.unit.as_ref()) {
                    self.meaning(i, false);
                }
            }
            Item::ExternSub(sub) => {
                for a in &sub.args {
                    self.expr(a);
                }
                for u in sub.outputs.iter().filter_map(|o| o.unit.as_ref()) {
                    self.meaning(u, false);
                }
            }
            Item::Body(b) => self.body(b),
            Item::Point(p) => {
                let q = self.expr(&p.at);
                self.need(q, &p.at, Need("m", "the coordinates of a point"));
            }
            Item::Let(l) => {
                if let Some((Named::Let(i), _)) = self.r.names.get(&l.name.text) {
                    self.let_quantity(*i);
                }
            }
            Item::Gravity(g) => {
                let q = self.expr(&g.value);
                self.need(q, &g.value, Need("m/s^2", "gravity"));
            }
            Item::Force(f) => self.load(
                (
                    f.options.get(ForceKey::Vector),
                    f.options.get(ForceKey::Along),
                ),
                f.options.get(ForceKey::Magnitude),
                ("N", "a force"),
            ),
            Item::Moment(m) => self.load(
                (
                    m.options.get(MomentKey::Vector),
                    m.options.get(MomentKey::About),
                ),
                m.options.get(MomentKey::Magnitude),
                ("N m", "a moment"),
            ),
            Item::State(s) => self.state(s),
            Item::Output(o) => {
                let q = self.expr(&o.value);
                self.declared(
                    q,
                    o.unit.as_ref(),
                    &o.value,
                    &o.name.text,
                    inferred,
                    "the output",
                );
            }
            Item::Constraint(c) => {
                let value = c
                    .options
                    .get(ConstraintKey::Position)
                    .or(c.options.get(ConstraintKey::Speed));
                if let Some(v) = value {
                    let q = self.expr(&v.value);
                    self.declared(
                        q,
                        c.unit.as_ref(),
                        &v.value,
                        &c.name.text,
                        inferred,
                        "the constraint",
                    );
                }
            }
            Item::Motion(m) => self.motion(m),
            Item::Event(e) => self.event(e, inferred),
            Item::Settings(_) | Item::ExternFn(_) => {}
        }
    }

    /// Reports unless `q` is in the unit `unit`.
    fn need(&mut self, q: Measure, e: &Expr, Need(unit, what): Need<'_>) {
        self.require(q, unit_dim(unit), e, what);
    }

    /// An output's or constraint's value against its declared unit, or
    /// its dimension recorded for the documentation.
    fn declared(
        &mut self,
        q: Measure,
        unit: Option<&ast::Unit>,
        e: &Expr,
        name: &str,
        inferred: &mut Vec<(String, Affine)>,
        what: &str,
    ) {
        // An output is converted to its declared unit; a constraint's
        // residual is not.
        let factor_allowed = what == "the output";
        match unit {
            Some(u) => {
                if let Some(dim) = self.meaning(u, factor_allowed) {
                    self.require(q, dim, e, &format!("{what} `{name}` [{}]", u.text));
                }
            }
            None => {
                if let Measure::Dim(a) = q {
                    inferred.push((name.to_string(), a));
                }
            }
        }
    }

    fn body(&mut self, b: &ast::Body) {
        let get = |k: BodyKey| b.options.get(k).map(|o| &o.value);
        if let Some(e) = get(BodyKey::Mass) {
            let q = self.expr(e);
            self.need(q, e, Need("kg", "a mass"));
        }
        if let Some(e) = get(BodyKey::Inertia) {
            let entries: Vec<&Expr> = match e {
                Expr::Call { args, .. } => args.iter().collect(),
                other => vec![other],
            };
            for e in entries {
                let q = self.expr(e);
                self.need(q, e, Need("kg m^2", "an inertia"));
            }
        }
        for (key, what) in [
            (BodyKey::Cm, "a mass center"),
            (BodyKey::Joint, "a joint point"),
        ] {
            if let Some(e) = get(key) {
                let q = self.expr(e);
                self.need(q, e, Need("m", what));
            }
        }
        let translations = match get(BodyKey::Translate) {
            Some(Expr::List { items, .. }) => items.len(),
            Some(_) => 1,
            None => 0,
        };
        for (key, (m, rad), what) in [
            (BodyKey::Initial, ("m", "rad"), "an initial coordinate"),
            (BodyKey::InitialSpeeds, ("m/s", "rad/s"), "an initial speed"),
        ] {
            let Some(e) = get(key) else { continue };
            let items: Vec<&Expr> = match e {
                Expr::List { items, .. } => items.iter().collect(),
                other => vec![other],
            };
            for (k, e) in items.into_iter().enumerate() {
                let unit = if k < translations { m } else { rad };
                let q = self.expr(e);
                self.need(q, e, Need(unit, what));
            }
        }
    }

    /// A force or moment: `vector` in `unit`, or `along`/`about` times
    /// `magnitude` in `unit`.
    fn load(
        &mut self,
        (vector, direction): (Option<&ast::Opt<impl Copy>>, Option<&ast::Opt<impl Copy>>),
        magnitude: Option<&ast::Opt<impl Copy>>,
        (unit, what): (&str, &str),
    ) {
        if let Some(v) = vector {
            let q = self.expr(&v.value);
            self.need(q, &v.value, Need(unit, &format!("{what}'s vector")));
        }
        let Some(m) = magnitude else { return };
        let d = direction.map(|d| self.expr(&d.value));
        let need = match d {
            Some(Measure::Dim(ref a)) => Affine::known(unit_dim(unit)).over(a),
            _ => Some(Affine::known(unit_dim(unit))),
        };
        let q = self.expr(&m.value);
        let Some(need) = need else { return };
        if self.require_affine(q, &need, &m.value, &format!("the magnitude of {what}")) {
            return;
        }
        // A direction with a unit scales the load: say so, lest `as` be
        // put on the magnitude where the direction is what is wrong.
        let direction_unit = match &d {
            Some(Measure::Dim(a)) => self.solver.known(a).filter(|u| *u != Dim::ONE),
            _ => None,
        };
        if let Some(u) = direction_unit
            && let Some(diagnostic) = self.diags.pop()
        {
            let key = if what == "a moment" { "about" } else { "along" };
            self.diags.push(diagnostic.note(format!(
                "`{key}` is in {u}, not a unit vector: {what} is `{key}` times `magnitude`, so the magnitude's unit is {unit} per {u}; for a direction, write `{key}: dir(...)`"
            )));
        }
    }

    fn state(&mut self, s: &ast::State) {
        let Some((Named::Symbol(sym), _)) = self.r.names.get(&s.name.text) else {
            return;
        };
        if let Some(u) = &s.unit {
            self.meaning(u, false);
        }
        let Measure::Dim(dim) = self.symbol(*sym) else {
            return;
        };
        if let Some(o) = s.options.get(StateKey::Initial) {
            let q = self.expr(&o.value);
            let what = format!("the initial value of `{}`", s.name.text);
            self.require_affine(q, &dim, &o.value, &what);
        }
        if let Some(o) = s.options.get(StateKey::Derivative)
            && let Some(rate) = dim.over(&Affine::known(unit_dim("s")))
        {
            let q = self.expr(&o.value);
            let what = format!("the derivative of `{}`", s.name.text);
            self.require_affine(q, &rate, &o.value, &what);
        }
    }

    /// An event: its indicator in its declared unit, each new value in
    /// the unit of the variable it is assigned to.
    fn event(&mut self, e: &ast::Event, inferred: &mut Vec<(String, Affine)>) {
        if let Some(o) = e.options.get(ast::EventKey::Indicator) {
            let q = self.expr(&o.value);
            let what = "the indicator of event";
            self.declared(q, e.unit.as_ref(), &o.value, &e.name.text, inferred, what);
        }
        let lists = [&e.set, &e.reset];
        for a in lists.into_iter().flatten().flat_map(|(_, list)| list) {
            let q = self.expr(&a.value);
            let Some((Named::Symbol(s), _)) = self.r.names.get(&a.target.text) else {
                continue;
            };
            if let Measure::Dim(dim) = self.symbol(*s) {
                let what = format!("the new value of `{}`", a.target.text);
                self.require_affine(q, &dim, &a.value, &what);
            }
        }
    }

    fn motion(&mut self, m: &ast::Motion) {
        let (Some(c), Some(v)) = (
            m.options.get(MotionKey::Coordinate),
            m.options.get(MotionKey::Value),
        ) else {
            return;
        };
        let q = self.expr(&v.value);
        let Expr::Name(n) = &c.value else { return };
        let Some((Named::Symbol(s), _)) = self.r.names.get(&n.text) else {
            return;
        };
        if let Measure::Dim(dim) = self.symbol(*s) {
            let what = format!("the motion of `{}`", n.text);
            self.require_affine(q, &dim, &v.value, &what);
        }
    }
}

//! `body` items: parents ordered and checked (unknown parents, cycles), and
//! each body's options turned into a [`BodySpec`].

use super::scope::{Named, Resolver};
use crate::diag::Diagnostic;
use crate::expr::ExprId;
use crate::mech::{BodySpec, Direction, Mat3};
use crate::syntax::ast::{self, BodyKey, Expr};

impl<'a> Resolver<'a> {
    /// Adds all bodies, parents first.
    pub fn add_bodies(&mut self, bodies: &[&'a ast::Body]) {
        // A body whose name is refused (reported) is not added.
        let declared: Vec<bool> = bodies
            .iter()
            .map(|b| self.declare(&b.name, Named::Body(None)))
            .collect();
        // Parent of each body (index into `bodies`, or None for N/unknown).
        let mut parent_of: Vec<Option<usize>> = vec![None; bodies.len()];
        let mut parent_ok = declared;
        for (i, b) in bodies.iter().enumerate() {
            let Some(opt) = b.options.get(BodyKey::Parent) else {
                continue;
            };
            let Expr::Name(p) = &opt.value else {
                self.error(
                    opt.value.span(),
                    "`parent` must be the name of a body (or `N`)",
                );
                parent_ok[i] = false;
                continue;
            };
            if p.text == "N" {
                continue;
            }
            match bodies.iter().position(|x| x.name.text == p.text) {
                Some(j) => parent_of[i] = Some(j),
                None => {
                    self.body_by_name(p);
                    parent_ok[i] = false;
                }
            }
        }
        // Order parents first; the rest is on (or below) a cycle.
        let mut placed = vec![false; bodies.len()];
        let mut order = Vec::with_capacity(bodies.len());
        loop {
            let mut progress = false;
            for i in 0..bodies.len() {
                if !placed[i] && parent_of[i].is_none_or(|j| placed[j]) {
                    placed[i] = true;
                    order.push(i);
                    progress = true;
                }
            }
            if !progress {
                break;
            }
        }
        let mut reported = vec![false; bodies.len()];
        for start in 0..bodies.len() {
            if placed[start] || reported[start] {
                continue;
            }
            let mut path: Vec<usize> = Vec::new();
            let mut cur = Some(start);
            while let Some(i) = cur {
                if let Some(pos) = path.iter().position(|p| *p == i) {
                    let cycle: Vec<usize> = path[pos..].to_vec();
                    if !cycle.iter().any(|k| reported[*k]) {
                        let names: Vec<String> = cycle
                            .iter()
                            .chain(std::iter::once(&cycle[0]))
                            .map(|k| format!("`{}`", bodies[*k].name.text))
                            .collect();
                        let first = bodies[cycle[0]];
                        let span = first
                            .options
                            .get(BodyKey::Parent)
                            .map(|o| o.value.span())
                            .unwrap_or(first.name.span);
                        self.push(
                            Diagnostic::error(
                                span,
                                format!(
                                    "the parents of bodies form a cycle: {}",
                                    names.join(" -> ")
                                ),
                            )
                            .help("every chain of parents must end at `N`"),
                        );
                    }
                    break;
                }
                path.push(i);
                cur = parent_of[i];
            }
            for k in path {
                reported[k] = true;
            }
        }
        for i in order {
            if !parent_ok[i] {
                continue;
            }
            let b = bodies[i];
            let parent = parent_of[i].map_or("N".to_string(), |j| bodies[j].name.text.clone());
            if self.sys.body_named(&parent).is_none() {
                continue; // the parent failed; already reported
            }
            let Some(spec) = self.body_spec(b, parent) else {
                continue;
            };
            let parameters_before = self.sys.parameters().len();
            match self.sys.add_body(spec) {
                Ok(id) => {
                    for &p in &self.sys.parameters()[parameters_before..] {
                        let name = self.sys.arena.symbol(p).name.clone();
                        self.implicit_parameters.push((name, b.name.span));
                    }
                    self.names
                        .insert(b.name.text.clone(), (Named::Body(Some(id)), b.name.span));
                    for (k, c) in self
                        .sys
                        .body(id)
                        .coordinates
                        .clone()
                        .into_iter()
                        .enumerate()
                    {
                        let coord = self.sys.coordinates()[c].clone();
                        let _ = k;
                        for s in [coord.q, coord.u] {
                            let name = self.sys.arena.symbol(s).name.clone();
                            self.names.insert(name, (Named::Symbol(s), b.name.span));
                        }
                    }
                }
                Err(e) => self.error(b.name.span, e.to_string()),
            }
        }
        // Unit-vector shorthands: `b1` for body `B`, `n1` for N.
        for (id, body) in self.sys.bodies().iter().enumerate() {
            for k in 1..=3 {
                let short = format!("{}{k}", body.name.to_lowercase());
                if !self.names.contains_key(&short) {
                    self.uv_short
                        .insert(short, (crate::mech::BodyId(id as u32), k));
                }
            }
        }
    }

    fn body_spec(&mut self, b: &ast::Body, parent: String) -> Option<BodySpec> {
        let name = b.name.text.clone();
        let mut spec = BodySpec::new(&name, &parent);
        spec.description = b.label.as_ref().map(|l| l.text.clone());
        let mut ok = true;
        for opt in &b.options.entries {
            let v = &opt.value;
            let good = match opt.key {
                BodyKey::Parent => true,
                BodyKey::Joint => self
                    .list3(v, "the joint point", true)
                    .map(|c| spec.joint = Some(c))
                    .is_some(),
                BodyKey::Cm => self
                    .list3(v, "the mass center", true)
                    .map(|c| spec.cm = Some(c))
                    .is_some(),
                BodyKey::Mass => self
                    .constant(v, "the mass")
                    .filter(|m| self.not_negative(*m, v, "a mass"))
                    .map(|m| spec.mass = Some(m))
                    .is_some(),
                BodyKey::Inertia => self
                    .inertia(v)
                    .filter(|m| {
                        (0..3).all(|k| self.not_negative(m[k][k], v, "a moment of inertia"))
                    })
                    .map(|m| spec.inertia = Some(m))
                    .is_some(),
                BodyKey::Rotate => match v {
                    Expr::Name(n) if n.text == "quaternion" => {
                        spec.quaternion = true;
                        true
                    }
                    _ => self
                        .axes(v, "a rotation axis")
                        .map(|a| spec.rotations = a)
                        .is_some(),
                },
                BodyKey::Translate => self
                    .translations(v)
                    .map(|t| spec.translations = t)
                    .is_some(),
                BodyKey::Q => self
                    .names_list(v, "coordinate names")
                    .map(|n| spec.coordinate_names = Some(n))
                    .is_some(),
                BodyKey::U => self
                    .names_list(v, "speed names")
                    .map(|n| spec.speed_names = Some(n))
                    .is_some(),
                BodyKey::Initial => self
                    .constants_list(v, "initial coordinates")
                    .map(|n| spec.initial_coordinates = Some(n))
                    .is_some(),
                BodyKey::InitialSpeeds => self
                    .constants_list(v, "initial speeds")
                    .map(|n| spec.initial_speeds = Some(n))
                    .is_some(),
                BodyKey::Small | BodyKey::Lock => true,
            };
            ok &= good;
        }
        // Checks with spans before the API sees the spec.
        let dofs = spec.dofs();
        if let Some(opt) = b.options.get(BodyKey::Rotate)
            && !matches!(spec.rotations.len(), 0 | 1 | 3)
        {
            self.push(
                Diagnostic::error(
                    opt.value.span(),
                    format!("body `{name}` has {} rotations", spec.rotations.len()),
                )
                .help("a body rotates 0, 1 or 3 times: `rotate: 3` or `rotate: [1, 2, 3]`"),
            );
            ok = false;
        }
        for (key, what, len) in [
            (
                BodyKey::Q,
                "coordinate names",
                spec.coordinate_names.as_ref().map(Vec::len),
            ),
            (
                BodyKey::U,
                "speed names",
                spec.speed_names.as_ref().map(Vec::len),
            ),
            (
                BodyKey::Initial,
                "initial coordinates",
                spec.initial_coordinates.as_ref().map(Vec::len),
            ),
            (
                BodyKey::InitialSpeeds,
                "initial speeds",
                spec.initial_speeds.as_ref().map(Vec::len),
            ),
        ] {
            // A quaternion has one coordinate more than its speeds (`e0`).
            let expected = match key {
                BodyKey::Q | BodyKey::Initial => spec.coordinate_count(),
                _ => dofs,
            };
            if let (Some(len), Some(opt)) = (len, b.options.get(key))
                && len != expected
            {
                let has = if expected == dofs {
                    format!(
                        "{dofs} degree{} of freedom",
                        if dofs == 1 { "" } else { "s" }
                    )
                } else {
                    format!("{expected} coordinates (a quaternion has e0 to e3)")
                };
                self.error(
                    opt.value.span(),
                    format!("body `{name}` has {has}, but {len} {what} were given"),
                );
                ok = false;
            }
        }
        // `small` and `lock` may name default coordinates (`q9`).
        if spec.coordinate_names.is_none()
            && (b.options.get(BodyKey::Small).is_some() || b.options.get(BodyKey::Lock).is_some())
        {
            let (q, _) = self.sys.default_names(&spec);
            spec.coordinate_names = Some(q);
        }
        if let Some(opt) = b.options.get(BodyKey::Small) {
            match self.small_flags(&opt.value, &spec) {
                Some(flags) => spec.small = flags,
                None => ok = false,
            }
        }
        if let Some(opt) = b.options.get(BodyKey::Lock) {
            match self.small_flags(&opt.value, &spec) {
                Some(flags) => spec.locked = flags,
                None => ok = false,
            }
        }
        // The scene's `small` and `lock` add to the body's own.
        if !self.scene.small.is_empty() || !self.scene.lock.is_empty() {
            let coords = spec
                .coordinate_names
                .clone()
                .unwrap_or_else(|| self.sys.default_names(&spec).0);
            let e0 = spec.quaternion.then_some(spec.translations.len());
            let dofs = spec.dofs();
            for (names, is_lock) in [
                (self.scene.small.clone(), false),
                (self.scene.lock.clone(), true),
            ] {
                let (flags, matched) =
                    crate::model::Scene::flags(&names, &spec.name, &coords, dofs, e0);
                if matched.is_empty() {
                    continue;
                }
                self.scene_matched.extend(matched);
                let target = if is_lock {
                    &mut spec.locked
                } else {
                    &mut spec.small
                };
                if target.is_empty() {
                    *target = vec![false; dofs];
                }
                for (t, f) in target.iter_mut().zip(flags) {
                    *t |= f;
                }
            }
        }
        ok.then_some(spec)
    }

    /// `false` (with a diagnostic) if `x` is a negative number.
    fn not_negative(&mut self, x: crate::expr::ExprId, at: &Expr, what: &str) -> bool {
        match self.sys.arena.as_number(x) {
            Some(n) if n.is_negative() => {
                self.push(
                    Diagnostic::error(at.span(), format!("{what} cannot be negative"))
                        .help("masses and moments of inertia are zero or positive"),
                );
                false
            }
            _ => true,
        }
    }

    fn axes(&mut self, v: &Expr, what: &str) -> Option<Vec<i64>> {
        let items: Vec<&Expr> = match v {
            Expr::List { items, .. } => items.iter().collect(),
            other => vec![other],
        };
        let mut out = Vec::new();
        let mut ok = true;
        for it in items {
            match self.integer(it, what) {
                Some(a) if (1..=3).contains(&a) => out.push(a),
                Some(a) => {
                    self.push(
                        Diagnostic::error(it.span(), format!("axis {a} is out of range"))
                            .help("axes are 1, 2 or 3"),
                    );
                    ok = false;
                }
                None => ok = false,
            }
        }
        ok.then_some(out)
    }

    fn translations(&mut self, v: &Expr) -> Option<Vec<Direction>> {
        let items: Vec<&Expr> = match v {
            Expr::List { items, .. } => items.iter().collect(),
            other => vec![other],
        };
        let mut out = Vec::new();
        let mut ok = true;
        for it in items {
            match it {
                Expr::List { .. } => match self.list3(it, "a translation direction", true) {
                    Some(c) => {
                        if c.iter().all(|x| self.sys.arena.is_zero(*x)) {
                            self.error(
                                it.span(),
                                "a translation direction cannot be the zero vector",
                            );
                            ok = false;
                        } else {
                            out.push(Direction::Vector(c));
                        }
                    }
                    None => ok = false,
                },
                other => match self.integer(other, "a translation axis") {
                    Some(a)
                        if out
                            .iter()
                            .any(|d| matches!(d, Direction::Axis(x) if *x == a)) =>
                    {
                        self.push(
                            Diagnostic::error(
                                other.span(),
                                format!("the body already translates along axis {a}"),
                            )
                            .help("each translation needs a direction of its own"),
                        );
                        ok = false;
                    }
                    Some(a) if (1..=3).contains(&a) => out.push(Direction::Axis(a)),
                    Some(a) => {
                        self.push(
                            Diagnostic::error(other.span(), format!("axis {a} is out of range"))
                                .help("translate along axis 1, 2 or 3, or a direction `[x, y, z]`"),
                        );
                        ok = false;
                    }
                    None => ok = false,
                },
            }
        }
        if out.len() > 3 {
            self.error(
                v.span(),
                format!(
                    "{} translations: a body translates at most 3 times",
                    out.len()
                ),
            );
            ok = false;
        }
        ok.then_some(out)
    }

    fn inertia(&mut self, v: &Expr) -> Option<Mat3> {
        let zero = self.sys.arena.zero();
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
                let d = self.constants(args, "an inertia")?;
                Some([[d[0], zero, zero], [zero, d[1], zero], [zero, zero, d[2]]])
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
                    for i in 0..3 {
                        for j in 0..i {
                            if m[i][j] != m[j][i] {
                                self.push(
                                    Diagnostic::error(*span, format!("the inertia matrix is not symmetric: entry ({}, {}) differs from ({}, {})", i + 1, j + 1, j + 1, i + 1))
                                        .help("entries are dyadic components about the mass center; I_jk must equal I_kj"),
                                );
                                return None;
                            }
                        }
                    }
                    Some(m)
                } else {
                    let refs: Vec<Expr> = items.clone();
                    let d = self.constants(&refs, "an inertia")?;
                    Some([[d[0], zero, zero], [zero, d[1], zero], [zero, zero, d[2]]])
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

    fn constants(&mut self, items: &[Expr], what: &str) -> Option<Vec<ExprId>> {
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

    fn constants_list(&mut self, v: &Expr, what: &str) -> Option<Vec<ExprId>> {
        match v {
            Expr::List { items, .. } => self.constants(items, what),
            other => self.constant(other, what).map(|x| vec![x]),
        }
    }

    fn names_list(&mut self, v: &Expr, what: &str) -> Option<Vec<String>> {
        let items: Vec<&Expr> = match v {
            Expr::List { items, .. } => items.iter().collect(),
            other => vec![other],
        };
        let mut out = Vec::new();
        let mut ok = true;
        for it in items {
            match it {
                Expr::Name(n) if n.text == "t" || n.text == "N" => {
                    self.push(
                        Diagnostic::error(n.span, format!("`{}` is reserved", n.text))
                            .help("choose another name"),
                    );
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
    /// coordinate names]`, one flag per degree of freedom.
    fn small_flags(&mut self, v: &Expr, spec: &BodySpec) -> Option<Vec<bool>> {
        let nt = spec.translations.len();
        let dofs = spec.dofs();
        let mut flags = vec![false; dofs];
        let items: Vec<&Expr> = match v {
            Expr::List { items, .. } => items.iter().collect(),
            other => vec![other],
        };
        let mut ok = true;
        for it in items {
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
                other => match spec
                    .coordinate_names
                    .as_ref()
                    .and_then(|ns| ns.iter().position(|x| x == other))
                    // A quaternion's names are e0..e3 for three speeds.
                    .map(|k| if spec.quaternion && k > nt { k - 1 } else { k })
                    .filter(|k| *k < dofs)
                {
                    Some(k) => flags[k] = true,
                    None => {
                        self.push(
                            Diagnostic::error(n.span, format!("`{other}` is not a coordinate of body `{}`", spec.name))
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

//! Differential test of `System::equations()` (Kane's equations in
//! composite-body form) against Kane's equations derived the textbook way
//! with the generic vector API: partial velocities of every mass center and
//! point of application, accelerations as time derivatives of velocities,
//! generalized active and inertia forces, `M_rs` the coefficient of `du_s`
//! and `f_r` the rest. Plus energy conservation of an undamped model and
//! rest without loads.

use autosim_core::expr::{
    Arena, Bindings, ExprId, NoUserFunctions, Number, OpCount, SymId, SymbolKind,
};
use autosim_core::mech::{
    Axis, BodyId, BodySpec, Direction, Dyadic, PointId, Rotation, System, Vector,
};
use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;

use autosim_test_support::Rng;

// ----- the textbook derivation -----

fn add(sys: &mut System, kr: &mut [ExprId], r: usize, x: ExprId) {
    kr[r] = sys.arena.add(kr[r], x);
}

/// Adds a load's generalized forces to `kr`: `partial(at, r)·vector`, less
/// `partial(reaction, r)·vector` where it has a reaction (`partial` is the
/// partial velocity of a point or angular velocity of a body).
fn add_load<T: Copy>(
    sys: &mut System,
    kr: &mut [ExprId],
    vector: &Vector,
    (at, reaction): (T, Option<T>),
    partial: impl Fn(&mut System, T, usize) -> Vector,
) {
    for r in 0..kr.len() {
        let pa = partial(sys, at, r);
        let x = sys.frames.dot_vec(&mut sys.arena, &pa, vector);
        add(sys, kr, r, x);
        if let Some(reaction) = reaction {
            let pr = partial(sys, reaction, r);
            let y = sys.frames.dot_vec(&mut sys.arena, &pr, vector);
            let y = sys.arena.neg(y);
            add(sys, kr, r, y);
        }
    }
}

struct Textbook {
    mass: Vec<Vec<ExprId>>,
    forcing: Vec<ExprId>,
}

fn body_ids(sys: &System) -> Vec<BodyId> {
    sys.bodies()
        .iter()
        .skip(1)
        .map(|b| sys.body_named(&b.name).unwrap())
        .collect()
}

/// `Σ_bodies v_r·(R + R*) + ω_r·T*  +  Σ_forces v_r(P)·F - v_r(Q)·F  +
/// Σ_moments ω_r(A)·M - ω_r(B)·M`, then `M_rs = -∂/∂(du_s)` and `f_r` the
/// value at du = 0.
fn textbook(sys: &mut System) -> Textbook {
    let n = sys.coordinates().len();
    let zero = sys.arena.zero();
    let mut kr = vec![zero; n];
    let gravity = sys.gravity().cloned();
    for b in body_ids(sys) {
        let body = sys.body(b).clone();
        let v = sys.vel(body.cm_point, None).unwrap();
        let w = sys.rot(b);
        let a = sys.dxdt_vector(&v).unwrap();
        let alpha = sys.dxdt_vector(&w).unwrap();
        let triad = sys.frames.frame(body.frame).triad;
        let inertia = Dyadic::from_matrix(&sys.arena, triad, body.inertia);
        // R* = -m a (+ m g), T* = -I·α - ω × (I·ω)
        let m_neg = sys.arena.neg(body.mass);
        let mut force = a.scale(&mut sys.arena, m_neg);
        if let Some(g) = &gravity {
            let mg = g.scale(&mut sys.arena, body.mass);
            force = force.add(&mut sys.arena, &mg);
        }
        let ia = sys.frames.dot_dyadic_vec(&mut sys.arena, &inertia, &alpha);
        let iw = sys.frames.dot_dyadic_vec(&mut sys.arena, &inertia, &w);
        let wxiw = sys.frames.cross_vec(&mut sys.arena, &w, &iw);
        let torque = ia.add(&mut sys.arena, &wxiw).neg(&mut sys.arena);
        for r in 0..n {
            let vr = sys.partial_velocity(body.cm_point, r).unwrap();
            let wr = sys.partial_angular_velocity(b, r).unwrap();
            let x = sys.frames.dot_vec(&mut sys.arena, &vr, &force);
            let y = sys.frames.dot_vec(&mut sys.arena, &wr, &torque);
            add(sys, &mut kr, r, x);
            add(sys, &mut kr, r, y);
        }
    }
    for f in sys.forces().to_vec() {
        let partial = |s: &mut System, p: PointId, r| s.partial_velocity(p, r).unwrap();
        add_load(sys, &mut kr, &f.vector, (f.at, f.reaction), partial);
    }
    for m in sys.moments().to_vec() {
        let partial = |s: &mut System, b: BodyId, r| s.partial_angular_velocity(b, r).unwrap();
        add_load(sys, &mut kr, &m.vector, (m.at, m.reaction), partial);
    }
    let du: Vec<SymId> = sys.coordinates().iter().map(|c| c.du).collect();
    let mut mass = vec![vec![zero; n]; n];
    for r in 0..n {
        for s in 0..n {
            let d = sys.arena.partial(kr[r], du[s]).unwrap();
            mass[r][s] = sys.arena.neg(d);
        }
    }
    let map: FxHashMap<SymId, ExprId> = du.iter().map(|s| (*s, zero)).collect();
    let forcing = kr.iter().map(|g| sys.arena.substitute(*g, &map)).collect();
    Textbook { mass, forcing }
}

// ----- models -----

struct Options {
    loads: bool,
    damping: bool,
    extra_forces: bool,
    gravity: bool,
}

impl Options {
    /// Every load, damper, extra force and gravity.
    const ALL: Options = Options {
        loads: true,
        damping: true,
        extra_forces: true,
        gravity: true,
    };
    /// None of them: the bodies and joints alone.
    const NONE: Options = Options {
        loads: false,
        damping: false,
        extra_forces: false,
        gravity: false,
    };
}

fn p(sys: &mut System, name: &str, v: f64) -> ExprId {
    let s = sys.add_parameter(name, v, None).unwrap();
    sys.arena.sym(s)
}

fn num(sys: &mut System, v: f64) -> ExprId {
    sys.arena.num(Number::float(v).unwrap())
}

fn e(sys: &mut System, text: &str) -> ExprId {
    sys.arena.parse_text(text).unwrap()
}

fn sym_matrix(sys: &mut System, d: [f64; 3], off: [f64; 3]) -> [[ExprId; 3]; 3] {
    let [a, b, c] = d.map(|x| num(sys, x));
    let [x, y, z] = off.map(|x| num(sys, x));
    [[a, x, y], [x, b, z], [y, z, c]]
}

/// B1: free body (3 translations along n1..n3, rotations 1-2-3) with an
/// offset mass center and a full inertia matrix. B2 on B1: translation
/// along the constant non-axis direction (1, 2, 2) and a rotation about 2.
/// B3 on B2: massless, rotation about 3. B4 on B3: rotation about 1.
/// B5 on B2: no degrees of freedom (added mass). B6 on B1: translation
/// along (1, -1, 1/2) only. B7 on B6: rotations 2-3-1.
///
/// Expressions are numbered in creation order: the parts below are built
/// in a fixed order (parameters, bodies B1 to B7, gravity, loads).
fn rich_model(opt: &Options) -> System {
    let mut sys = System::new("Rich");
    let k = p(&mut sys, "k", 40.0);
    let c = p(&mut sys, "c", 0.7);
    let kt = p(&mut sys, "kt", 3.0);
    let ct = p(&mut sys, "ct", 0.2);
    let l0 = p(&mut sys, "L0", 0.4);
    let g = p(&mut sys, "g", 9.81);
    let m1 = p(&mut sys, "m1", 2.5);
    let zero = sys.arena.zero();

    let b1 = rich_b1(&mut sys, m1);
    let b2 = rich_b2(&mut sys);
    let (b3, b4, b5) = rich_b3_b4_b5(&mut sys, zero);
    let (b6, b7) = rich_b6_b7(&mut sys, zero);
    sys.add_bodies(vec![b4, b3, b2, b1, b5, b6, b7]).unwrap();
    if opt.gravity {
        let n3 = sys.unit_vector(BodyId::N, Axis::A3);
        let mg = sys.arena.neg(g);
        let gv = n3.scale(&mut sys.arena, mg);
        sys.set_gravity(gv);
    }
    if !opt.loads {
        return sys;
    }
    add_spring(&mut sys, opt, k, c, l0);
    add_torsion_springs(&mut sys, opt, kt, ct);
    if opt.extra_forces {
        add_extra_loads(&mut sys);
    }
    sys
}

/// B1: free body (3 translations along n1..n3, rotations 1-2-3) with an
/// offset mass center and a full inertia matrix.
fn rich_b1(sys: &mut System, m1: ExprId) -> BodySpec {
    let mut b1 = BodySpec::new("B1", "N");
    b1.joint.translations = vec![
        Direction::Axis(Axis::A1),
        Direction::Axis(Axis::A2),
        Direction::Axis(Axis::A3),
    ];
    b1.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A2, Axis::A3]);
    b1.mass = Some(m1);
    b1.cm = Some([num(sys, 0.05), e(sys, "-L0/4"), num(sys, 0.1)]);
    b1.inertia = Some(sym_matrix(sys, [0.9, 1.1, 1.4], [0.05, -0.03, 0.02]));
    b1
}

/// B2 on B1: translation along the constant non-axis direction (1, 2, 2)
/// and a rotation about 2.
fn rich_b2(sys: &mut System) -> BodySpec {
    let mut b2 = BodySpec::new("B2", "B1");
    b2.joint_point = Some([num(sys, 0.1), num(sys, 0.2), num(sys, -0.3)]);
    b2.joint.translations = vec![Direction::Vector([
        sys.arena.int(1),
        sys.arena.int(2),
        sys.arena.int(2),
    ])];
    b2.joint.rotation = Rotation::Simple(Axis::A2);
    b2.mass = Some(num(sys, 1.3));
    b2.cm = Some([num(sys, 0.02), num(sys, -0.15), num(sys, 0.04)]);
    b2.inertia = Some(sym_matrix(sys, [0.2, 0.15, 0.1], [0.01, 0.0, -0.02]));
    b2
}

/// B3 on B2: massless, rotation about 3. B4 on B3: rotation about 1. B5
/// on B2: no degrees of freedom (added mass).
fn rich_b3_b4_b5(sys: &mut System, zero: ExprId) -> (BodySpec, BodySpec, BodySpec) {
    let mut b3 = BodySpec::new("B3", "B2");
    b3.joint_point = Some([zero, num(sys, -0.3), zero]);
    b3.joint.rotation = Rotation::Simple(Axis::A3);
    b3.mass = Some(zero);
    b3.inertia = Some([[zero; 3]; 3]);

    let mut b4 = BodySpec::new("B4", "B3");
    b4.joint_point = Some([num(sys, 0.05), zero, zero]);
    b4.joint.rotation = Rotation::Simple(Axis::A1);
    b4.mass = Some(num(sys, 0.8));
    b4.cm = Some([zero, num(sys, -0.25), num(sys, 0.03)]);
    b4.inertia = Some(sym_matrix(sys, [0.05, 0.02, 0.06], [0.0, 0.004, 0.0]));

    let mut b5 = BodySpec::new("B5", "B2");
    b5.joint_point = Some([num(sys, 0.1), num(sys, 0.1), num(sys, 0.1)]);
    b5.mass = Some(num(sys, 0.6));
    b5.cm = Some([num(sys, 0.02), zero, num(sys, -0.05)]);
    b5.inertia = Some(sym_matrix(sys, [0.01, 0.02, 0.03], [0.001, 0.002, 0.0]));
    (b3, b4, b5)
}

/// B6 on B1: translation along (1, -1, 1/2) only. B7 on B6: rotations
/// 2-3-1.
fn rich_b6_b7(sys: &mut System, zero: ExprId) -> (BodySpec, BodySpec) {
    let mut b6 = BodySpec::new("B6", "B1");
    b6.joint_point = Some([num(sys, -0.2), zero, num(sys, 0.1)]);
    b6.joint.translations = vec![Direction::Vector([
        sys.arena.int(1),
        sys.arena.int(-1),
        sys.arena.rational(1, 2),
    ])];
    b6.mass = Some(num(sys, 0.9));
    b6.cm = Some([zero, num(sys, 0.05), zero]);
    b6.inertia = Some(sym_matrix(sys, [0.03, 0.03, 0.04], [0.0, 0.0, 0.005]));

    let mut b7 = BodySpec::new("B7", "B6");
    b7.joint_point = Some([num(sys, 0.1), num(sys, -0.1), zero]);
    b7.joint.rotation = Rotation::Sequence([Axis::A2, Axis::A3, Axis::A1]);
    b7.mass = Some(num(sys, 0.4));
    b7.cm = Some([num(sys, 0.03), num(sys, 0.02), num(sys, -0.04)]);
    b7.inertia = Some(sym_matrix(
        sys,
        [0.02, 0.025, 0.015],
        [0.002, -0.001, 0.003],
    ));
    (b6, b7)
}

fn id(sys: &System, name: &str) -> BodyId {
    sys.body_named(name).unwrap()
}

/// A point of body `b` at constant coordinates `c`.
fn pt(sys: &mut System, name: &str, b: BodyId, c: [f64; 3]) -> PointId {
    let c = c.map(|x| num(sys, x));
    sys.add_point(name, b, c).unwrap()
}

/// Spring-damper between a point of B2 and a point of B6:
/// F = -(k (|r| - L0) + c (v·r/|r|)) r/|r| on P3, reaction on P4.
fn add_spring(sys: &mut System, opt: &Options, k: ExprId, c: ExprId, l0: ExprId) {
    let (ib2, ib6) = (id(sys, "B2"), id(sys, "B6"));
    let p3 = pt(sys, "P3", ib2, [0.1, -0.2, 0.05]);
    let p4 = pt(sys, "P4", ib6, [0.0, 0.1, -0.1]);
    let r = sys.pos(p3, Some(p4));
    let rr = sys.frames.dot_vec(&mut sys.arena, &r, &r);
    let len = sys.arena.sqrt(rr);
    let inv = sys.arena.inv(len);
    let dir = r.scale(&mut sys.arena, inv);
    let stretch = sys.arena.sub(len, l0);
    let mut mag = sys.arena.mul(k, stretch);
    if opt.damping {
        let v = sys.vel(p3, Some(p4)).unwrap();
        let rate = sys.frames.dot_vec(&mut sys.arena, &v, &dir);
        let cr = sys.arena.mul(c, rate);
        mag = sys.arena.add(mag, cr);
    }
    let mag = sys.arena.neg(mag);
    let f = dir.scale(&mut sys.arena, mag);
    sys.add_force("spring", p3, Some(p4), f).unwrap();
}

/// Torsion springs (dampers) at the single-rotation joints, about the
/// shared joint axis: on the child, reaction on the parent.
fn add_torsion_springs(sys: &mut System, opt: &Options, kt: ExprId, ct: ExprId) {
    let (ib1, ib2, ib3, ib4) = (id(sys, "B1"), id(sys, "B2"), id(sys, "B3"), id(sys, "B4"));
    for (name, child, parent, axis) in [
        ("t2", ib2, ib1, 2usize),
        ("t3", ib3, ib2, 3),
        ("t4", ib4, ib3, 1),
    ] {
        let ci = sys.body(child).coordinates.last().copied().unwrap();
        let q = sys.arena.sym(sys.coordinates()[ci].q);
        let u = sys.arena.sym(sys.coordinates()[ci].u);
        let kq = sys.arena.mul(kt, q);
        let mut m = kq;
        if opt.damping {
            let cu = sys.arena.mul(ct, u);
            m = sys.arena.add(m, cu);
        }
        let m = sys.arena.neg(m);
        let d = sys.unit_vector(parent, Axis::number(axis as i64).unwrap());
        let mv = d.scale(&mut sys.arena, m);
        sys.add_moment(name, child, Some(parent), mv).unwrap();
    }
}

/// The sum of `text` times the unit vector `axis` of body `b`, over the
/// given components (in several frames).
fn components(sys: &mut System, parts: &[(BodyId, i64, &str)]) -> Vector {
    let mut v = Vector::zero();
    for &(b, axis, text) in parts {
        let x = e(sys, text);
        let t = sys
            .unit_vector(b, Axis::number(axis).unwrap())
            .scale(&mut sys.arena, x);
        v = v.add(&mut sys.arena, &t);
    }
    v
}

/// State- and time-dependent forces and moments, with and without
/// reactions, with components in several frames.
fn add_extra_loads(sys: &mut System) {
    let (ib1, ib2, ib3, ib4) = (id(sys, "B1"), id(sys, "B2"), id(sys, "B3"), id(sys, "B4"));
    // A state- and time-dependent force at a point of B4 with its
    // reaction at a point of B1, with components in several frames.
    let p1 = pt(sys, "P1", ib4, [0.02, -0.3, 0.01]);
    let p2 = pt(sys, "P2", ib1, [0.1, 0.1, -0.2]);
    let f = components(
        sys,
        &[
            (BodyId::N, 1, "2 + q1*u3"),
            (ib2, 2, "sin(t)*q5 - u9"),
            (ib4, 3, "0.3f*u10 + cos(q10)"),
        ],
    );
    sys.add_force("push", p1, Some(p2), f).unwrap();
    // A force at the mass center of the added-mass body B5, no reaction.
    let ib5 = id(sys, "B5");
    let cm5 = sys.body(ib5).cm_point;
    let x = e(sys, "u7 - q8");
    let f5 = sys.unit_vector(ib3, Axis::A2).scale(&mut sys.arena, x);
    sys.add_force("push5", cm5, None, f5).unwrap();
    // A moment on B4 with reaction on B1, components in N and B2.
    let m = components(
        sys,
        &[(BodyId::N, 3, "u4 - 0.5f*q6"), (ib2, 1, "q2*q7 + 1")],
    );
    sys.add_moment("twist", ib4, Some(ib1), m).unwrap();
    // A moment on B1 alone.
    let x = e(sys, "-0.4f*u5");
    let m1v = sys.unit_vector(ib1, Axis::A2).scale(&mut sys.arena, x);
    sys.add_moment("drag", ib1, None, m1v).unwrap();
}

// ----- random states -----

fn random_state(sys: &System, rng: &mut Rng, speeds: bool) -> Bindings {
    let mut b = Bindings::with_defaults(&sys.arena);
    for c in sys.coordinates() {
        b.set(c.q, rng.uniform(-1.2, 1.2));
        b.set(c.u, if speeds { rng.uniform(-2.0, 2.0) } else { 0.0 });
    }
    b.set(sys.time(), rng.uniform(0.0, 5.0));
    b
}

fn eval_all(arena: &Arena, es: &[ExprId], b: &Bindings) -> Vec<f64> {
    arena.eval_many(es, b, &mut NoUserFunctions)
}

fn flatten(m: &[Vec<ExprId>]) -> Vec<ExprId> {
    m.iter().flatten().copied().collect()
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

fn compare(sys: &mut System, seed: u64, samples: usize) {
    let eqs = sys.equations().unwrap();
    let tb = textbook(sys);
    let n = eqs.speeds.len();
    let mut rng = Rng::new(seed);
    for sample in 0..samples {
        let b = random_state(sys, &mut rng, true);
        let m_eng = eval_all(&sys.arena, &flatten(&eqs.mass_matrix), &b);
        let m_tb = eval_all(&sys.arena, &flatten(&tb.mass), &b);
        let f_eng = eval_all(&sys.arena, &eqs.forcing, &b);
        let f_tb = eval_all(&sys.arena, &tb.forcing, &b);
        let sm = max_abs(&m_tb);
        let sf = max_abs(&f_tb).max(1e-300);
        for r in 0..n {
            for s in 0..n {
                let (x, y) = (m_eng[r * n + s], m_tb[r * n + s]);
                assert!(
                    (x - y).abs() <= 1e-10 * sm,
                    "{}: sample {sample}: M[{r}][{s}] = {x}, textbook {y}",
                    sys.name()
                );
            }
            assert!(
                (f_eng[r] - f_tb[r]).abs() <= 1e-10 * sf,
                "{}: sample {sample}: f[{r}] = {}, textbook {}",
                sys.name(),
                f_eng[r],
                f_tb[r]
            );
        }
        // The textbook mass matrix is symmetric and positive definite.
        let mm = DMatrix::from_row_slice(n, n, &m_tb);
        assert!(
            (&mm - mm.transpose()).amax() <= 1e-12 * sm,
            "textbook M symmetric"
        );
        assert!(mm.cholesky().is_some(), "textbook M positive definite");
    }
}

#[test]
fn rich_model_matches_textbook_kane() {
    let mut sys = rich_model(&Options::ALL);
    assert_eq!(sys.coordinates().len(), 14);
    compare(&mut sys, 0x1234_5678_9abc_def1, 8);
}

#[test]
fn unloaded_model_matches_textbook_kane() {
    let mut sys = rich_model(&Options::NONE);
    compare(&mut sys, 0x0fed_cba9_8765_4321, 8);
}

#[test]
fn satellite_matches_textbook_kane() {
    let data = autosim_test_support::load("satellite");
    let mut sys = autosim_test_support::api::satellite(&data["parameters"], false);
    compare(&mut sys, 0x5eed_5eed_5eed_5eed, 4);
}

/// Without loads, a system at rest stays at rest: dq/dt = 0 and f = 0 at
/// u = 0 for any configuration.
#[test]
fn derivatives_vanish_at_rest_without_loads() {
    let mut sys = rich_model(&Options::NONE);
    let eqs = sys.equations().unwrap();
    let mut rng = Rng::new(42);
    for _ in 0..10 {
        let b = random_state(&sys, &mut rng, false);
        let dq = eval_all(&sys.arena, &eqs.kinematics, &b);
        let f = eval_all(&sys.arena, &eqs.forcing, &b);
        let m = eval_all(&sys.arena, &flatten(&eqs.mass_matrix), &b);
        assert!(max_abs(&dq) == 0.0, "dq/dt at rest: {dq:?}");
        assert!(max_abs(&f) <= 1e-14 * max_abs(&m), "f at rest: {f:?}");
    }
}

/// d/dt (KE + PE) = 0 along the motion of the undamped model with
/// gravity, a point-to-point spring and torsion springs, with du/dt from
/// solving M du = f.
#[test]
fn undamped_model_conserves_energy() {
    let mut sys = rich_model(&Options {
        damping: false,
        extra_forces: false,
        ..Options::ALL
    });
    let eqs = sys.equations().unwrap();
    let n = eqs.speeds.len();
    // Potential energy: gravity on every mass center, the point spring and
    // the three torsion springs.
    let g = e(&mut sys, "g");
    let mut pe = Vec::new();
    for b in body_ids(&sys) {
        let body = sys.body(b).clone();
        let r = sys.pos(body.cm_point, None);
        let n3 = sys.unit_vector(BodyId::N, Axis::A3);
        let z = sys.frames.dot_vec(&mut sys.arena, &r, &n3);
        pe.push(sys.arena.product(&[body.mass, g, z]));
    }
    let p3 = sys.point_named("P3").unwrap();
    let p4 = sys.point_named("P4").unwrap();
    let r = sys.pos(p3, Some(p4));
    let rr = sys.frames.dot_vec(&mut sys.arena, &r, &r);
    let len = sys.arena.sqrt(rr);
    let l0 = e(&mut sys, "L0");
    let stretch = sys.arena.sub(len, l0);
    let s2 = sys.arena.powi(stretch, 2);
    let half_k = e(&mut sys, "k/2");
    pe.push(sys.arena.mul(half_k, s2));
    let half_kt = e(&mut sys, "kt/2");
    for b in ["B2", "B3", "B4"] {
        let ci = *sys
            .body(sys.body_named(b).unwrap())
            .coordinates
            .last()
            .unwrap();
        let q = sys.arena.sym(sys.coordinates()[ci].q);
        let q2 = sys.arena.powi(q, 2);
        pe.push(sys.arena.mul(half_kt, q2));
    }
    let pe = sys.arena.sum(&pe);
    let ke = sys.kinetic_energy();
    let energy = sys.arena.add(ke, pe);
    let power = sys.arena.dxdt(energy).unwrap();
    // Scale: the kinetic energy's rate computed term by term is of the
    // size of u·(M du) and u·f.
    let mut rng = Rng::new(7);
    for sample in 0..10 {
        let mut b = random_state(&sys, &mut rng, true);
        let m = eval_all(&sys.arena, &flatten(&eqs.mass_matrix), &b);
        let f = eval_all(&sys.arena, &eqs.forcing, &b);
        let mm = DMatrix::from_row_slice(n, n, &m);
        let du = mm.lu().solve(&DVector::from_row_slice(&f)).unwrap();
        for (k, s) in eqs.speed_rates.iter().enumerate() {
            b.set(*s, du[k]);
        }
        let u: Vec<f64> = eqs.speeds.iter().map(|s| b.get(*s)).collect();
        let scale: f64 = u
            .iter()
            .zip(&f)
            .map(|(a, b)| (a * b).abs())
            .sum::<f64>()
            .max(1.0);
        let p = sys.arena.eval(power, &b, &mut NoUserFunctions);
        assert!(
            p.abs() <= 1e-9 * scale,
            "sample {sample}: dE/dt = {p} (scale {scale})"
        );
        // Not vacuous: the energy does change when du is perturbed.
        b.set(eqs.speed_rates[0], du[0] + 1.0);
        let p2 = sys.arena.eval(power, &b, &mut NoUserFunctions);
        assert!(p2.abs() > 1e-6, "power insensitive to du");
    }
}

/// A force at a point whose coordinates in its body depend on another
/// body's coordinate (a point sliding on B1 as q of B2 changes): its
/// partial velocities include the sliding direction.
#[test]
fn moving_point_force_matches_textbook_kane() {
    let mut sys = System::new("Moving");
    let mut a = BodySpec::new("A", "N");
    a.joint.rotation = Rotation::Simple(Axis::A3);
    a.cm = Some([sys.arena.rational(1, 5), sys.arena.zero(), sys.arena.zero()]);
    let mut b = BodySpec::new("B", "A");
    b.joint.translations = vec![Direction::Axis(Axis::A1)];
    sys.add_bodies(vec![a, b]).unwrap();
    let ia = sys.body_named("A").unwrap();
    let q2 = sys.arena.sym(sys.coordinates()[1].q);
    let zero = sys.arena.zero();
    let pt = sys.add_point("slider", ia, [q2, zero, zero]).unwrap();
    let x = e(&mut sys, "1 + q1");
    let f = sys.unit_vector(ia, Axis::A1).scale(&mut sys.arena, x);
    sys.add_force("f", pt, None, f).unwrap();
    compare(&mut sys, 99, 4);
}

#[test]
fn textbook_and_engine_sizes() {
    // Not a check: the composite-body form should be much smaller than the
    // textbook form; print both for the record.
    let mut sys = rich_model(&Options::ALL);
    let eqs = sys.equations().unwrap();
    let tb = textbook(&mut sys);
    let mut a = flatten(&eqs.mass_matrix);
    a.extend(&eqs.forcing);
    let mut t = flatten(&tb.mass);
    t.extend(&tb.forcing);
    let (ca, ct): (OpCount, OpCount) = (sys.arena.op_count(&a), sys.arena.op_count(&t));
    eprintln!("rich model: equations() {ca}; textbook {ct}");
    let _ = SymbolKind::Free;
}

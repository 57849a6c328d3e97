//! The reference models of `tests/reference/models.md` built through the
//! core API (independently of the model language), and their equations
//! evaluated and solved numerically.

use crate::reference::floats;
use autosim_core::expr::{Bindings, ExprId};
use autosim_core::mech::{Axis, BodySpec, Direction, Equations, Rotation, System, Vector};
use nalgebra::{DMatrix, DVector};
use serde_json::Value;

/// chain-planar-n or chain-spatial-n of reference-models.md, with the
/// parameter values of the reference file.
pub fn chain(n: usize, spatial: bool, params: &Value) -> System {
    let mut sys = System::new(if spatial {
        "ChainSpatial"
    } else {
        "ChainPlanar"
    });
    let p = |name: &str| {
        params[name]
            .as_f64()
            .unwrap_or_else(|| panic!("parameter {name}"))
    };
    let par = |sys: &mut System, name: &str| -> ExprId {
        let s = sys.add_parameter(name, p(name), None).unwrap();
        sys.arena.sym(s)
    };
    let k = par(&mut sys, "k");
    let c = par(&mut sys, "c");
    let g = par(&mut sys, "g");
    let pp = if spatial {
        Some(par(&mut sys, "P"))
    } else {
        None
    };
    let zero = sys.arena.zero();
    let mut lengths = Vec::new();
    for i in 1..=n {
        let m = par(&mut sys, &format!("m{i}"));
        let l = par(&mut sys, &format!("L{i}"));
        let ixx = par(&mut sys, &format!("Ixx{i}"));
        let iyy = par(&mut sys, &format!("Iyy{i}"));
        let izz = par(&mut sys, &format!("Izz{i}"));
        let parent = if i == 1 {
            "N".to_string()
        } else {
            format!("B{}", i - 1)
        };
        let mut spec = BodySpec::new(&format!("B{i}"), &parent);
        if i > 1 {
            let prev: ExprId = lengths[i - 2];
            spec.joint_point = Some([zero, zero, sys.arena.neg(prev)]);
        }
        let axis = if spatial { ((i - 1) % 3) as i64 + 1 } else { 1 };
        spec.joint.rotation = Rotation::Simple(Axis::number(axis).unwrap());
        spec.mass = Some(m);
        let half = sys.arena.rational(-1, 2);
        spec.cm = Some([zero, zero, sys.arena.mul(half, l)]);
        let off = pp.unwrap_or(zero);
        spec.inertia = Some([[ixx, off, zero], [off, iyy, zero], [zero, zero, izz]]);
        spec.coordinate_names = Some(vec![format!("q{i}")]);
        spec.speed_names = Some(vec![format!("u{i}")]);
        lengths.push(l);
        let b = sys.add_body(spec).unwrap();
        // Spring-damper about the parent's axis a_i (shared with the body).
        let q = sys.arena.sym(sys.coordinates()[i - 1].q);
        let u = sys.arena.sym(sys.coordinates()[i - 1].u);
        let kq = sys.arena.mul(k, q);
        let cu = sys.arena.mul(c, u);
        let s = sys.arena.add(kq, cu);
        let mag = sys.arena.neg(s);
        let parent_id = sys.body_named(&parent).unwrap();
        let axis_v = sys.unit_vector(parent_id, Axis::number(axis).unwrap());
        let vecm = axis_v.scale(&mut sys.arena, mag);
        let reaction = Some(parent_id);
        sys.add_moment(&format!("spring{i}"), b, reaction, vecm)
            .unwrap();
    }
    let n3 = sys.unit_vector(autosim_core::mech::BodyId::N, Axis::A3);
    let mg = sys.arena.neg(g);
    let gv = n3.scale(&mut sys.arena, mg);
    sys.set_gravity(gv);
    sys
}

/// The satellite of reference-models.md; inputs clkcmd, camcmd, thr1..thr3
/// replace the user procedures.
pub fn satellite(params: &Value, small: bool) -> System {
    satellite_with(params, small, false)
}

/// The satellite with the boom hinge angles (q9, q10) locked at zero.
pub fn satellite_locked_boom(params: &Value) -> System {
    build_satellite(params, false, false, true)
}

/// The satellite with the bus oriented by Euler parameters if `quaternion`.
pub fn satellite_with(params: &Value, small: bool, quaternion: bool) -> System {
    build_satellite(params, small, quaternion, false)
}

/// The satellite's bodies, inputs and moments, added in a fixed order
/// (expressions are numbered in creation order).
fn build_satellite(params: &Value, small: bool, quaternion: bool, lock_boom: bool) -> System {
    let mut sys = System::new("Satellite");
    let names = [
        "DB", "DC", "G", "IB11", "IB12", "IB13", "IB22", "IB23", "IB33", "IC", "ID11", "ID12",
        "ID13", "ID22", "ID23", "ID33", "IF1", "IF2", "KB", "KC", "L1", "L2", "L3", "L5", "L6",
        "L7", "L8", "LTT1", "LTT2", "LTT3", "MB", "MC", "MD", "MF",
    ];
    for n in names {
        sys.add_parameter(n, params[n].as_f64().unwrap(), None)
            .unwrap();
    }
    let zero = sys.arena.zero();
    let b = satellite_bus(small, quaternion);
    let (c, d) = satellite_clock_camera(&mut sys, zero);
    let (be, f) = satellite_boom(&mut sys, zero, small, lock_boom);
    sys.add_bodies(vec![b, c, d, be, f]).unwrap();
    for (n, u) in [
        ("clkcmd", "rad"),
        ("camcmd", "rad"),
        ("thr1", ""),
        ("thr2", ""),
        ("thr3", ""),
    ] {
        sys.add_input(n, 0.0, Some(u)).unwrap();
    }
    satellite_moments(&mut sys, lock_boom);
    sys
}

/// An expression from its text (known to be valid).
fn e(sys: &mut System, text: &str) -> ExprId {
    sys.arena.parse_text(text).unwrap()
}

/// The bus B: three translations, and 1-2-3 angles or Euler parameters.
fn satellite_bus(small: bool, quaternion: bool) -> BodySpec {
    let mut b = BodySpec::new("B", "N");
    b.joint.translations = vec![
        Direction::Axis(Axis::A1),
        Direction::Axis(Axis::A2),
        Direction::Axis(Axis::A3),
    ];
    if quaternion {
        b.joint.rotation = Rotation::Quaternion;
        b.coordinate_names = Some(
            ["q1", "q2", "q3", "e0", "e1", "e2", "e3"]
                .map(String::from)
                .to_vec(),
        );
    } else {
        b.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A2, Axis::A3]);
    }
    if small {
        b.small = vec![true; 6];
    }
    b
}

/// The clock C on the bus and the camera D on the clock.
fn satellite_clock_camera(sys: &mut System, zero: ExprId) -> (BodySpec, BodySpec) {
    let mut c = BodySpec::new("C", "B");
    c.joint.rotation = Rotation::Simple(Axis::A3);
    c.mass = Some(e(sys, "MC"));
    let ic = e(sys, "IC");
    c.inertia = Some([[ic, zero, zero], [zero, ic, zero], [zero, zero, zero]]);
    c.cm = Some([zero, zero, e(sys, "-L2")]);
    let mut d = BodySpec::new("D", "C");
    d.joint_point = Some([zero, e(sys, "L3"), e(sys, "-L1")]);
    d.cm = Some([zero, e(sys, "-L5"), e(sys, "-L6")]);
    d.joint.rotation = Rotation::Simple(Axis::A1);
    (c, d)
}

/// The boom: the massless hinge E on the bus and the boom F on it (small
/// or locked angles q9, q10 if asked).
fn satellite_boom(
    sys: &mut System,
    zero: ExprId,
    small: bool,
    lock_boom: bool,
) -> (BodySpec, BodySpec) {
    let mut be = BodySpec::new("E", "B");
    be.joint_point = Some([zero, e(sys, "-L7"), zero]);
    be.joint.rotation = Rotation::Simple(Axis::A3);
    be.mass = Some(zero);
    be.inertia = Some([[zero; 3]; 3]);
    let mut f = BodySpec::new("F", "E");
    f.joint.rotation = Rotation::Simple(Axis::A1);
    let if1 = e(sys, "IF1");
    let if2 = e(sys, "IF2");
    f.inertia = Some([[if1, zero, zero], [zero, if2, zero], [zero, zero, if1]]);
    f.cm = Some([zero, e(sys, "-L8"), zero]);
    if small {
        be.small = vec![true];
        f.small = vec![true];
    }
    if lock_boom {
        be.locked = vec![true];
        f.locked = vec![true];
        be.coordinate_names = Some(vec!["q9".to_string()]);
        f.coordinate_names = Some(vec!["q10".to_string()]);
    }
    (be, f)
}

/// The moments: the boom's springs (without their dampers if the boom is
/// locked: its speeds are zero, and `u9`, `u10` are no symbols of that
/// model), the clock's and the camera's servos, and the three thruster
/// pairs.
fn satellite_moments(sys: &mut System, lock_boom: bool) {
    let (boom1, boom2) = match lock_boom {
        true => ("-KB*q9", "-KB*q10"),
        false => ("-KB*q9 - DB*u9", "-KB*q10 - DB*u10"),
    };
    moment(sys, "boom1", "F", Some("B"), "E", 3, boom1);
    moment(sys, "boom2", "F", Some("B"), "F", 1, boom2);
    moment(
        sys,
        "clock",
        "C",
        Some("B"),
        "C",
        3,
        "KC*(clkcmd - q7) - DC*u7",
    );
    moment(
        sys,
        "camera",
        "D",
        Some("C"),
        "D",
        1,
        "KC*(camcmd - q8) - DC*u8",
    );
    moment(sys, "tt1", "B", None, "B", 1, "LTT1*thr1");
    moment(sys, "tt2", "B", None, "B", 2, "LTT2*thr2");
    moment(sys, "tt3", "B", None, "B", 3, "LTT3*thr3");
}

/// Adds the moment `mag` along axis `axis` of body `frame`, on body `on`
/// (reaction on `reaction`).
fn moment(
    sys: &mut System,
    name: &str,
    on: &str,
    reaction: Option<&str>,
    frame: &str,
    axis: usize,
    mag: &str,
) {
    let body = |sys: &System, n: &str| sys.body_named(n).unwrap();
    let m = sys.arena.parse_text(mag).unwrap();
    let fb = body(sys, frame);
    let d = sys
        .unit_vector(fb, Axis::number(axis as i64).unwrap())
        .scale(&mut sys.arena, m);
    let on = body(sys, on);
    let r = reaction.map(|r| body(sys, r));
    sys.add_moment(name, on, r, d).unwrap();
}

/// Binds a sample's q, u and inputs (and the file's parameters).
pub fn bind(sys: &System, eqs: &Equations, sample: &Value, params: &Value) -> Bindings {
    let mut b = Bindings::with_defaults(&sys.arena);
    for (id, s) in sys.arena.symbols() {
        if let Some(x) = params.get(&s.name).and_then(|x| x.as_f64())
            && s.is_constant()
        {
            b.set(id, x);
        }
    }
    let q = floats(&sample["q"]);
    let u = floats(&sample["u"]);
    for (i, s) in eqs.coordinates.iter().enumerate() {
        b.set(*s, q[i]);
    }
    for (i, s) in eqs.speeds.iter().enumerate() {
        b.set(*s, u[i]);
    }
    if let Some(obj) = sample["inputs"].as_object() {
        for (k, v) in obj {
            if let Some(s) = sys.arena.symbol_named(k) {
                b.set(s, v.as_f64().unwrap());
            }
        }
    }
    b.set(sys.time(), sample["t"].as_f64().unwrap_or(0.0));
    b
}

/// dq/dt, the mass matrix M and the forcing f of `eqs` evaluated at `b`.
pub fn evaluated(
    sys: &System,
    eqs: &Equations,
    b: &Bindings,
) -> (Vec<f64>, DMatrix<f64>, DVector<f64>) {
    let (nq, nu) = (eqs.kinematics.len(), eqs.forcing.len());
    let mut roots = eqs.kinematics.clone();
    for row in &eqs.mass_matrix {
        roots.extend(row);
    }
    roots.extend(&eqs.forcing);
    let vals = sys
        .arena
        .eval_many(&roots, b, &mut autosim_core::expr::NoUserFunctions);
    let dq = vals[..nq].to_vec();
    let m = DMatrix::from_row_slice(nu, nu, &vals[nq..nq + nu * nu]);
    let f = DVector::from_row_slice(&vals[nq + nu * nu..]);
    (dq, m, f)
}

/// Evaluates dq/dt and solves M du/dt = f numerically (Cholesky, or LU
/// where M is not positive definite).
pub fn derivatives(sys: &System, eqs: &Equations, b: &Bindings) -> (Vec<f64>, Vec<f64>) {
    let (dq, m, f) = evaluated(sys, eqs, b);
    let du = m
        .clone()
        .cholesky()
        .map(|c| c.solve(&f))
        .unwrap_or_else(|| m.lu().solve(&f).expect("solvable mass matrix"));
    (dq, du.iter().copied().collect())
}

/// The component of `v` along `n3`.
pub fn vector_dot_n3(sys: &mut System, v: &Vector) -> ExprId {
    let n3 = sys.unit_vector(autosim_core::mech::BodyId::N, Axis::A3);
    sys.frames.dot_vec(&mut sys.arena, v, &n3)
}

//! Every invalid construction through the `System` API is an `Err` whose
//! message names the problem, and random body specifications never panic.

use autosim_core::expr::ExprId;
use autosim_core::mech::{
    Axis, BodyId, BodySpec, Direction, FixedTurn, ModelError, Rotation, System,
};
use proptest::prelude::*;

fn err_text(e: &ModelError) -> String {
    e.to_string()
}

#[track_caller]
fn assert_err<T: std::fmt::Debug>(r: Result<T, ModelError>, needles: &[&str]) {
    match r {
        Ok(v) => panic!("expected an error mentioning {needles:?}, got Ok({v:?})"),
        Err(e) => {
            let msg = err_text(&e);
            for n in needles {
                assert!(msg.contains(n), "error `{msg}` does not mention `{n}`");
            }
        }
    }
}

#[track_caller]
fn assert_errs<T: std::fmt::Debug>(r: Result<T, Vec<ModelError>>, needles: &[&str]) {
    match r {
        Ok(v) => panic!("expected errors mentioning {needles:?}, got Ok({v:?})"),
        Err(es) => {
            let all: Vec<String> = es.iter().map(err_text).collect();
            let joined = all.join("\n");
            for n in needles {
                assert!(joined.contains(n), "errors {all:?} do not mention `{n}`");
            }
        }
    }
}

fn sys() -> System {
    System::new("Errors")
}

fn spec(name: &str, parent: &str) -> BodySpec {
    BodySpec::new(name, parent)
}

/// A coordinate symbol (not constant), made by adding a body.
fn a_coordinate(sys: &mut System) -> ExprId {
    let mut s = spec("Mover", "N");
    s.joint.rotation = Rotation::Simple(Axis::A1);
    sys.add_body(s).unwrap();
    let q = sys.coordinates().last().unwrap().q;
    sys.arena.sym(q)
}

#[test]
fn unknown_parent() {
    let mut s = sys();
    assert_err(
        s.add_body(spec("A", "Nowhere")),
        &["unknown body", "`Nowhere`"],
    );
    assert_errs(
        s.add_bodies(vec![spec("A", "N"), spec("B", "Ghost")]),
        &["unknown body", "`Ghost`"],
    );
    // Nothing was added by the failed calls.
    assert!(s.body_named("A").is_none());
}

#[test]
fn parent_cycles() {
    let mut s = sys();
    assert_errs(
        s.add_bodies(vec![spec("A", "B"), spec("B", "A")]),
        &["cycle", "`A`", "`B`"],
    );
    let mut s = sys();
    let r = s.add_bodies(vec![
        spec("X", "N"),
        spec("C1", "C3"),
        spec("C2", "C1"),
        spec("C3", "C2"),
    ]);
    assert_errs(r, &["cycle", "`C1`", "`C2`", "`C3`"]);
    // A body that is its own parent.
    let mut s = sys();
    assert_errs(s.add_bodies(vec![spec("S", "S")]), &["cycle", "`S`"]);
    // One report per cycle, also with bodies hanging off the cycle.
    let mut s = sys();
    let r = s.add_bodies(vec![spec("A", "B"), spec("B", "A"), spec("D", "A")]);
    let es = r.unwrap_err();
    let cycles = es.iter().filter(|e| err_text(e).contains("cycle")).count();
    assert_eq!(cycles, 1, "{es:?}");
}

#[test]
fn axis_numbers_outside_1_to_3_are_not_axes() {
    // The API takes typed axes: what the language writes as 4 or 0 has no
    // `Axis` to become (the resolver reports it at its span).
    for k in [4, 0, -1] {
        assert_eq!(Axis::number(k), None);
    }
    assert_eq!(Axis::number(2), Some(Axis::A2));
    assert_eq!(Rotation::from_axes(&[Axis::A1, Axis::A2]), None);
    assert_eq!(
        Rotation::from_axes(&[Axis::A3]),
        Some(Rotation::Simple(Axis::A3))
    );
}

#[test]
fn consecutive_rotations_about_one_axis() {
    let mut s = sys();
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A1, Axis::A2]);
    assert_err(s.add_body(b), &["`A`", "same axis"]);
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A3, Axis::A1, Axis::A1]);
    assert_err(s.add_body(b), &["`A`", "same axis"]);
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A3, Axis::A1, Axis::A3]);
    s.add_body(b).expect("3-1-3 is a sequence");
}

#[test]
fn fixed_rotation_angles() {
    let mut s = sys();
    let q = a_coordinate(&mut s);
    let mut b = spec("A", "N");
    b.fixed_rotations = vec![(FixedTurn::Axis(Axis::A1), q)];
    assert_err(s.add_body(b), &["fixed rotation", "`A`", "constant"]);
}

#[test]
fn translations() {
    let mut s = sys();
    let mut b = spec("A", "N");
    b.joint.translations = vec![Direction::Axis(Axis::A1); 4];
    assert_err(s.add_body(b), &["`A`", "4 translations"]);
    let mut b = spec("A", "N");
    b.joint.translations = vec![Direction::Axis(Axis::A2), Direction::Axis(Axis::A2)];
    assert_err(s.add_body(b), &["already translates along axis 2"]);
    let zero = s.arena.zero();
    let mut b = spec("A", "N");
    b.joint.translations = vec![Direction::Vector([zero; 3])];
    assert_err(s.add_body(b), &["`A`", "zero vector"]);
    let q = a_coordinate(&mut s);
    let mut b = spec("A", "N");
    b.joint.translations = vec![Direction::Vector([q, zero, zero])];
    assert_err(s.add_body(b), &["translation direction", "`A`", "constant"]);
}

#[test]
fn duplicate_names() {
    let mut s = sys();
    s.add_body(spec("A", "N")).unwrap();
    assert_err(s.add_body(spec("A", "N")), &["`A`", "defined twice"]);
    assert_errs(
        s.add_bodies(vec![spec("B", "N"), spec("B", "N")]),
        &["`B`", "defined twice"],
    );
    s.add_parameter("k", 1.0, None).unwrap();
    assert_err(s.add_parameter("k", 2.0, None), &["`k`", "defined twice"]);
    // Parameters, bodies, points and inputs share one name space.
    assert_err(s.add_parameter("A", 2.0, None), &["`A`", "defined twice"]);
    assert_err(s.add_input("k", 0.0, None), &["`k`", "defined twice"]);
    let zero = s.arena.zero();
    let a = s.body_named("A").unwrap();
    s.add_point("P", a, [zero; 3]).unwrap();
    assert_err(s.add_point("P", a, [zero; 3]), &["`P`", "defined twice"]);
    assert_err(s.add_point("k", a, [zero; 3]), &["`k`", "defined twice"]);
    // The time symbol and generated coordinate names are taken too.
    assert_err(s.add_parameter("t", 1.0, None), &["`t`", "defined twice"]);
    let mut b = spec("C", "N");
    b.joint.rotation = Rotation::Simple(Axis::A2);
    s.add_body(b).unwrap();
    assert_err(s.add_parameter("q1", 1.0, None), &["`q1`", "defined twice"]);
    // Coordinate names that collide with a parameter.
    let mut b = spec("D", "N");
    b.joint.rotation = Rotation::Simple(Axis::A1);
    b.coordinate_names = Some(vec!["k".to_string()]);
    assert_err(s.add_body(b), &["`k`", "defined twice"]);
    // Forces and moments by name.
    let v = s.unit_vector(a, Axis::A1);
    let p = s.point_named("P").unwrap();
    s.add_force("F", p, None, v.clone()).unwrap();
    assert_err(
        s.add_force("F", p, None, v.clone()),
        &["`F`", "defined twice"],
    );
    assert_err(s.add_moment("F", a, None, v), &["`F`", "defined twice"]);
}

#[test]
fn non_constant_geometry_and_mass() {
    let mut s = sys();
    let q = a_coordinate(&mut s);
    let zero = s.arena.zero();
    let mut b = spec("A", "N");
    b.joint_point = Some([q, zero, zero]);
    assert_err(s.add_body(b), &["joint coordinates", "`A`", "constant"]);
    let mut b = spec("A", "N");
    b.cm = Some([zero, q, zero]);
    assert_err(s.add_body(b), &["mass center", "`A`", "constant"]);
    let mut b = spec("A", "N");
    b.mass = Some(q);
    assert_err(s.add_body(b), &["mass", "`A`", "constant"]);
    let mut b = spec("A", "N");
    let mut m = [[zero; 3]; 3];
    m[1][2] = q;
    b.inertia = Some(m);
    assert_err(s.add_body(b), &["inertia", "`A`", "constant"]);
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Simple(Axis::A1);
    b.initial_coordinates = Some(vec![q]);
    assert_err(s.add_body(b), &["initial coordinate", "`A`", "constant"]);
    // Time and inputs are not constant either.
    let t = s.arena.sym(s.time());
    let mut b = spec("A", "N");
    b.joint_point = Some([zero, zero, t]);
    assert_err(s.add_body(b), &["joint coordinates", "constant"]);
    let i = s.add_input("steer", 0.0, None).unwrap();
    let i = s.arena.sym(i);
    let mut b = spec("A", "N");
    b.mass = Some(i);
    assert_err(s.add_body(b), &["mass", "constant"]);
}

#[test]
fn wrong_name_counts() {
    let mut s = sys();
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A2, Axis::A3]);
    b.coordinate_names = Some(vec!["a".into(), "b".into()]);
    assert_err(
        s.add_body(b),
        &["`A`", "3 degrees of freedom", "2 coordinate"],
    );
    let mut b = spec("A", "N");
    b.joint.translations = vec![Direction::Axis(Axis::A1)];
    b.speed_names = Some(vec!["a".into(), "b".into()]);
    assert_err(s.add_body(b), &["`A`", "1 degree of freedom", "2 speed"]);
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Simple(Axis::A3);
    b.initial_speeds = Some(vec![]);
    assert_err(s.add_body(b), &["`A`", "initial speed"]);
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Simple(Axis::A3);
    b.small = vec![true, false];
    assert_err(s.add_body(b), &["`A`", "small flags"]);
    // A name given twice within one body.
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A2, Axis::A3]);
    b.coordinate_names = Some(vec!["a".into(), "a".into(), "c".into()]);
    assert_err(s.add_body(b), &["`a`", "defined twice"]);
}

#[test]
fn the_inertial_frame() {
    let mut s = sys();
    assert_err(s.add_body(spec("N", "N")), &["`N`", "inertial frame"]);
    assert_errs(
        s.add_bodies(vec![spec("A", "N"), spec("N", "A")]),
        &["`N`", "inertial frame"],
    );
    assert_err(s.add_parameter("N", 1.0, None), &["`N`", "defined twice"]);
}

/// Bodies share the name space of parameters, inputs and points (as
/// `add_parameter` and `add_point` already check the other way round).
#[test]

fn body_names_share_the_name_space() {
    let mut s = sys();
    s.add_parameter("k", 1.0, None).unwrap();
    assert_err(s.add_body(spec("k", "N")), &["`k`", "defined twice"]);
    assert_err(s.add_body(spec("t", "N")), &["`t`", "defined twice"]);
}

#[test]

fn failed_bodies_leave_no_trace() {
    // A rejected body must not leave symbols behind that make a corrected
    // retry fail.
    let mut s = sys();
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A1, Axis::A2]);
    assert!(s.add_body(b).is_err());
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A2, Axis::A3]);
    b.coordinate_names = Some(vec!["x".into(), "y".into(), "x".into()]);
    assert!(s.add_body(b).is_err());
    let mut b = spec("A", "N");
    b.joint.rotation = Rotation::Sequence([Axis::A1, Axis::A2, Axis::A3]);
    b.coordinate_names = Some(vec!["x".into(), "y".into(), "z".into()]);
    s.add_body(b).expect("a corrected body is accepted");
    assert_eq!(s.coordinates().len(), 3);
    // A non-constant mass is found after the body's coordinates exist.
    let q = s.arena.sym(s.coordinates()[0].q);
    let mut b = spec("B", "N");
    b.joint.rotation = Rotation::Simple(Axis::A2);
    b.mass = Some(q);
    assert_err(s.add_body(b), &["mass", "constant"]);
    let mut b = spec("B", "N");
    b.joint.rotation = Rotation::Simple(Axis::A2);
    s.add_body(b).expect("the next body is accepted");
    s.equations().unwrap();
}

// ----- random specifications never panic -----

#[derive(Clone, Debug)]
struct RandomSpec {
    name: usize,
    parent: usize,
    translations: Vec<(usize, Option<[i8; 3]>)>,
    rotations: Vec<usize>,
    small: Vec<bool>,
    names: Option<usize>,
    joint_kind: u8,
    mass_kind: u8,
    quaternion: bool,
    locked: Vec<bool>,
}

const NAMES: [&str; 6] = ["A", "B", "C", "D", "N", "k"];
const PARENTS: [&str; 7] = ["N", "A", "B", "C", "D", "Z", "k"];

prop_compose! {
    fn random_spec()(
        name in 0..NAMES.len(),
        parent in 0..PARENTS.len(),
        translations in prop::collection::vec(
            (0usize..3, prop::option::of(prop::array::uniform3(-1i8..2))),
            0..5,
        ),
        rotations in prop::collection::vec(0usize..3, 0..5),
        small in prop::collection::vec(any::<bool>(), 0..8),
        names in prop::option::of(0usize..8),
        joint_kind in 0u8..4,
        mass_kind in 0u8..4,
        quaternion in prop::bool::weighted(0.15),
        locked in prop::collection::vec(prop::bool::weighted(0.2), 0..8),
    ) -> RandomSpec {
        RandomSpec {
            name, parent, translations, rotations, small, names, joint_kind, mass_kind, quaternion, locked,
        }
    }
}

fn make_spec(s: &mut System, r: &RandomSpec, serial: usize) -> BodySpec {
    let mut b = spec(NAMES[r.name], PARENTS[r.parent]);
    let zero = s.arena.zero();
    for (axis, vector) in &r.translations {
        b.joint.translations.push(match vector {
            Some(v) => Direction::Vector(v.map(|x| s.arena.int(i64::from(x)))),
            None => Direction::Axis(Axis::from_index(*axis)),
        });
    }
    let axes: Vec<Axis> = r.rotations.iter().map(|k| Axis::from_index(*k)).collect();
    // A random count of axes: 0, 1 and 3 are rotations, others are not.
    b.joint.rotation = match r.quaternion {
        true => Rotation::Quaternion,
        false => Rotation::from_axes(&axes).unwrap_or_default(),
    };
    b.small = r.small.clone();
    b.locked = r.locked.clone();
    if let Some(n) = r.names {
        b.coordinate_names = Some((0..n).map(|k| format!("c{serial}_{k}")).collect());
    }
    let t = s.arena.sym(s.time());
    let half = s.arena.rational(1, 2);
    b.joint_point = match r.joint_kind {
        0 => None,
        1 => Some([half, zero, half]),
        2 => Some([t, zero, zero]),
        _ => Some([zero; 3]),
    };
    b.mass = match r.mass_kind {
        0 => None,
        1 => Some(zero),
        2 => Some(t),
        _ => Some(half),
    };
    b
}

/// Error variants whose message must name the body (when they concern one).
fn message_is_specific(e: &ModelError) -> bool {
    let m = err_text(e);
    !m.is_empty() && (m.contains('`') || m.contains("axis") || m.contains("flags"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_specs_never_panic(specs in prop::collection::vec(random_spec(), 1..5), one_by_one in any::<bool>()) {
        let mut s = sys();
        s.add_parameter("k", 1.0, None).unwrap();
        let built: Vec<BodySpec> = specs.iter().enumerate().map(|(i, r)| make_spec(&mut s, r, i)).collect();
        if one_by_one {
            for b in built {
                if let Err(e) = s.add_body(b) {
                    prop_assert!(message_is_specific(&e), "{e}");
                }
            }
        } else if let Err(es) = s.add_bodies(built) {
            prop_assert!(!es.is_empty());
            for e in &es {
                prop_assert!(message_is_specific(e), "{e}");
            }
        }
        // Whatever was accepted gives equations, and accepted bodies are
        // valid: at most 3 translations, no rotation sequence turning about
        // one axis twice in a row.
        let eqs = s.equations();
        prop_assert!(eqs.is_ok(), "{:?}", eqs.err());
        for b in s.bodies().iter().skip(1) {
            prop_assert!(b.joint.translations.len() <= 3);
            if let Rotation::Sequence([a, b, c]) = b.joint.rotation {
                prop_assert!(a != b && b != c);
            }
        }
        let _ = BodyId::N;
    }
}

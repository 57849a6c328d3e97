//! Frames and direction cosines against rotation matrices built
//! independently with nalgebra from the reference-models.md convention:
//! a rotation about axis k by q gives `C_ij = b_i · a_j = R_k(q)ᵀ`, with
//! `R_k` nalgebra's (active, right-handed) rotation about `e_k`, and a body's
//! unit vectors in N are the rows of `C_BN = C_BA C_AN`.

use autosim_core::expr::{Arena, Bindings, ExprId, NoUserFunctions, SymId, SymbolKind};
use autosim_core::mech::{
    Axis, BodyId, BodySpec, Direction, FrameId, Frames, Rotation, System, UvId, Vector,
};
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use proptest::prelude::*;

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(cases),
        ..ProptestConfig::default()
    }
}

/// `C = b_i · a_j` for a rotation about axis `k` (0-based) by `q`.
fn c_axis(k: usize, q: f64) -> Matrix3<f64> {
    let axis = Unit::new_normalize(Vector3::ith(k, 1.0));
    Rotation3::from_axis_angle(&axis, q).matrix().transpose()
}

/// `C_BN` of body-fixed rotations about `axes` (0-based) by `angles`.
fn c_sequence(axes: &[usize], angles: &[f64]) -> Matrix3<f64> {
    let mut c = Matrix3::identity();
    for (k, q) in axes.iter().zip(angles) {
        c = c_axis(*k, *q) * c;
    }
    c
}

/// Evaluates `e` with all symbols of `arena` bound by `vals`.
fn eval(arena: &Arena, e: ExprId, b: &Bindings) -> f64 {
    arena.eval(e, b, &mut NoUserFunctions)
}

/// A unit vector's components in N, from the matrices of its home frame.
fn uv_in_n(frames: &Frames, c_fn: &[Matrix3<f64>], u: UvId) -> Vector3<f64> {
    let uv = frames.uv(u);
    c_fn[uv.home.index()].row(uv.axis).transpose()
}

/// A basis-free vector's components in N.
fn vector_in_n(
    arena: &Arena,
    frames: &Frames,
    c_fn: &[Matrix3<f64>],
    v: &Vector,
    b: &Bindings,
) -> Vector3<f64> {
    v.terms().iter().fold(Vector3::zeros(), |acc, (u, c)| {
        acc + uv_in_n(frames, c_fn, *u) * eval(arena, *c, b)
    })
}

fn assert_close_vec(got: Vector3<f64>, want: Vector3<f64>, what: &str) {
    assert!(
        (got - want).amax() <= 1e-12,
        "{what}: got {got:?}, want {want:?}"
    );
}

#[test]
fn convention_sanity() {
    // reference-models.md: 1-2-3, first row (cb cc, ca sc + sa sb cc,
    // sa sc - ca sb cc), third row (sb, -sa cb, ca cb).
    let (a, b, c) = (0.3f64, -0.7f64, 1.1f64);
    let m = c_sequence(&[0, 1, 2], &[a, b, c]);
    let (sa, ca, sb, cb, sc, cc) = (a.sin(), a.cos(), b.sin(), b.cos(), c.sin(), c.cos());
    let row1 = [cb * cc, ca * sc + sa * sb * cc, sa * sc - ca * sb * cc];
    let row3 = [sb, -sa * cb, ca * cb];
    for j in 0..3 {
        assert!((m[(0, j)] - row1[j]).abs() < 1e-15);
        assert!((m[(2, j)] - row3[j]).abs() < 1e-15);
    }
    // The paper's camera (rotation about axis 1): [[1,0,0],[0,c,s],[0,-s,c]].
    let m = c_axis(0, a);
    assert!((m[(1, 2)] - sa).abs() < 1e-15 && (m[(2, 1)] + sa).abs() < 1e-15);
}

/// A random tree of frames: frame i+1 is its parent (any earlier frame,
/// N included) rotated about a random axis by a random angle.
#[derive(Clone, Debug)]
struct FrameTree {
    parents: Vec<usize>,
    axes: Vec<usize>,
    angles: Vec<f64>,
}

fn frame_tree() -> impl Strategy<Value = FrameTree> {
    (1usize..7)
        .prop_flat_map(|n| {
            (
                (0..n).map(|i| (0..=i).boxed()).collect::<Vec<_>>(),
                prop::collection::vec(0usize..3, n),
                prop::collection::vec(-3.2f64..3.2, n),
            )
        })
        .prop_map(|(parents, axes, angles)| FrameTree {
            parents,
            axes,
            angles,
        })
}

struct Built {
    arena: Arena,
    frames: Frames,
    ids: Vec<FrameId>,
    bindings: Bindings,
    c_fn: Vec<Matrix3<f64>>,
}

fn build(t: &FrameTree) -> Built {
    let mut arena = Arena::new();
    let mut frames = Frames::new();
    let mut ids = vec![FrameId::N];
    let mut syms: Vec<SymId> = Vec::new();
    let mut c_fn = vec![Matrix3::identity()];
    for i in 0..t.parents.len() {
        let s = arena
            .add_symbol(&format!("th{i}"), SymbolKind::Coordinate { index: i })
            .unwrap();
        syms.push(s);
        let q = arena.sym(s);
        let parent = ids[t.parents[i]];
        let f = frames.add_rotated(
            &mut arena,
            parent,
            Axis::from_index(t.axes[i]),
            q,
            &format!("F{i}"),
            &format!("f{i}_"),
        );
        assert_eq!(f.index(), ids.len());
        ids.push(f);
        c_fn.push(c_axis(t.axes[i], t.angles[i]) * c_fn[t.parents[i]]);
    }
    let mut bindings = Bindings::with_defaults(&arena);
    for (s, q) in syms.iter().zip(&t.angles) {
        bindings.set(*s, *q);
    }
    Built {
        arena,
        frames,
        ids,
        bindings,
        c_fn,
    }
}

proptest! {
    #![proptest_config(config(256))]

    /// Every dot and cross product between unit vectors of any two frames.
    #[test]
    fn unit_vector_products_match_rotation_matrices(t in frame_tree()) {
        let mut b = build(&t);
        let uvs: Vec<UvId> = b
            .ids
            .iter()
            .flat_map(|f| b.frames.frame(*f).triad)
            .collect();
        for &u in &uvs {
            for &v in &uvs {
                let (un, vn) = (
                    uv_in_n(&b.frames, &b.c_fn, u),
                    uv_in_n(&b.frames, &b.c_fn, v),
                );
                let d = b.frames.dot(&mut b.arena, u, v);
                let got = eval(&b.arena, d, &b.bindings);
                prop_assert!((got - un.dot(&vn)).abs() <= 1e-12,
                    "{} . {}: {got} vs {}", b.frames.uv(u).name, b.frames.uv(v).name, un.dot(&vn));
                let c = b.frames.cross(&mut b.arena, u, v);
                let got = vector_in_n(&b.arena, &b.frames, &b.c_fn, &c, &b.bindings);
                let want = un.cross(&vn);
                prop_assert!((got - want).amax() <= 1e-12,
                    "{} x {}: {got:?} vs {want:?}", b.frames.uv(u).name, b.frames.uv(v).name);
            }
        }
    }

    /// cosine_matrix(a, b)_ij = a_i · b_j, express_in, dot_vec and cross_vec
    /// on random vectors spread over several frames.
    #[test]
    fn frame_operations_match_rotation_matrices(
        t in frame_tree(),
        picks in prop::collection::vec((0usize..64, 0usize..3, -2.0f64..2.0), 1..6),
        picks2 in prop::collection::vec((0usize..64, 0usize..3, -2.0f64..2.0), 1..6),
        fa in 0usize..64, fb in 0usize..64,
    ) {
        let mut b = build(&t);
        let nf = b.ids.len();
        let (fa, fb) = (fa % nf, fb % nf);
        let c = b.frames.cosine_matrix(&mut b.arena, b.ids[fa], b.ids[fb]);
        let want = b.c_fn[fa] * b.c_fn[fb].transpose();
        for i in 0..3 {
            for j in 0..3 {
                let got = eval(&b.arena, c[i][j], &b.bindings);
                prop_assert!((got - want[(i, j)]).abs() <= 1e-12,
                    "C[{i}][{j}] of F{fa} vs F{fb}: {got} vs {}", want[(i, j)]);
            }
        }
        // Random vectors: sums of numeric multiples of unit vectors.
        let make = |picks: &[(usize, usize, f64)], b: &mut Built| {
            let mut v = Vector::zero();
            let mut vn = Vector3::zeros();
            for (f, k, x) in picks {
                let f = f % nf;
                let u = b.frames.frame(b.ids[f]).triad[*k];
                let coef = b.arena.num(autosim_core::expr::Number::float(*x).unwrap());
                let term = Vector::term(&mut b.arena, u, coef);
                v = v.add(&mut b.arena, &term);
                vn += uv_in_n(&b.frames, &b.c_fn, u) * *x;
            }
            (v, vn)
        };
        let (v1, n1) = make(&picks, &mut b);
        let (v2, n2) = make(&picks2, &mut b);
        let d = b.frames.dot_vec(&mut b.arena, &v1, &v2);
        prop_assert!((eval(&b.arena, d, &b.bindings) - n1.dot(&n2)).abs() <= 1e-11);
        let cr = b.frames.cross_vec(&mut b.arena, &v1, &v2);
        let got = vector_in_n(&b.arena, &b.frames, &b.c_fn, &cr, &b.bindings);
        prop_assert!((got - n1.cross(&n2)).amax() <= 1e-11);
        let comps = b.frames.express_in(&mut b.arena, &v1, b.ids[fa]);
        let want = b.c_fn[fa] * n1;
        for k in 0..3 {
            prop_assert!((eval(&b.arena, comps[k], &b.bindings) - want[k]).abs() <= 1e-11);
        }
        // vector_in(frame, components) is the inverse of express_in.
        let back = b.frames.vector_in(&mut b.arena, b.ids[fa], comps);
        let got = vector_in_n(&b.arena, &b.frames, &b.c_fn, &back, &b.bindings);
        prop_assert!((got - n1).amax() <= 1e-11);
    }
}

// ----- bodies with three rotations, through System::add_body -----

const SEQUENCES: [[i64; 3]; 4] = [[1, 2, 3], [3, 2, 1], [3, 1, 3], [2, 3, 1]];

/// A chain N -> A (one rotation, axis `a_axis`) -> B (three rotations) ->
/// C (no rotation, translation only): B's matrices relative to N and A.
fn body_system(seq: [i64; 3], a_axis: i64) -> System {
    let mut sys = System::new("Frames");
    let mut a = BodySpec::new("A", "N");
    a.joint.rotation = Rotation::Simple(Axis::number(a_axis).unwrap());
    let mut b = BodySpec::new("B", "A");
    b.joint.rotation = Rotation::Sequence(seq.map(|k| Axis::number(k).unwrap()));
    let mut c = BodySpec::new("C", "B");
    c.joint.translations = vec![Direction::Axis(Axis::A2)];
    sys.add_bodies(vec![a, b, c]).unwrap();
    sys
}

fn bind_state(sys: &System, q: &[f64], u: &[f64]) -> Bindings {
    let mut b = Bindings::with_defaults(&sys.arena);
    for (k, c) in sys.coordinates().iter().enumerate() {
        b.set(c.q, q[k]);
        b.set(c.u, u[k]);
    }
    b
}

fn eval_matrix(sys: &System, m: &[[ExprId; 3]; 3], b: &Bindings) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| eval(&sys.arena, m[i][j], b))
}

proptest! {
    #![proptest_config(config(64))]

    /// cosine_matrix(B, N) and (B, A) for the four sequences, and the
    /// kinematical equations: with q̇ from `kinematics`, the numerically
    /// differentiated unit vectors of B obey d b_i/dt = w × b_i with
    /// w = u_a b1 + u_b b2 + u_c b3 (+ the parent's rotation).
    #[test]
    fn three_rotation_bodies_match_rotation_matrices(
        which in 0usize..4, a_axis in 1i64..=3,
        q in prop::collection::vec(-1.4f64..1.4, 5),
        u in prop::collection::vec(-2.0f64..2.0, 5),
    ) {
        let seq = SEQUENCES[which];
        // Stay away from the sequence's singularity (sin q_b = 0 for i-j-i
        // sequences, cos q_b = 0 for i-j-k), where the angle rates blow up
        // and central differences lose their accuracy.
        let conditioning = if seq[0] == seq[2] { q[2].sin() } else { q[2].cos() };
        prop_assume!(conditioning.abs() > 0.2);
        let mut sys = body_system(seq, a_axis);
        let bid = sys.body_named("B").unwrap();
        let aid = sys.body_named("A").unwrap();
        let cid = sys.body_named("C").unwrap();
        let axes: Vec<usize> = seq.iter().map(|a| (*a - 1) as usize).collect();
        let c_an = c_axis((a_axis - 1) as usize, q[0]);
        let c_bn = c_sequence(&axes, &q[1..4]) * c_an;
        let bnd = bind_state(&sys, &q, &u);
        let m = sys.cosine_matrix(bid, BodyId::N);
        let got = eval_matrix(&sys, &m, &bnd);
        prop_assert!((got - c_bn).amax() <= 1e-12, "{seq:?}: {got} vs {c_bn}");
        let m = sys.cosine_matrix(bid, aid);
        let got = eval_matrix(&sys, &m, &bnd);
        prop_assert!((got - c_sequence(&axes, &q[1..4])).amax() <= 1e-12);
        // C does not rotate relative to B.
        let m = sys.cosine_matrix(cid, bid);
        let got = eval_matrix(&sys, &m, &bnd);
        prop_assert!((got - Matrix3::identity()).amax() <= 1e-14);

        // Kinematics: dq/dt, then d/dt of C_BN by central differences.
        let qdot: Vec<f64> = sys
            .coordinates()
            .iter()
            .map(|c| eval(&sys.arena, c.qdot, &bnd))
            .collect();
        let c_at = |h: f64| {
            let qq: Vec<f64> = q.iter().zip(&qdot).map(|(a, b)| a + h * b).collect();
            c_sequence(&axes, &qq[1..4]) * c_axis((a_axis - 1) as usize, qq[0])
        };
        let h = 1e-5;
        let cdot = (c_at(h) - c_at(-h)) / (2.0 * h);
        // w of B in N: A's rotation about n_a plus u_b1 b1 + u_b2 b2 + u_b3 b3.
        let w_n = c_an.row((a_axis - 1) as usize).transpose() * u[0]
            + c_bn.transpose() * Vector3::new(u[1], u[2], u[3]);
        for i in 0..3 {
            let bi = c_bn.row(i).transpose();
            let want = w_n.cross(&bi);
            let got = cdot.row(i).transpose();
            prop_assert!((got - want).amax() <= 1e-7,
                "{seq:?}: d b{}/dt = {got:?}, w x b = {want:?}", i + 1);
        }
        // rot(B) is that angular velocity.
        let w = sys.rot(bid);
        let comps = sys.frames.express_in(&mut sys.arena, &w, FrameId::N);
        let got = Vector3::from_fn(|k, _| eval(&sys.arena, comps[k], &bnd));
        assert_close_vec(got, w_n, "rot(B) in N");
    }
}

//! The satellite's body structures against the paper's Table 8 (Sayers
//! 1991): cosine matrices of the bus B relative to N, the clock C relative
//! to B and the camera D relative to C, the shared unit vectors, and the
//! absolute angular velocities, at random states. The printed formulas are
//! transcribed here and evaluated in f64.

use autosim_core::expr::{Bindings, NoUserFunctions};
use autosim_core::mech::{BodyId, System};
use proptest::prelude::*;

fn satellite() -> System {
    let data = autosim_test_support::load("satellite");
    autosim_test_support::api::satellite(&data["parameters"], false)
}

fn bind(sys: &System, q: &[f64], u: &[f64]) -> Bindings {
    let mut b = Bindings::with_defaults(&sys.arena);
    for (k, c) in sys.coordinates().iter().enumerate() {
        b.set(c.q, q[k]);
        b.set(c.u, u[k]);
    }
    b
}

type M3 = [[f64; 3]; 3];

fn mat_vec(m: &M3, v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (0..3).map(|j| m[i][j] * v[j]).sum())
}

/// Table 8, cos-matrix: bus (q4, q5, q6), clock (q7), camera (q8).
fn table8(q: &[f64]) -> (M3, M3, M3) {
    let (s4, c4) = q[3].sin_cos();
    let (s5, c5) = q[4].sin_cos();
    let (s6, c6) = q[5].sin_cos();
    let (s7, c7) = q[6].sin_cos();
    let (s8, c8) = q[7].sin_cos();
    let bus = [
        [c5 * c6, c4 * s6 + c6 * s5 * s4, s4 * s6 - c4 * c6 * s5],
        [-c5 * s6, c4 * c6 - s5 * s4 * s6, c6 * s4 + c4 * s5 * s6],
        [s5, -c5 * s4, c4 * c5],
    ];
    let clock = [[c7, s7, 0.0], [-s7, c7, 0.0], [0.0, 0.0, 1.0]];
    let camera = [[1.0, 0.0, 0.0], [0.0, c8, s8], [0.0, -s8, c8]];
    (bus, clock, camera)
}

fn check_matrix(sys: &mut System, b: BodyId, a: BodyId, want: &M3, bnd: &Bindings, what: &str) {
    let m = sys.cosine_matrix(b, a);
    for i in 0..3 {
        for j in 0..3 {
            let got = sys.arena.eval(m[i][j], bnd, &mut NoUserFunctions);
            assert!(
                (got - want[i][j]).abs() <= 1e-13,
                "{what}[{}][{}]: {got} vs Table 8 {}",
                i + 1,
                j + 1,
                want[i][j]
            );
        }
    }
}

/// Components of rot(body) along the body's own axes.
fn w_in_body(sys: &mut System, body: BodyId, bnd: &Bindings) -> [f64; 3] {
    let w = sys.rot(body);
    let frame = sys.body(body).frame;
    let c = sys.frames.express_in(&mut sys.arena, &w, frame);
    c.map(|x| sys.arena.eval(x, bnd, &mut NoUserFunctions))
}

fn assert_vec(got: [f64; 3], want: [f64; 3], what: &str) {
    for k in 0..3 {
        assert!(
            (got[k] - want[k]).abs() <= 1e-12,
            "{what}: {got:?} vs Table 8 {want:?}"
        );
    }
}

#[test]
fn unit_vectors_are_shared_as_in_table8() {
    // uvs: B (b1, b2, b3), C (c1, c2, b3), D (c1, d2, d3).
    let sys = satellite();
    let triad = |n: &str| {
        let f = sys.body(sys.body_named(n).unwrap()).frame;
        sys.frames.frame(f).triad
    };
    let (b, c, d) = (triad("B"), triad("C"), triad("D"));
    let names = |t: [autosim_core::mech::UvId; 3]| t.map(|u| sys.frames.uv(u).name.clone());
    assert_eq!(c[2], b[2], "C's third unit vector is b3: {:?}", names(c));
    assert_ne!(c[0], b[0]);
    assert_ne!(c[1], b[1]);
    assert_eq!(d[0], c[0], "D's first unit vector is c1: {:?}", names(d));
    assert_ne!(d[1], c[1]);
    assert_ne!(d[2], c[2]);
    // Names: the engine calls B's third unit vector `b'3` (it belongs to
    // the intermediate frame B' of the 1-2-3 sequence, about whose third
    // axis the last rotation turns); Table 8 calls it b3.
    assert_eq!(names(c)[..2], ["c1", "c2"]);
    assert_eq!(names(d), ["c1", "d2", "d3"]);
    assert_eq!(names(c)[2], names(b)[2]);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn cosine_matrices_and_angular_velocities_match_table8(
        q in prop::collection::vec(-3.2f64..3.2, 10),
        u in prop::collection::vec(-3.0f64..3.0, 10),
    ) {
        let mut sys = satellite();
        let bnd = bind(&sys, &q, &u);
        let id = |sys: &System, n: &str| sys.body_named(n).unwrap();
        let (b, c, d) = (id(&sys, "B"), id(&sys, "C"), id(&sys, "D"));
        let (bus, clock, camera) = table8(&q);
        check_matrix(&mut sys, b, BodyId::N, &bus, &bnd, "bus");
        check_matrix(&mut sys, c, b, &clock, &bnd, "clock");
        check_matrix(&mut sys, d, c, &camera, &bnd, "camera");

        // abs-w. B: u4 b1 + u5 b2 + u6 b3.
        let wb = [u[3], u[4], u[5]];
        assert_vec(w_in_body(&mut sys, b, &bnd), wb, "abs-w of B in b");
        // C: u4 b1 + u5 b2 + (u6 + u7) b3, moved to C's axes with Table 8's
        // clock matrix.
        let wc_b = [u[3], u[4], u[5] + u[6]];
        let wc = mat_vec(&clock, wc_b);
        assert_vec(w_in_body(&mut sys, c, &bnd), wc, "abs-w of C in c");
        // D: u4 b1 + u5 b2 + (u6 + u7) b3 + u8 c1, in D's axes.
        let wd_c = [wc[0] + u[7], wc[1], wc[2]];
        let wd = mat_vec(&camera, wd_c);
        assert_vec(w_in_body(&mut sys, d, &bnd), wd, "abs-w of D in d");
    }
}

/// The paper's `convert-coordinates`: D's mass center coordinates in C's
/// axes equal the camera's cosine matrix applied to them (C_ij = d_i · c_j,
/// so c-components are Cᵀ times d-components).
#[test]
fn convert_coordinates_uses_the_cosine_matrix() {
    let mut sys = satellite();
    let d = sys.body_named("D").unwrap();
    let c = sys.body_named("C").unwrap();
    let coords = sys.body(d).cm;
    let conv = sys.convert_coordinates(coords, d, c);
    let q8 = sys.arena.symbol_named("q8").unwrap();
    let mut b = Bindings::with_defaults(&sys.arena);
    let angle = 0.7_f64;
    b.set(q8, angle);
    let ev = |sys: &System, e| sys.arena.eval(e, &b, &mut NoUserFunctions);
    let (l5, l6) = (0.22, 0.2);
    let d_comp = [0.0, -l5, -l6];
    // Camera: d1 = c1, d2 = cos c2 + sin c3, d3 = -sin c2 + cos c3.
    let (s, co) = angle.sin_cos();
    let want = [
        d_comp[0],
        co * d_comp[1] - s * d_comp[2],
        s * d_comp[1] + co * d_comp[2],
    ];
    for k in 0..3 {
        let got = ev(&sys, conv[k]);
        assert!(
            (got - want[k]).abs() < 1e-14,
            "component {k}: {got} vs {}",
            want[k]
        );
    }
}

//! Euler parameters `(e0, e1, e2, e3)` and body-fixed 1-2-3 angles, for
//! converting the states of a quaternion body to those of an Euler-angle
//! body (the conventions of `tests/reference/models.md`).

/// The Hamilton product `a ⊗ b`.
pub fn mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// The Euler parameters of body-fixed 1-2-3 rotations by `a`, `b`, `c`.
pub fn from_123(a: f64, b: f64, c: f64) -> [f64; 4] {
    let qx = [(a / 2.0).cos(), (a / 2.0).sin(), 0.0, 0.0];
    let qy = [(b / 2.0).cos(), 0.0, (b / 2.0).sin(), 0.0];
    let qz = [(c / 2.0).cos(), 0.0, 0.0, (c / 2.0).sin()];
    mul(mul(qx, qy), qz)
}

/// 1-2-3 angle rates from the body's angular velocity in its own axes.
pub fn rates_123(q: [f64; 3], w: [f64; 3]) -> [f64; 3] {
    let (s2, c2, s3, c3) = (q[1].sin(), q[1].cos(), q[2].sin(), q[2].cos());
    let a = (c3 * w[0] - s3 * w[1]) / c2;
    [a, s3 * w[0] + c3 * w[1], w[2] - s2 * a]
}

/// The distance between two orientations given as Euler parameters (`q`
/// and `-q` are the same orientation).
pub fn distance(a: [f64; 4], b: [f64; 4]) -> f64 {
    let d = |s: f64| {
        (0..4)
            .map(|k| (a[k] - s * b[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    d(1.0).min(d(-1.0))
}

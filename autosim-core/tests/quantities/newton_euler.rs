//! The satellite's kinematics and the Newton–Euler loads of its boom,
//! written here from `tests/reference/models.md` ("satellite") with
//! nalgebra, independently of the compiler: rotation matrices, angular
//! velocities and accelerations body by body from the coordinates, speeds
//! and their rates.

use nalgebra::{Matrix3, Vector3};

/// Rotation by `q` about axis `axis` (1, 2, 3): body components to parent
/// components.
fn rotation(axis: usize, q: f64) -> Matrix3<f64> {
    let (s, c) = q.sin_cos();
    match axis {
        1 => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        2 => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// A body's motion in N: its axes (body components to N components), its
/// origin's position, velocity and acceleration, its angular velocity and
/// acceleration, all in N's components.
#[derive(Clone, Debug)]
pub struct Motion {
    pub axes: Matrix3<f64>,
    pub origin: Vector3<f64>,
    pub velocity: Vector3<f64>,
    pub acceleration: Vector3<f64>,
    pub omega: Vector3<f64>,
    pub alpha: Vector3<f64>,
}

impl Motion {
    /// A child hinged at `joint` (parent axes) turning by `q` about its
    /// axis `axis`, with speed `u = dq/dt` and rate `du`.
    fn hinged(&self, joint: [f64; 3], axis: usize, q: f64, u: f64, du: f64) -> Motion {
        let r = self.axes * Vector3::from(joint);
        let axes = self.axes * rotation(axis, q);
        let e = axes.column(axis - 1).into_owned();
        Motion {
            axes,
            origin: self.origin + r,
            velocity: self.velocity + self.omega.cross(&r),
            acceleration: self.acceleration
                + self.alpha.cross(&r)
                + self.omega.cross(&self.omega.cross(&r)),
            omega: self.omega + e * u,
            alpha: self.alpha + e * du + self.omega.cross(&(e * u)),
        }
    }

    /// The vector from the origin to the point `p` (body axes), in N.
    pub fn arm(&self, p: [f64; 3]) -> Vector3<f64> {
        self.axes * Vector3::from(p)
    }

    /// The velocity of the point `p` (body axes) fixed in the body.
    pub fn velocity_of(&self, p: [f64; 3]) -> Vector3<f64> {
        self.velocity + self.omega.cross(&self.arm(p))
    }

    /// The acceleration of the point `p` (body axes) fixed in the body.
    pub fn acceleration_of(&self, p: [f64; 3]) -> Vector3<f64> {
        let r = self.arm(p);
        self.acceleration + self.alpha.cross(&r) + self.omega.cross(&self.omega.cross(&r))
    }
}

/// A body's mass properties: mass, mass center (body axes), inertia about
/// it (body axes).
#[derive(Clone, Debug)]
pub struct Mass {
    pub mass: f64,
    pub cm: [f64; 3],
    pub inertia: Matrix3<f64>,
}

impl Mass {
    /// The inertia about the mass center in N's components.
    pub fn inertia_in_n(&self, m: &Motion) -> Matrix3<f64> {
        m.axes * self.inertia * m.axes.transpose()
    }

    /// `½ m v*·v* + ½ ω·I·ω`.
    pub fn kinetic_energy(&self, m: &Motion) -> f64 {
        let v = m.velocity_of(self.cm);
        0.5 * self.mass * v.norm_squared() + 0.5 * m.omega.dot(&(self.inertia_in_n(m) * m.omega))
    }

    /// `m v*`.
    pub fn momentum(&self, m: &Motion) -> Vector3<f64> {
        m.velocity_of(self.cm) * self.mass
    }

    /// `I·ω + (r* − p) × m v*`, about the point `p` (N).
    pub fn angular_momentum(&self, m: &Motion, p: &Vector3<f64>) -> Vector3<f64> {
        let r = m.origin + m.arm(self.cm) - p;
        self.inertia_in_n(m) * m.omega + r.cross(&self.momentum(m))
    }

    /// The force `m a*` and the moment about the body's origin
    /// `I·α + ω × I·ω + r* × m a*` that its motion takes.
    pub fn inertia_load(&self, m: &Motion) -> (Vector3<f64>, Vector3<f64>) {
        let i = self.inertia_in_n(m);
        let f = m.acceleration_of(self.cm) * self.mass;
        let moment = i * m.alpha + m.omega.cross(&(i * m.omega)) + m.arm(self.cm).cross(&f);
        (f, moment)
    }
}

/// The satellite's parameters by name.
pub type Parameters<'a> = &'a dyn Fn(&str) -> f64;

/// The bodies B, C, D, E, F of the satellite at coordinates `q`, speeds
/// `u` and rates `du` (q1..q10, u1..u10 of `models.md`).
pub fn satellite_motion(p: Parameters<'_>, q: &[f64], u: &[f64], du: &[f64]) -> [Motion; 5] {
    let axes = rotation(1, q[3]) * rotation(2, q[4]) * rotation(3, q[5]);
    let b = Motion {
        axes,
        origin: Vector3::new(q[0], q[1], q[2]),
        velocity: Vector3::new(u[0], u[1], u[2]),
        acceleration: Vector3::new(du[0], du[1], du[2]),
        omega: axes * Vector3::new(u[3], u[4], u[5]),
        alpha: axes * Vector3::new(du[3], du[4], du[5]),
    };
    let c = b.hinged([0.0; 3], 3, q[6], u[6], du[6]);
    let d = c.hinged([0.0, p("L3"), -p("L1")], 1, q[7], u[7], du[7]);
    let e = b.hinged([0.0, -p("L7"), 0.0], 3, q[8], u[8], du[8]);
    let f = e.hinged([0.0; 3], 1, q[9], u[9], du[9]);
    [b, c, d, e, f]
}

/// The mass properties of B, C, D, F (E is massless).
pub fn satellite_masses(p: Parameters<'_>) -> [Mass; 4] {
    let sym =
        |a: f64, b: f64, c: f64, d: f64, e: f64, f: f64| Matrix3::new(a, b, c, b, d, e, c, e, f);
    [
        Mass {
            mass: p("MB"),
            cm: [0.0; 3],
            inertia: sym(
                p("IB11"),
                p("IB12"),
                p("IB13"),
                p("IB22"),
                p("IB23"),
                p("IB33"),
            ),
        },
        Mass {
            mass: p("MC"),
            cm: [0.0, 0.0, -p("L2")],
            inertia: Matrix3::from_diagonal(&Vector3::new(p("IC"), p("IC"), 0.0)),
        },
        Mass {
            mass: p("MD"),
            cm: [0.0, -p("L5"), -p("L6")],
            inertia: sym(
                p("ID11"),
                p("ID12"),
                p("ID13"),
                p("ID22"),
                p("ID23"),
                p("ID33"),
            ),
        },
        Mass {
            mass: p("MF"),
            cm: [0.0, -p("L8"), 0.0],
            inertia: Matrix3::from_diagonal(&Vector3::new(p("IF1"), p("IF2"), p("IF1"))),
        },
    ]
}

/// The load the bus B exerts on the boom hinge E through E's joint, about
/// E's origin: the subtree E (massless), F takes `m a*` and the moment of
/// its inertia loads, less the two boom moments, which act on F.
pub fn boom_hinge_reaction(
    p: Parameters<'_>,
    q: &[f64],
    u: &[f64],
    motion: &[Motion; 5],
) -> (Vector3<f64>, Vector3<f64>) {
    let [_, _, _, e, f] = motion;
    let boom = &satellite_masses(p)[3];
    let (force, moment_f) = boom.inertia_load(f);
    // F's origin is E's: the moment about it is the same point's.
    let e3 = e.axes.column(2).into_owned();
    let f1 = f.axes.column(0).into_owned();
    let boom1 = e3 * (-p("KB") * q[8] - p("DB") * u[8]);
    let boom2 = f1 * (-p("KB") * q[9] - p("DB") * u[9]);
    (force, moment_f - boom1 - boom2)
}

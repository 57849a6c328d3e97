// A mistake in the model, and code that names the model's items: only the
// mistake is reported (the macro still defines the model's module with its
// type, `Parameters`, `Inputs` and `Externs`).
autosim::model! {
    /// A pendulum with a damped hinge.
    model Pendulum;
    parameters { m = 1 [kg], l = 0.5 [m], g = 9.81 [m/s^2], c = 0.05 [N m s/rad] }
    body P { rotate: 1, mass: m, cm: [0, 0, -l], inertia: 0 }
    moment hinge { on: P, reaction: N, about: n1, magnitude: -c*u(P) }
    gravity = -g*n3;
    output height [m] = dot(pos(P.cm), n3)
    output speed [m/s] = mag(vel(P.cm));
}

struct Controller;
impl pendulum::Externs for Controller {}

fn main() {
    let _model: Option<pendulum::Pendulum> = None;
    let _parameters = pendulum::Parameters::default();
    let _inputs = pendulum::Inputs::default();
}

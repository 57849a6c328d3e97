// A mistake in a model with user code, and a program that uses the model as
// the guide shows (its constructor, parameters, states, the integrator, the
// user code's trait): only the mistake is reported, nothing at the
// program's correct lines (the macro's placeholder module is made of an
// error type the compiler says nothing more about).
autosim::model! {
    model Cart;
    parameters { m = 2 [kg] }
    body B { translate: 1, mass: m }
    extern fn friction(speed [m/s]) -> [N];
    extern sub push(t) -> (f [N], g [N]);
    force drag { on: B, along: n1, magnitude: friction(u(B)) + f + g }
    output where [m] = q(Bx);
}

use autosim::runtime::{Stepper, integrate::Rk4};

struct Coulomb;
impl cart::Externs for Coulomb {
    fn friction(&mut self, speed: f64) -> f64 {
        -0.3 * speed.signum()
    }
    fn push(&mut self, t: f64) -> [f64; 2] {
        [t, 2.0 * t]
    }
}

fn main() {
    let mut model = cart::Cart::with_parameters(cart::Parameters { m: 3.0 }, Coulomb);
    model.parameters.m = 2.5;
    let mut x = [0.0; cart::N_STATES];
    let mut rk4 = Rk4::new();
    rk4.step(&mut model, 0.0, &mut x, 1e-3).unwrap();
    let light: cart::Cart<Coulomb> = cart::Cart::new(Coulomb);
    let outputs: [f64; cart::N_OUTPUTS] = light.outputs(0.0, &x);
    println!("{outputs:?} {:?}", cart::Inputs::default());
}

// A reaction in a load and in a state's derivative (they are computed
// from the loads: only outputs may read them), and a reaction in a model
// with a constraint that does not say where its load acts.
autosim::model! {
    model Arm;
    parameters { L = 1 [m], m = 1 [kg], g = 9.81 [m/s^2], mu = 0.1 }
    body Link { rotate: 3, mass: m, cm: [L, 0, 0], inertia: diag(0.1, 0.1, 0.1) }
    body Slider { translate: [1, 2], mass: m, inertia: 0 }
    let normal = dot(reaction_force(Link), n2);
    moment friction { on: Link, reaction: N, about: n3, magnitude: -mu*normal }
    state wear [N s] { initial: 0, derivative: normal }
    constraint rail [m] { position: dot(pos(Slider), n2) - dot(pos(Slider), n1)^2/L }
    gravity = -g*n2;
    output load [N] = dot(reaction_force(Slider), n1);
}

fn main() {}

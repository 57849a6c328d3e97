// The built-ins' units are known: a force is not a moment, energy is not
// power.
autosim::model! {
    model Arm;
    parameters { L = 1 [m], m = 1 [kg], g = 9.81 [m/s^2] }
    body Link { rotate: 3, mass: m, cm: [L, 0, 0], inertia: diag(0.1, 0.1, 0.1) }
    moment drive { on: Link, reaction: N, about: n3, magnitude: 1 [N m] }
    gravity = -g*n2;
    output a [N m] = dot(reaction_force(Link), n1);
    output b [W] = kinetic_energy() + potential_energy();
    output c [J] = power(drive);
    output d [kg m/s] = dot(angular_momentum(Link), n3);
    output ok [J] = kinetic_energy() + potential_energy() + dot(momentum(), vel(Link.cm));
}

fn main() {}

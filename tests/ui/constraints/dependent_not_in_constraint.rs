autosim::model! {
    model DependentNotInConstraint;
    parameters { L = 1 [m] }
    body A { rotate: 1, q: [q1], u: [u1], mass: 1, inertia: diag(1, 1, 1) }
    body B { parent: A, joint: [0, L, 0], rotate: 1, q: [q2], u: [u2], mass: 1, inertia: diag(1, 1, 1) }
    point P in B at [0, L, 0];
    body C { rotate: 2, q: [q3], u: [u3], mass: 1, inertia: diag(1, 1, 1) }
    constraint tie [rad/s] { speed: u1 - u2, dependent: u3 }
}

fn main() {}

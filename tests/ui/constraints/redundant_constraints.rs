// Two position constraints that say the same thing at the initial state.
autosim::model! {
    model RedundantConstraints;
    body A { rotate: 1, q: [q1], u: [u1], mass: 1, inertia: diag(1, 1, 1) }
    body B { parent: A, joint: [0, 1, 0], rotate: 1, q: [q2], u: [u2], mass: 1, inertia: diag(1, 1, 1) }
    constraint same [rad] { position: q1 - q2 }
    constraint again [rad] { position: 2*q1 - 2*q2 }
}

fn main() {}

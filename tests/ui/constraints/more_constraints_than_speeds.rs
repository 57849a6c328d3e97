// Three constraints on a model with two speeds.
autosim::model! {
    model MoreConstraintsThanSpeeds;
    parameters { L = 1 [m] }
    body A { rotate: 1, q: [q1], u: [u1], mass: 1, inertia: diag(1, 1, 1) }
    body B { parent: A, joint: [0, L, 0], rotate: 1, q: [q2], u: [u2], mass: 1, inertia: diag(1, 1, 1) }
    point P in B at [0, L, 0];
    constraint tip_n2 [m] { position: dot(pos(P), n2) }
    constraint tip_n3 [m] { position: dot(pos(P), n3) }
    constraint stop [rad/s] { speed: u1 }
}

fn main() {}

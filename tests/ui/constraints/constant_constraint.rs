autosim::model! {
    model ConstantConstraint;
    parameters { L = 1 [m] }
    body A { rotate: 1, q: [q1], u: [u1], mass: 1, inertia: diag(1, 1, 1) }
    body B { parent: A, joint: [0, L, 0], rotate: 1, q: [q2], u: [u2], mass: 1, inertia: diag(1, 1, 1) }
    point P in B at [0, L, 0];
    constraint nothing [m] { position: L - 1 }
}

fn main() {}

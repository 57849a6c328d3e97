autosim::model! {
    model MotionOfAState;
    parameters { L = 1 [m] }
    body A { rotate: 1, q: [q1], u: [u1], mass: 1, inertia: diag(1, 1, 1) }
    body B { parent: A, joint: [0, L, 0], rotate: 1, q: [q2], u: [u2], mass: 1, inertia: diag(1, 1, 1) }
    point P in B at [0, L, 0];
    motion drive { coordinate: q1, value: q2*t }
}

fn main() {}

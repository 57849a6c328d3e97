autosim::model! {
    model SpeedNotLinear;
    parameters { L = 1 [m] }
    body A { rotate: 1, q: [q1], u: [u1], mass: 1, inertia: diag(1, 1, 1) }
    body B { parent: A, joint: [0, L, 0], rotate: 1, q: [q2], u: [u2], mass: 1, inertia: diag(1, 1, 1) }
    point P in B at [0, L, 0];
    // A rolling condition must be linear in the speeds.
    constraint roll [m/s] { speed: u1*u2 }
}

fn main() {}

// Mistakes inside single constraint and motion statements: each is
// reported at its own expression, all in one compile.
autosim::model! {
    model StatementErrors;
    parameters { L = 1 [m] }
    body A { rotate: 1, q: [q1], u: [u1], mass: 1, inertia: diag(1, 1, 1) }
    body B { parent: A, joint: [0, L, 0], rotate: 1, q: [q2], u: [u2], mass: 1, inertia: diag(1, 1, 1) }
    body C { rotate: 2, q: [q3], u: [u3], mass: 1, inertia: diag(1, 1, 1) }
    // Restricts nothing.
    constraint nothing [m] { position: L - 1 }
    // The named dependent speed is not in the constraint.
    constraint tie [rad/s] { speed: u1 - u2, dependent: u3 }
    // A rolling condition must be linear in the speeds.
    constraint roll [rad^2/s^2] { speed: u1*u2 }
    // A motion is a function of time and parameters only.
    motion drive { coordinate: q1, value: q2 + 0.1 [rad/s]*t }
}

fn main() {}

// A misspelt parent: one error, at it; the body's speed, named in an
// event's reset and an output, adds none (the body's error says what is
// wrong).
autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    body Lower { parent: Uper, rotate: 1, u: [w] }
    event stop [rad] { indicator: q(Upper) - 1, reset: { w: -0.5*w } }
    output spin [rad/s] = w;
}

fn main() {}

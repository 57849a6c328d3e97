// A position constraint whose gradient vanishes at the initial state (a
// point on a circle, started at its centre): singular there only, so the
// message says to start elsewhere, not to remove a constraint.
autosim::model! {
    model Ring;
    body P { translate: [1, 2], q: [x, y], mass: 1, inertia: 0 }
    constraint circle [m^2] { position: x^2 + y^2 - 1 }
}

fn main() {}

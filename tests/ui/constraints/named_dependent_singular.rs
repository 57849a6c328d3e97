// Dependents named with `dependent:` are checked at the initial
// configuration too: a point on a circle started at its centre (the
// constraint's gradient is zero there, whatever the dependent), and one
// started at (1, 0) with `y` named (its coefficient is zero there).
autosim::model! {
    model Centre;
    body P { translate: [1, 2], q: [x, y], mass: 1, inertia: 0 }
    constraint circle [m^2] { position: x^2 + y^2 - 1, dependent: x }
}

autosim::model! {
    model Side;
    body P { translate: [1, 2], q: [x, y], initial: [1, 0], mass: 1, inertia: 0 }
    constraint circle [m^2] { position: x^2 + y^2 - 1, dependent: y }
}

fn main() {}

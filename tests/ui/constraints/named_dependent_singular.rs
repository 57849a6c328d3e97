// A constraint whose dependent is named with `dependent:` is checked at
// the initial configuration too: a point on a circle started at its
// centre (the constraint's gradient is zero there, whatever the
// dependent) is singular there, as without `dependent:`.
autosim::model! {
    model Centre;
    body P { translate: [1, 2], q: [x, y], mass: 1, inertia: 0 }
    constraint circle [m^2] { position: x^2 + y^2 - 1, dependent: x }
}

fn main() {}

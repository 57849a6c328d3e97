// A sum of quantities of different units: `m` is a mass, `x` a length.
autosim::model! {
    model Cart;
    parameters { m = 2 [kg], k = 10 [N/m] }
    body B { translate: 1, q: [x], u: [v], mass: m, inertia: 0 }
    force spring { on: B, along: n1, magnitude: m + x }
}

fn main() {}

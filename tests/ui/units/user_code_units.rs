// A user function's result is dimensionless unless its signature says
// otherwise; an argument with a declared unit is checked.
autosim::model! {
    model Cart;
    extern fn friction(speed);
    extern fn spring(stretch [m]) -> [N];
    body B { translate: 1, q: [x], u: [v], mass: 1, inertia: 0 }
    force drag { on: B, along: n1, magnitude: friction(v) }
    force pull { on: B, along: n1, magnitude: spring(v) }
}

fn main() {}

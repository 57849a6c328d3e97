// Constants that fold to infinity or NaN are errors where they are
// written, never a silent `f64::INFINITY` or NaN in generated code.
autosim::model! {
    model Bad;
    body A { translate: 1, q: [x], mass: 1, inertia: 0 }
    output huge = 2^100000*x;
    output root = sqrt(-1)*x;
    output log = ln(0)*x;
    output angle = acos(2) + x;
}

autosim::model! {
    model Start;
    body A { translate: 1, q: [x], mass: 1, inertia: 0, initial: [(10)^400] }
}

fn main() {}

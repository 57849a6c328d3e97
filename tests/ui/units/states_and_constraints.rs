// An added state's derivative must be its unit per second; a constraint's
// expression its declared unit; a motion its coordinate's unit.
autosim::model! {
    model Slider;
    input F [N];
    parameters { L = 1 [m], tau = 0.1 [s] }
    body C { rotate: 1, q: [q1], u: [u1], mass: 1, cm: [0, 1, 0], inertia: 0 }
    body S { translate: 2, q: [y], u: [vy], mass: 1, inertia: 0 }
    state lag [N] { initial: 0, derivative: F - lag }
    constraint pin [m] { position: y - q1 }
    motion drive { coordinate: q1, value: 2*t }
}

fn main() {}

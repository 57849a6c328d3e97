// Units of events: the indicator in its declared unit, each new value in
// the unit of the variable it is assigned to.
autosim::model! {
    model Ball;
    parameters { g = 9.81 [m/s^2], e = 0.8 [1] }
    discrete toff [s] = 0;
    body B { translate: 3, q: [h], u: [v], mass: 1, inertia: 0, initial: [1] }
    gravity = -g*n3;
    event bounce [s] { indicator: h, direction: falling, reset: { v: -e*h }, set: { toff: v } }
}

fn main() {}

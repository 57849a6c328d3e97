// An event may call an `extern fn`, but not read an `extern sub`'s outputs.
autosim::model! {
    model Ball;
    parameters { g = 9.81 [m/s^2] }
    extern fn restitution(speed [m/s]);
    extern sub floor(t) -> (level [m]);
    body B { translate: 3, q: [h], u: [v], mass: 1, inertia: 0, initial: [1] }
    gravity = -g*n3;
    event bounce [m] { indicator: h - level, direction: falling, reset: { v: -restitution(-v)*v } }
}

/// A constrained model: the dependent coordinate cannot be reset.
mod slider {
    autosim::model! {
        model Slider;
        parameters { L = 1 [m] }
        body A { translate: [1, 2], q: [x, y], u: [ux, uy], mass: 1, inertia: 0, initial: [0, 1] }
        constraint on_line [m] { position: y - L, dependent: y }
        event stop_x [m] { indicator: x - 1, direction: rising, reset: { y: 0 } }
    }
}

fn main() {}

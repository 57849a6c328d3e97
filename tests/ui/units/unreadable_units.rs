// Units that do not read, and a unit with a factor where the value is not
// converted (an input or a user function's result is passed in SI units);
// each is then read in rad, so the moments that use them add no error.
autosim::model! {
    model Arm;
    parameters { L = 1 [furlong], c = 2 [m/s/s], a = 30 [deg], k = 2 [N m/rad] }
    body Link { rotate: 3, q: [th], u: [w], mass: 1, cm: [1, 0, 0], inertia: 0 }
    input command [deg];
    moment servo { on: Link, about: n3, magnitude: k*command }
    extern fn aim(time [s]) -> [deg];
    moment tracker { on: Link, about: n2, magnitude: k*aim(t) }
}

fn main() {}

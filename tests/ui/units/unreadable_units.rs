// Units that do not read, and a unit with a factor where the value is not
// converted (an input is passed in SI units).
autosim::model! {
    model Arm;
    parameters { L = 1 [furlong], c = 2 [m/s/s], a = 30 [deg] }
    body Link { rotate: 3, q: [th], u: [w], mass: 1, cm: [1, 0, 0], inertia: 0 }
    input command [deg];
}

fn main() {}

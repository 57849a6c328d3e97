autosim::model! {
    model Arm;
    parameters { g = 9.81 [m/s^2] }
    body Upper { rotate: 1, cm: [0, 0, -1] }
    gravity = -g*n0;
}

fn main() {}

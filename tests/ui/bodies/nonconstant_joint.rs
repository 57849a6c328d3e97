autosim::model! {
    model Arm;
    parameters { L = 1 [m] }
    body Upper { rotate: 1 }
    body Lower { parent: Upper, joint: [0, 0, -L*q(Upper)], rotate: 1 }
}

fn main() {}

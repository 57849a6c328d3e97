autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    body Lower { parent: Upper, joint: [0, 0, -q(Upper)], rotate: 1 }
}

fn main() {}

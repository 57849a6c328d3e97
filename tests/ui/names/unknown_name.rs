autosim::model! {
    model Arm;
    parameters { stiffness = 100 [N m/rad] }
    body Upper { rotate: 1 }
    moment spring { on: Upper, about: n1, magnitude: -stifness*q(Upper) }
}

fn main() {}

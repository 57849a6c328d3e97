autosim::model! {
    model Arm;
    parameters { k = 100 [N m/rad] }
    body Upper { rotate: 1 }
    moment spring { on: Upper, about: n1, magnitude: -k(q(Upper) - 0.1) }
}

fn main() {}

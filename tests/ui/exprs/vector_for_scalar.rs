autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    moment drive { on: Upper, about: n1, magnitude: n1 }
}

fn main() {}

autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    moment drive { on: Upper, about: 3, magnitude: 1 }
}

fn main() {}

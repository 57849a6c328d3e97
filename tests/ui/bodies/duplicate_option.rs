autosim::model! {
    model Arm;
    body Upper { rotate: 1, mass: 2, rotate: 3 }
}

fn main() {}

autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    body Lower { parent: Uper, rotate: 1 }
}

fn main() {}

autosim::model! {
    model Arm;
    body Upper { parent: Lower, rotate: 1 }
    body Lower { parent: Upper, rotate: 1 }
}

fn main() {}

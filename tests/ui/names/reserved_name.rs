autosim::model! {
    model Arm;
    parameters { t = 1 [s] }
    body Upper { rotate: 1 }
}

fn main() {}

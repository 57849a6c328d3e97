autosim::model! {
    model Arm;
    body Upper { rotate = 1 }
}

fn main() {}

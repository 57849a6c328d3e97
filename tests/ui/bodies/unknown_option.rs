autosim::model! {
    model Arm;
    body Upper { rotat: 1 }
}

fn main() {}

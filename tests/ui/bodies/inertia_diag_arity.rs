autosim::model! {
    model Arm;
    body Upper { rotate: 1, inertia: diag(1) }
}

fn main() {}

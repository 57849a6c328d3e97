autosim::model! {
    model Gimbal;
    body Frame { rotate: [1, 2] }
}

fn main() {}

autosim::model! {
    model Gimbal;
    body Frame { rotate: [1, 4, 3] }
}

fn main() {}

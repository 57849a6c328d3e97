autosim::model! {
    model double_pendulum;
    body Upper { rotate: 1 }
}

fn main() {}

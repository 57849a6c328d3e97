autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    moment motor { on: Hand, reaction: Upper, about: n1, magnitude: 1 }
}

fn main() {}

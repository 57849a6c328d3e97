autosim::model! {
    model Arm;
    parameters { F = 10 [N] }
    body Upper { rotate: 1 }
    force push { on: F, along: n2, magnitude: F }
}

fn main() {}

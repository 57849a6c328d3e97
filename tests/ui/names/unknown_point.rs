autosim::model! {
    model Arm;
    parameters { F = 10 [N] }
    body Upper { rotate: 1 }
    point tip in Upper at [0, 0, -1];
    force push { on: tp, along: n2, magnitude: F }
}

fn main() {}

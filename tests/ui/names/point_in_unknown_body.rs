autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    point tip in Uper at [0, 0, -1];
    output height [m] = dot(pos(tip), n3);
}

fn main() {}

autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    output height [m] = dot(pos(Upper.tip), n3);
}

fn main() {}

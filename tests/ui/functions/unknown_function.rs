autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    output height [m] = cso(q(Upper));
}

fn main() {}

autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    output ratio = mag(vel(Upper.cm) / rot(Upper));
}

fn main() {}

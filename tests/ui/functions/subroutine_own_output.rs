autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    extern sub control(t, torque) -> (torque [N m]);
    moment drive { on: Upper, about: n1, magnitude: torque }
}

fn main() {}

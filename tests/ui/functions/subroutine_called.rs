autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    extern sub control(t, q(Upper)) -> (torque [N m]);
    moment drive { on: Upper, about: n1, magnitude: control(t, q(Upper)) }
}

fn main() {}

autosim::model! {
    model Arm;
    parameters { m = 1 [kg] }
    body Upper { rotate: 1 }
    moment inertia_torque { on: Upper, about: n1, magnitude: -m*dxdt(u(Upper)) }
}

fn main() {}

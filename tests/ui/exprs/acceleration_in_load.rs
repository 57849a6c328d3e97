autosim::model! {
    model Arm;
    parameters { J = 1 [kg m^2] }
    body Upper { rotate: 1 }
    moment inertia_torque { on: Upper, about: n1, magnitude: -J*dxdt(u(Upper)) }
}

fn main() {}

autosim::model! {
    model Arm;
    parameters { m = 1e999 [kg] }
    body Upper { rotate: 1, mass: m }
    output big = 1e40*q(Upper);
}

fn main() {}

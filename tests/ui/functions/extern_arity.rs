autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    extern fn f(a, b) -> [N m];
    moment drive { on: Upper, about: n1, magnitude: f(t, q(Upper), u(Upper)) }
}

fn main() {}

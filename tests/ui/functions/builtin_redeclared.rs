autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    extern fn sin(x);
}

fn main() {}

autosim::model! {
    model Arm;
    body Upper { rotate: 1 }
    let a = 2*b;
    let b = a + 1;
    output x = a;
}

fn main() {}

autosim::model! {
    model Arm;
    parameters { k = 100 [N m/rad], c = 1 [N m s/rad] }
    body Upper { rotate: 1 }
    let k = 2*c;
}

fn main() {}

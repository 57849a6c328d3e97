autosim::model! {
    model Gimbal;
    body Frame { rotate: [1, 2, 3] }
    output angle [rad] = q(Frame);
}

fn main() {}

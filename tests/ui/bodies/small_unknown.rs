autosim::model! {
    model Arm;
    body Upper { rotate: 1, small: bogus }
}

fn main() {}

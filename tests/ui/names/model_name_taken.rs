autosim::model! {
    model Parameters;
    body Upper { rotate: 1 }
}

fn main() {}

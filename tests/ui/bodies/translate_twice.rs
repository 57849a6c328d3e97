autosim::model! {
    model Cart;
    body Base { translate: [1, 1] }
}

fn main() {}

autosim::model! {
    parameters { m = 1 [kg] }
    body P { rotate: 1, mass: m }
}

fn main() {}

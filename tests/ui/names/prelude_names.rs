// Names of Rust's prelude that generated code uses unqualified: a model
// named `Result` and a coordinate named `Some`, `Ok`, `Err` or `None` broke
// rustc with errors spanning the whole macro call; now each is reported
// where it is written.
autosim::model! {
    model Result;
    body A { translate: 1, mass: 1, inertia: 0 }
}

autosim::model! {
    model Variants;
    parameters { Ok = 1 [kg] }
    body A { translate: [1, 2], q: [Some, None], mass: 1, inertia: 0 }
}

fn main() {}

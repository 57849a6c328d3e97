autosim::model! {
    /// A slider with neither mass nor inertia: its mass matrix is singular
    /// whatever the state, so the compiler says so.
    model Slider;
    body Cart { translate: 1, mass: 0, inertia: 0 }
}

fn main() {}

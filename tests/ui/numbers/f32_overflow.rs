// In an `f32` model a constant beyond f32's range (about 3.4e38) would be
// infinite: the fuzzer's case panicked the macro (proc-macro2 asserts its
// literals are finite); now each is a diagnostic.
autosim::model! {
    model M;
    settings { float: f32 }
    parameters { k = 1e300 [N/m] }
    body A { translate: 1, q: [x], mass: 1, inertia: 0 }
    output y = sqrt(x*x + 10^20*10^20);
    output z = k*x;
}

fn main() {}

// Each number fits f32, but the mass matrix's m l^2 = 1e57 does not.
autosim::model! {
    model Far;
    settings { float: f32 }
    body B { rotate: 3, mass: 10^19, cm: [10^19, 0, 0], inertia: 0 }
}

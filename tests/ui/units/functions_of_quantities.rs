// The sine of a length, a power that is not a constant number, `min` of a
// length and a mass, and an exponential of a time.
autosim::model! {
    model Arm;
    parameters { L = 1 [m], m = 1 [kg], n = 2 }
    body Link { rotate: 3, q: [th], u: [w], mass: m, cm: [L, 0, 0], inertia: 0 }
    output a = sin(L);
    output b = L^n*th^th;
    output c = min(L, m);
    output d = exp(-t);
}

fn main() {}

// An output declared in J whose expression is a sum of a length and a
// speed (reported once: the sum itself is wrong), and one in J that is a
// length.
autosim::model! {
    model Cart;
    parameters { m = 2 [kg] }
    body B { translate: 1, q: [x], u: [v], mass: m, inertia: 0 }
    output energy [J] = x + v;
    output kinetic [J] = m*v;
}

fn main() {}

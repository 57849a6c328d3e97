// A force and a constraint with mistakes: their own errors are reported,
// and `power` and `constraint_force` of them add none (they named the
// wrong kind of item before).
autosim::model! {
    model Slider;
    parameters { k = 10 [N/m], m = 1 [kg] }
    body B { translate: [1, 2], q: [x, y], mass: m, inertia: 0 }
    force spring { on: B, along: n1, magnitude: -k*presure(x) }
    constraint rail [m] { position: y, dependent: yy }
    output p [W] = power(spring);
    output f [N] = constraint_force(rail);
}

fn main() {}

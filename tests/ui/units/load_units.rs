// A moment whose magnitude is a damping coefficient times an angular speed
// without its unit, a force vector in N m, and gravity given as a length.
autosim::model! {
    model Arm;
    parameters { L = 1 [m], m = 1 [kg], c = 0.1 [N m s/rad], k = 5 [N m/rad] }
    body Link { rotate: 3, q: [th], u: [w], mass: m, cm: [L, 0, 0], inertia: 0 }
    moment damper { on: Link, about: n3, magnitude: -0.01*w }
    force push { on: Link.cm, vector: k*th*n1 }
    gravity = -L*n3;
}

fn main() {}

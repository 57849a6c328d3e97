// A rolling disc that also declares the vertical component of no-slip:
// that row is the time derivative of the contact (position) constraint,
// redundant at every configuration; the message says so and to remove it.
autosim::model! {
    model Disc;
    parameters { m = 1 [kg], r = 0.5 [m], g = 9.81 [m/s^2] }
    body D {
        translate: [1, 2, 3], rotate: [3, 1, 2],
        q: [x, y, z, psi, phi, theta], u: [ux, uy, uz, u4, u5, u6],
        mass: m, inertia: diag(m*r^2/4, m*r^2/2, m*r^2/4),
        initial: [0, 0, 0.5, 0, 0.1, 0],
    }
    let contact = -r*dir(n3 - dot(n3, D.2)*D.2);
    let slip = vel(D) + cross(rot(D), contact);
    constraint touch [m] { position: dot(pos(D), n3) - r*cos(phi), dependent: z }
    constraint roll_n1 [m/s] { speed: dot(slip, n1) }
    constraint roll_n2 [m/s] { speed: dot(slip, n2) }
    constraint roll_n3 [m/s] { speed: dot(slip, n3) }
    gravity = -g*n3;
}

fn main() {}

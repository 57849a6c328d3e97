// Reactions of N and of an unknown body, arguments of the wrong kind, too
// many arguments, `power` of something that is not a load, and
// `constraint_force` of something that is not a constraint.
autosim::model! {
    model Arm;
    parameters { L = 1 [m], m = 1 [kg], g = 9.81 [m/s^2] }
    body Link { rotate: 3, mass: m, cm: [L, 0, 0], inertia: 0 }
    gravity = -g*n2;
    output a [N] = dot(reaction_force(N), n1);
    output b [N] = dot(reaction_force(Lnk), n1);
    output c [N] = dot(reaction_force(2*L), n1);
    output d [N m] = dot(reaction_moment(Link, L), n1);
    output e [N] = reaction_force(Link, Link);
    output f [W] = power(Link);
    output h [W] = power(spring);
    output i [J] = kinetic_energy(Link, Link);
    output j [N] = constraint_force(Link);
    output k [N] = constraint_force(rail);
}

fn main() {}

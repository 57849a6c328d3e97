// Every mistake of an event's actions and options, reported at once.
autosim::model! {
    model Ball;
    parameters { g = 9.81 [m/s^2], e = 0.8 }
    input push [N];
    discrete mode = 0;
    body B { translate: 3, q: [h], u: [v], mass: 1, inertia: 0, initial: [1] }
    gravity = -g*n3;
    event no_indicator { direction: falling, set: { mode: 1 } }
    event bad_direction [m] { indicator: h, direction: down, set: { mode: 1 } }
    event set_a_state [m] { indicator: h, set: { v: 0 } }
    event reset_a_mode [m] { indicator: h, reset: { mode: 1 } }
    event reset_a_parameter [m] { indicator: h, reset: { e: 0.5 } }
    event twice [m] { indicator: h, reset: { v: -e*v, v: 0 } }
    event unknown [m] { indicator: h, set: { mood: 1 } }
    event not_a_bool [m] { indicator: h, stop: yes }
    event mode [m] { indicator: h }
}

fn main() {}

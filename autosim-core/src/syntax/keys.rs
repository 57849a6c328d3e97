//! The vocabulary of `key: value` blocks: one enum per block kind, each
//! with the table of its spellings (the parser reports unknown keys against
//! it, with a "did you mean").

/// A key allowed in one kind of `{ key: value }` block.
pub trait OptionKey: Copy + Eq + std::fmt::Debug + 'static {
    /// What the keys are called in messages (`body option`).
    const WHAT: &'static str;
    /// Every key with its spelling, in documentation order.
    const ALL: &'static [(&'static str, Self)];

    /// The key as written in a model.
    fn as_str(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, key)| *key == self)
            .map_or("?", |(text, _)| text)
    }

    /// The key spelled `text`, if any.
    fn from_str(text: &str) -> Option<Self> {
        Self::ALL
            .iter()
            .find(|(spelling, _)| *spelling == text)
            .map(|(_, key)| *key)
    }
}

macro_rules! option_keys {
    ($(#[$meta:meta])* $name:ident, $what:literal { $($(#[$vmeta:meta])* $variant:ident = $text:literal,)* }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum $name {
            $($(#[$vmeta])* $variant,)*
        }

        impl OptionKey for $name {
            const WHAT: &'static str = $what;
            const ALL: &'static [(&'static str, Self)] = &[$(($text, $name::$variant),)*];
        }
    };
}

option_keys! {
    /// Keys of a `body` block.
    BodyKey, "body option" {
        /// `parent: B` — the body this one is attached to (default `N`).
        Parent = "parent",
        /// `joint: [x, y, z]` — the joint point in the parent.
        Joint = "joint",
        /// `translate: [1, 2, 3]` — translation directions (axis index or vector).
        Translate = "translate",
        /// `rotate: [1, 2, 3]` — body-fixed rotation axes; `rotate: [[x, y, z]]`
        /// — a rotation about a constant direction of the parent.
        Rotate = "rotate",
        /// `reference: [x, y, z]` — the reference direction of a rotation
        /// about a direction (the body's axis 2 is along `axis × reference`).
        Reference = "reference",
        /// `small: [translations, rotations]` — small-motion assumptions.
        Small = "small",
        /// `lock: [q9]` — degrees of freedom locked at compile time.
        Lock = "lock",
        /// `mass: m`
        Mass = "mass",
        /// `inertia: diag(a, b, c)` or a matrix.
        Inertia = "inertia",
        /// `cm: [x, y, z]` — mass center in body coordinates.
        Cm = "cm",
        /// `q: [x, y]` — names of the generalized coordinates.
        Q = "q",
        /// `u: [vx, vy]` — names of the generalized speeds.
        U = "u",
        /// `initial: [...]` — initial coordinates.
        Initial = "initial",
        /// `initial_speeds: [...]` — initial speeds.
        InitialSpeeds = "initial_speeds",
    }
}

option_keys! {
    /// Keys of a `constraint` block.
    ConstraintKey, "constraint option" {
        /// `position: g` — the configuration must keep `g = 0`.
        Position = "position",
        /// `speed: c` — the motion must keep `c = 0` (linear in the speeds).
        Speed = "speed",
        /// `dependent: q` — the coordinate (or speed) the constraint determines.
        Dependent = "dependent",
    }
}

option_keys! {
    /// Keys of an `event` block.
    EventKey, "event option" {
        /// `indicator: h` — the function whose sign change is the event.
        Indicator = "indicator",
        /// `direction: falling` (or `rising`, `either`).
        Direction = "direction",
        /// `set: { mode: 1 }` — discrete variables given new values.
        Set = "set",
        /// `reset: { v: -e*v }` — states given new values.
        Reset = "reset",
        /// `stop: true` — the run ends at the event.
        Stop = "stop",
    }
}

option_keys! {
    /// Keys of a `motion` block.
    MotionKey, "motion option" {
        /// `coordinate: q` — the coordinate given as a function of time.
        Coordinate = "coordinate",
        /// `value: f(t)` — its value.
        Value = "value",
    }
}

option_keys! {
    /// Keys of a `force` block.
    ForceKey, "force option" {
        /// `on: P` — the point the force acts on.
        On = "on",
        /// `reaction: Q` — the point taking the equal and opposite force.
        Reaction = "reaction",
        /// `vector: F1*b1 + F2*b3` — the whole force vector.
        Vector = "vector",
        /// `along: dir(r)` — direction, with `magnitude`.
        Along = "along",
        /// `magnitude: -k*x` — scalar along `along`.
        Magnitude = "magnitude",
    }
}

option_keys! {
    /// Keys of a `moment` block.
    MomentKey, "moment option" {
        /// `on: F` — the body the moment acts on.
        On = "on",
        /// `reaction: B` — the body taking the opposite moment.
        Reaction = "reaction",
        /// `vector: ...` — the whole moment vector.
        Vector = "vector",
        /// `about: e3` — axis, with `magnitude`.
        About = "about",
        /// `magnitude: ...` — scalar about `about`.
        Magnitude = "magnitude",
    }
}

option_keys! {
    /// Keys of a `state` block.
    StateKey, "state option" {
        /// `initial: 0` — initial value.
        Initial = "initial",
        /// `derivative: (F1 - lag)/tau` — the time derivative.
        Derivative = "derivative",
    }
}

option_keys! {
    /// Keys of the `settings` block.
    SettingKey, "setting" {
        /// `threshold: 2` — order-of-smallness truncation threshold.
        Threshold = "threshold",
        /// `float: f64` or `float: f32`.
        Float = "float",
        /// `outputs: [roll, yaw]` — generate only these outputs.
        Outputs = "outputs",
        /// `linearize: true` — generate `linearize` (A, B, C, D).
        Linearize = "linearize",
        /// `formulation: auto` (or `mass_matrix`, `recursive`).
        Formulation = "formulation",
        /// `lanes: true` — generate `derivatives_lanes` (many states per call).
        Lanes = "lanes",
    }
}

option_keys! {
    /// The scene options of `autosim::model!(file = "...", key = value, ...)`:
    /// what one use of a model sets (the settings it overrides, and more).
    SceneKey, "model option" {
        /// `name = RigidBoom` — a new name for the model and its module.
        Name = "name",
        /// `float = f32` — the float type (overrides the setting).
        Float = "float",
        /// `threshold = 3` — the small-term threshold (overrides the setting).
        Threshold = "threshold",
        /// `outputs = [roll, yaw]` — generate only these outputs.
        Outputs = "outputs",
        /// `small = [B, q9]` — bodies or coordinates made small.
        Small = "small",
        /// `lock = [q9, q10]` — bodies or coordinates locked.
        Lock = "lock",
        /// `linearize = true` — generate `linearize` (overrides the setting).
        Linearize = "linearize",
        /// `formulation = recursive` — how the accelerations are solved
        /// (overrides the setting).
        Formulation = "formulation",
        /// `lanes = true` — generate `derivatives_lanes` (overrides the setting).
        Lanes = "lanes",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spellings_round_trip() {
        for &(text, key) in BodyKey::ALL {
            assert_eq!(key.as_str(), text);
            assert_eq!(BodyKey::from_str(text), Some(key));
        }
        assert_eq!(BodyKey::ALL.len(), 14);
        assert_eq!(ForceKey::from_str("along"), Some(ForceKey::Along));
        assert_eq!(MomentKey::from_str("along"), None);
        assert_eq!(SettingKey::Float.as_str(), "float");
        assert_eq!(StateKey::ALL.len(), 2);
    }
}

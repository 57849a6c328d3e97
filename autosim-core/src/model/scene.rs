//! Scene options: what one use of a model needs, given where the model is
//! used (`autosim::model!(file = "...", lock = [q9], outputs = [roll])`, or
//! the build-script `Config`) rather than in the model file, so one model
//! serves several scenes. They override the model's `settings` and add to
//! its bodies' `small` and `lock` options.

use super::FloatType;
use crate::diag::Span;
use crate::mech::Joint;
use crate::syntax::ast;

/// Options a use site sets on a model.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    /// A new name for the model (and its module), so one file can be
    /// compiled several ways in one crate.
    pub name: Option<ast::Name>,
    /// The float type of generated code.
    pub float: Option<FloatType>,
    /// The small-term threshold.
    pub threshold: Option<i16>,
    /// Only these outputs are generated.
    pub outputs: Option<Vec<ast::Name>>,
    /// Generate `linearize` (overrides the model's `linearize` setting).
    pub linearize: Option<bool>,
    /// Generate `derivatives_lanes` (overrides the model's `lanes` setting).
    pub lanes: Option<bool>,
    /// How the accelerations are solved (overrides the model's setting).
    pub formulation: Option<super::Formulation>,
    /// Bodies (all their degrees of freedom) or coordinates made small.
    pub small: Vec<ast::Name>,
    /// Bodies (all their degrees of freedom) or coordinates locked.
    pub lock: Vec<ast::Name>,
}

impl Scene {
    /// A name with no source location (for options given from Rust code).
    pub fn name(text: &str) -> ast::Name {
        ast::Name {
            text: text.to_string(),
            span: Span::unknown(),
        }
    }

    /// Flags for `small` or `lock` named in the scene for one body with
    /// these coordinate names (translations, then rotations; a quaternion's
    /// `e0` matches no speed), and the names that matched.
    pub(crate) fn flags(
        names: &[ast::Name],
        body: &str,
        coordinates: &[String],
        joint: &Joint,
    ) -> (Vec<bool>, Vec<String>) {
        let mut flags = vec![false; joint.dofs()];
        let mut matched = Vec::new();
        for n in names {
            if n.text == body {
                flags.iter_mut().for_each(|f| *f = true);
                matched.push(n.text.clone());
            } else if let Some(k) = coordinates
                .iter()
                .position(|c| *c == n.text)
                .and_then(|k| joint.speed_of_coordinate(k))
            {
                flags[k] = true;
                matched.push(n.text.clone());
            }
        }
        (flags, matched)
    }
}

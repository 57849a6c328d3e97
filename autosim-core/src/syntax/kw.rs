//! Keywords of the model language (Rust keywords `let`, `extern`, `fn` and
//! `in` are used through `syn::Token!`).

syn::custom_keyword!(model);
syn::custom_keyword!(settings);
syn::custom_keyword!(parameters);
syn::custom_keyword!(parameter);
syn::custom_keyword!(body);
syn::custom_keyword!(point);
syn::custom_keyword!(force);
syn::custom_keyword!(moment);
syn::custom_keyword!(gravity);
syn::custom_keyword!(input);
syn::custom_keyword!(state);
syn::custom_keyword!(output);
syn::custom_keyword!(sub);
syn::custom_keyword!(at);
syn::custom_keyword!(constraint);
syn::custom_keyword!(motion);
syn::custom_keyword!(discrete);
syn::custom_keyword!(event);

/// Words that start an item: used for "did you mean", for error recovery
/// (skip to the next item) and for the missing-`;` check.
pub(crate) const ITEM_STARTS: &[&str] = &[
    "model",
    "settings",
    "parameters",
    "parameter",
    "body",
    "point",
    "let",
    "force",
    "moment",
    "gravity",
    "input",
    "extern",
    "state",
    "output",
    "constraint",
    "motion",
    "discrete",
    "event",
];

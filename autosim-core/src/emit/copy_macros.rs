//! The copy macros of multiversioned functions (`macro_rules!
//! derivatives_copy { ... }`, `emit/model/versions.rs`) formatted as code.
//! prettyplease prints a macro's body as a run of tokens; a copy macro's
//! body is one function, the model's biggest, so the file shows it
//! formatted like every other function instead: each copy macro is set
//! aside before formatting (an empty placeholder keeps its place), its
//! function formatted on its own, and the macro written back around it.

use proc_macro2::{TokenStream, TokenTree};
use quote::quote;

/// The matcher every copy macro has (`versions_of` writes it).
const MATCHER: &str = "($(#[$attr:meta])* $vis:vis $name:ident)";

/// A copy macro set aside: its name and its function formatted (the
/// function's first line without the `$vis fn $name` it starts with).
pub(super) struct Copy {
    name: String,
    function: String,
}

/// Replaces every copy macro in `items` (recursively in modules) with an
/// empty `macro_rules! name { () => {}; }` and returns what it set aside.
/// A macro that does not have a copy macro's shape is left as it is.
pub(super) fn set_aside(items: &mut [syn::Item]) -> Vec<Copy> {
    let mut copies = Vec::new();
    for item in items {
        match item {
            syn::Item::Mod(module) => {
                if let Some((_, inner)) = &mut module.content {
                    copies.extend(set_aside(inner));
                }
            }
            syn::Item::Macro(mac) if mac.mac.path.is_ident("macro_rules") => {
                let Some(name) = mac.ident.as_ref().map(ToString::to_string) else {
                    continue;
                };
                if let Some(function) = formatted_function(&mac.mac.tokens) {
                    let ident = mac.ident.clone();
                    if let Ok(placeholder) =
                        syn::parse2::<syn::ItemMacro>(quote!(macro_rules! #ident { () => {}; }))
                    {
                        *mac = placeholder;
                        copies.push(Copy { name, function });
                    }
                }
            }
            _ => {}
        }
    }
    copies
}

/// Writes the macros set aside back in place of their placeholders in
/// prettyplease's `text`.
pub(super) fn restore(text: &str, copies: &[Copy]) -> String {
    let mut out = text.to_string();
    for copy in copies {
        let head = format!("macro_rules! {} {{\n", copy.name);
        let Some(at) = out.find(&head) else { continue };
        let line_start = out[..at].rfind('\n').map_or(0, |i| i + 1);
        let indent = out[line_start..at].to_string();
        let placeholder = format!("{head}{indent}    () => {{}};\n{indent}}}\n");
        if !out[at..].starts_with(&placeholder) {
            continue;
        }
        let function: String = copy
            .function
            .lines()
            .map(|l| match l.is_empty() {
                true => "\n".to_string(),
                false => format!("{indent}        {l}\n"),
            })
            .collect();
        let written = format!(
            "{head}{indent}    {MATCHER} => {{\n{indent}        $(#[$attr])*\n{function}{indent}    }};\n{indent}}}\n"
        );
        out.replace_range(at..at + placeholder.len(), &written);
    }
    out
}

/// The function of a copy macro's rules (`MATCHER => { $(#[$attr])* $vis
/// fn $name ... }`), formatted, starting `$vis fn $name`; `None` for any
/// other macro.
fn formatted_function(rules: &TokenStream) -> Option<String> {
    let tokens: Vec<TokenTree> = rules.clone().into_iter().collect();
    let [
        TokenTree::Group(matcher),
        TokenTree::Punct(eq),
        TokenTree::Punct(gt),
        TokenTree::Group(body),
        ..,
    ] = &tokens[..]
    else {
        return None;
    };
    let squeeze = |text: String| -> String { text.split_whitespace().collect() };
    if squeeze(matcher.to_string()) != squeeze(MATCHER.to_string())
        || eq.as_char() != '='
        || gt.as_char() != '>'
    {
        return None;
    }
    // `$(#[$attr])* $vis fn $name <rest>`.
    let body: Vec<TokenTree> = body.stream().into_iter().collect();
    let split = body
        .iter()
        .position(|t| matches!(t, TokenTree::Ident(i) if i == "fn"))?;
    let before: TokenStream = body[..split].iter().cloned().collect();
    let name: TokenStream = body.get(split + 1..split + 3)?.iter().cloned().collect();
    if squeeze(before.to_string()) != "$(#[$attr])*$vis" || squeeze(name.to_string()) != "$name" {
        return None;
    }
    let rest: TokenStream = body[split + 3..].iter().cloned().collect();
    let file: syn::File = syn::parse2(quote!(impl __Copy { fn __autosim_copy_name #rest })).ok()?;
    let text = prettyplease::unparse(&file);
    let inner: Vec<&str> = text.lines().collect();
    let function = inner.get(1..inner.len().checked_sub(1)?)?;
    let mut out = String::new();
    for line in function {
        let line = line.strip_prefix("    ").unwrap_or(line);
        out.push_str(&line.replacen("fn __autosim_copy_name", "$vis fn $name", 1));
        out.push('\n');
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::super::file::format_tokens;
    use quote::quote;

    /// Tokens without their spacing, and without the trailing commas
    /// prettyplease adds where it breaks a list over lines, to compare a
    /// file with what it was formatted from.
    fn squeezed(text: &str) -> String {
        let file: syn::File = syn::parse_str(text).expect("formatted text parses");
        let tokens: String = quote!(#file).to_string().split_whitespace().collect();
        tokens
            .replace(",)", ")")
            .replace(",]", "]")
            .replace(",}", "}")
    }

    #[test]
    fn a_copy_macro_is_formatted_as_a_function_and_keeps_its_tokens() {
        let tokens = quote! {
            pub mod m {
                macro_rules! derivatives_copy {
                    ($(#[$attr:meta])* $vis:vis $name:ident) => {
                        $(#[$attr])*
                        $vis fn $name(&mut self, _: f64, x: &[f64; 2], dx: &mut [f64; 2]) -> Result<(), E> {
                            let q1 = x[0]; let u1 = x[1]; dx[0] = u1; dx[1] = -(q1.add_mul(u1, 0.5)); Ok(())
                        }
                    };
                }
                impl M { derivatives_copy! { #[inline(always)] derivatives_baseline } }
            }
        };
        let text = format_tokens(&tokens);
        assert!(text.contains("    macro_rules! derivatives_copy {\n        ($(#[$attr:meta])* $vis:vis $name:ident) => {\n            $(#[$attr])*\n            $vis fn $name(\n"), "{text}");
        assert!(
            text.contains("\n                let q1 = x[0];\n                let u1 = x[1];\n"),
            "{text}"
        );
        assert_eq!(squeezed(&text), squeezed(&tokens.to_string()));
    }

    #[test]
    fn other_macros_are_left_to_prettyplease() {
        let tokens = quote! {
            macro_rules! other { ($x:expr) => { $x + 1 }; }
        };
        let text = format_tokens(&tokens);
        assert_eq!(squeezed(&text), squeezed(&tokens.to_string()));
        assert!(text.contains("macro_rules! other"), "{text}");
    }
}

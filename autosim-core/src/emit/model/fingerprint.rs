//! The fingerprint of a generated module: FNV-1a over its tokens, so a
//! study folder can tell results of one build of a model from another's.
//!
//! The walk hashes what each token is (an identifier's name, a
//! punctuation character and its spacing, a literal's text, a group's
//! delimiters), not how a token stream prints, so the same module has the
//! same fingerprint in the proc macro and in a build script; and the
//! runtime crate's path (`::autosim::runtime` in a user's crate,
//! `::autosim_runtime` in Python's and FMUs' builds) hashes as one
//! marker, so the same model has the same fingerprint wherever it is
//! built.

use proc_macro2::{Delimiter, Spacing, TokenStream, TokenTree};

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0100_0000_01b3;

/// FNV-1a of `tokens`, with each occurrence of the token sequence
/// `runtime` hashed as one marker.
pub(super) fn fingerprint(tokens: &TokenStream, runtime: &TokenStream) -> u64 {
    let mut hash = Fnv {
        state: FNV_OFFSET,
        runtime: runtime.clone().into_iter().collect(),
    };
    hash.stream(tokens);
    hash.state
}

struct Fnv {
    state: u64,
    runtime: Vec<TokenTree>,
}

impl Fnv {
    fn bytes(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.state ^= u64::from(*b);
            self.state = self.state.wrapping_mul(FNV_PRIME);
        }
    }

    fn stream(&mut self, tokens: &TokenStream) {
        let trees: Vec<TokenTree> = tokens.clone().into_iter().collect();
        let mut at = 0;
        while at < trees.len() {
            if self.runtime_at(&trees[at..]) {
                self.bytes(b"R");
                at += self.runtime.len();
            } else {
                self.tree(&trees[at]);
                at += 1;
            }
        }
    }

    /// Whether `trees` start with the runtime's path.
    fn runtime_at(&self, trees: &[TokenTree]) -> bool {
        !self.runtime.is_empty()
            && trees.len() >= self.runtime.len()
            && self.runtime.iter().zip(trees).all(|(a, b)| same_leaf(a, b))
    }

    /// Each token starts with a byte saying its kind, so `a b` and `ab`
    /// differ.
    fn tree(&mut self, tree: &TokenTree) {
        match tree {
            TokenTree::Ident(i) => {
                self.bytes(b"i");
                self.bytes(i.to_string().as_bytes());
            }
            TokenTree::Punct(p) => {
                let joint = p.spacing() == Spacing::Joint;
                self.bytes(if joint { b"j" } else { b"p" });
                self.bytes(p.as_char().to_string().as_bytes());
            }
            TokenTree::Literal(l) => {
                self.bytes(b"l");
                self.bytes(l.to_string().as_bytes());
            }
            TokenTree::Group(g) => {
                let (open, close): (&[u8], &[u8]) = match g.delimiter() {
                    Delimiter::Parenthesis => (b"(", b")"),
                    Delimiter::Brace => (b"{", b"}"),
                    Delimiter::Bracket => (b"[", b"]"),
                    Delimiter::None => (b"<", b">"),
                };
                self.bytes(open);
                self.stream(&g.stream());
                self.bytes(close);
            }
        }
    }
}

/// Whether two tokens are the same identifier or punctuation (a path has
/// no literals or groups).
fn same_leaf(a: &TokenTree, b: &TokenTree) -> bool {
    match (a, b) {
        (TokenTree::Ident(a), TokenTree::Ident(b)) => a == b,
        (TokenTree::Punct(a), TokenTree::Punct(b)) => {
            a.as_char() == b.as_char() && a.spacing() == b.spacing()
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::FNV_OFFSET;
    use proc_macro2::TokenStream;
    use quote::quote;

    fn tokens(text: &str) -> TokenStream {
        text.parse().expect("Rust tokens")
    }

    fn fingerprint(text: &str) -> u64 {
        super::fingerprint(&tokens(text), &quote!(::autosim::runtime))
    }

    #[test]
    fn a_token_changed_changes_the_fingerprint() {
        let a = fingerprint("fn f(x: f64) -> f64 { x.sin() }");
        assert_ne!(a, fingerprint("fn f(x: f64) -> f64 { x.cos() }"));
        assert_ne!(a, fingerprint("fn f(x: f64) -> f64 { x.sin(); }"));
        assert_eq!(
            a,
            fingerprint("fn f ( x : f64 ) -> f64 {\n    x . sin ( )\n}")
        );
    }

    #[test]
    fn tokens_split_differently_differ() {
        assert_ne!(fingerprint("a b"), fingerprint("ab"));
        assert_ne!(fingerprint("(a) b"), fingerprint("(a b)"));
        assert_ne!(fingerprint("a += b"), fingerprint("a + = b"));
        assert_ne!(fingerprint("1.0"), fingerprint("1.00"));
    }

    #[test]
    fn the_runtime_path_is_one_marker() {
        let with = |rt: &str| {
            let text = format!("use {rt}::math; fn f() {{ {rt}::math::sin(1.0) }}");
            super::fingerprint(&tokens(&text), &tokens(rt))
        };
        let a = with("::autosim::runtime");
        assert_eq!(a, with("::autosim_runtime"));
        assert_eq!(a, with("crate::rt"));
        let other = "use ::autosim::runtime::math; fn f() { ::autosim::runtime::math::cos(1.0) }";
        assert_ne!(a, fingerprint(other));
        assert_ne!(
            fingerprint("autosim::runtime"),
            fingerprint("::autosim::runtime")
        );
    }

    #[test]
    fn the_empty_stream_is_fnv_offset() {
        assert_eq!(fingerprint(""), FNV_OFFSET);
    }
}

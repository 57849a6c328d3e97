//! The fingerprint of a generated module: FNV-1a over its tokens, so a
//! study folder can tell results of one build of a model from another's.
//!
//! The walk hashes what each token is (an identifier's name, a
//! punctuation character and its spacing, a literal's text, a group's
//! delimiters), not how a token stream prints, so the same module has the
//! same fingerprint in the proc macro and in a build script.

use proc_macro2::{Delimiter, Spacing, TokenStream, TokenTree};

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0100_0000_01b3;

/// FNV-1a of `tokens`.
pub(super) fn fingerprint(tokens: &TokenStream) -> u64 {
    let mut hash = Fnv(FNV_OFFSET);
    hash.stream(tokens);
    hash.0
}

struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 ^= u64::from(*b);
            self.0 = self.0.wrapping_mul(FNV_PRIME);
        }
    }

    /// Each token starts with a byte saying its kind, so `a b` and `ab`
    /// differ.
    fn stream(&mut self, tokens: &TokenStream) {
        for tree in tokens.clone() {
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use quote::quote;

    #[test]
    fn a_token_changed_changes_the_fingerprint() {
        let a = fingerprint(&quote!(
            fn f(x: f64) -> f64 {
                x.sin()
            }
        ));
        let b = fingerprint(&quote!(
            fn f(x: f64) -> f64 {
                x.cos()
            }
        ));
        let c = fingerprint(&quote!(
            fn f(x: f64) -> f64 {
                x.sin()
            }
        ));
        assert_ne!(a, b);
        assert_eq!(a, c, "spacing in the source is not a token");
    }

    #[test]
    fn tokens_split_differently_differ() {
        assert_ne!(fingerprint(&quote!(a b)), fingerprint(&quote!(ab)));
        assert_ne!(fingerprint(&quote!((a) b)), fingerprint(&quote!((a b))));
        assert_ne!(fingerprint(&quote!(a += b)), fingerprint(&quote!(a + = b)));
    }

    #[test]
    fn the_empty_stream_is_fnv_offset() {
        assert_eq!(fingerprint(&TokenStream::new()), FNV_OFFSET);
    }
}

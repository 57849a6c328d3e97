//! Basis-free vectors and dyadics: sparse sums of unit vectors (and dyads)
//! from any frames, with scalar coefficients.

use super::frames::UvId;
use crate::expr::{Arena, ExprId};

/// A vector `Σ c_k u_k` over unit vectors of any frames, kept sorted by unit
/// vector with no zero coefficients.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Vector {
    terms: Vec<(UvId, ExprId)>,
}

impl Vector {
    /// The zero vector.
    pub fn zero() -> Vector {
        Vector { terms: Vec::new() }
    }

    /// A unit vector.
    pub fn uv(arena: &mut Arena, u: UvId) -> Vector {
        Vector {
            terms: vec![(u, arena.one())],
        }
    }

    /// `c u`.
    pub fn term(arena: &mut Arena, u: UvId, c: ExprId) -> Vector {
        if arena.is_zero(c) {
            Vector::zero()
        } else {
            Vector {
                terms: vec![(u, c)],
            }
        }
    }

    /// The terms `(unit vector, coefficient)`.
    pub fn terms(&self) -> &[(UvId, ExprId)] {
        &self.terms
    }

    /// `true` for the zero vector.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// `self + other`.
    pub fn add(&self, arena: &mut Arena, other: &Vector) -> Vector {
        if other.is_zero() {
            return self.clone();
        }
        if self.is_zero() {
            return other.clone();
        }
        let mut out = Vec::with_capacity(self.terms.len() + other.terms.len());
        let (mut i, mut j) = (0, 0);
        while i < self.terms.len() || j < other.terms.len() {
            let take_left = j >= other.terms.len()
                || (i < self.terms.len() && self.terms[i].0 < other.terms[j].0);
            let take_right = i >= self.terms.len()
                || (j < other.terms.len() && other.terms[j].0 < self.terms[i].0);
            if take_left {
                out.push(self.terms[i]);
                i += 1;
            } else if take_right {
                out.push(other.terms[j]);
                j += 1;
            } else {
                let c = arena.add(self.terms[i].1, other.terms[j].1);
                if !arena.is_zero(c) {
                    out.push((self.terms[i].0, c));
                }
                i += 1;
                j += 1;
            }
        }
        Vector { terms: out }
    }

    /// `self - other`.
    pub fn sub(&self, arena: &mut Arena, other: &Vector) -> Vector {
        let n = other.neg(arena);
        self.add(arena, &n)
    }

    /// `-self`.
    pub fn neg(&self, arena: &mut Arena) -> Vector {
        Vector {
            terms: self
                .terms
                .iter()
                .map(|(u, c)| (*u, arena.neg(*c)))
                .collect(),
        }
    }

    /// `s self` for a scalar `s`.
    pub fn scale(&self, arena: &mut Arena, s: ExprId) -> Vector {
        Vector {
            terms: scale_terms(arena, &self.terms, s),
        }
    }

    /// Applies `f` to every coefficient (dropping zeros).
    pub fn map(
        &self,
        arena: &mut Arena,
        mut f: impl FnMut(&mut Arena, ExprId) -> ExprId,
    ) -> Vector {
        let mut terms = Vec::with_capacity(self.terms.len());
        for (u, c) in &self.terms {
            let k = f(arena, *c);
            if !arena.is_zero(k) {
                terms.push((*u, k));
            }
        }
        Vector { terms }
    }

    /// The coefficient of a unit vector (not a dot product).
    pub fn coefficient(&self, arena: &Arena, u: UvId) -> ExprId {
        self.terms
            .iter()
            .find(|t| t.0 == u)
            .map(|t| t.1)
            .unwrap_or_else(|| arena.zero())
    }
}

/// A dyadic `Σ c_k u_k v_k` over dyads of unit vectors of any frames.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Dyadic {
    terms: Vec<((UvId, UvId), ExprId)>,
}

impl Dyadic {
    /// The zero dyadic.
    pub fn zero() -> Dyadic {
        Dyadic { terms: Vec::new() }
    }

    /// The terms `((left, right), coefficient)`.
    pub fn terms(&self) -> &[((UvId, UvId), ExprId)] {
        &self.terms
    }

    /// `true` for the zero dyadic.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The dyadic `Σ m_jk t_j t_k` of a 3×3 matrix in a triad.
    pub fn from_matrix(arena: &Arena, triad: [UvId; 3], m: [[ExprId; 3]; 3]) -> Dyadic {
        let mut terms = Vec::new();
        for j in 0..3 {
            for k in 0..3 {
                if !arena.is_zero(m[j][k]) {
                    terms.push(((triad[j], triad[k]), m[j][k]));
                }
            }
        }
        terms.sort_by_key(|t| t.0);
        Dyadic { terms }
    }

    /// The outer product `a b`.
    pub fn outer(arena: &mut Arena, a: &Vector, b: &Vector) -> Dyadic {
        let mut d = Dyadic::zero();
        for &(u, cu) in a.terms() {
            for &(v, cv) in b.terms() {
                let c = arena.mul(cu, cv);
                d = d.add(
                    arena,
                    &Dyadic {
                        terms: vec![((u, v), c)],
                    },
                );
            }
        }
        d
    }

    /// `self + other`.
    pub fn add(&self, arena: &mut Arena, other: &Dyadic) -> Dyadic {
        let mut terms = self.terms.clone();
        for &(k, c) in &other.terms {
            match terms.binary_search_by_key(&k, |t| t.0) {
                Ok(i) => terms[i].1 = arena.add(terms[i].1, c),
                Err(i) => terms.insert(i, (k, c)),
            }
        }
        terms.retain(|t| !arena.is_zero(t.1));
        Dyadic { terms }
    }

    /// `s self`.
    pub fn scale(&self, arena: &mut Arena, s: ExprId) -> Dyadic {
        Dyadic {
            terms: scale_terms(arena, &self.terms, s),
        }
    }
}

/// Each coefficient of `terms` times `s`, the terms that vanish dropped.
fn scale_terms<K: Copy>(arena: &mut Arena, terms: &[(K, ExprId)], s: ExprId) -> Vec<(K, ExprId)> {
    if arena.is_zero(s) {
        return Vec::new();
    }
    let mut scaled = Vec::with_capacity(terms.len());
    for (k, c) in terms {
        let x = arena.mul(*c, s);
        if !arena.is_zero(x) {
            scaled.push((*k, x));
        }
    }
    scaled
}

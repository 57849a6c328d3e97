//! Pathological shapes: long chains of `let`s or points, deep nesting,
//! long sums, many bodies, many states.

use std::fmt::Write;

use super::Rng;

/// A size from 1 to `max`, spread evenly over orders of magnitude.
fn log_size(rng: &mut Rng, max: usize) -> usize {
    let bits = usize::BITS - max.leading_zeros();
    let n = 1usize << rng.below(bits as usize);
    rng.range(n, (2 * n - 1).min(max))
}

/// One-argument wrappers for chains (`X` is the previous link).
const LINKS: &[&str] = &[
    "sin(X)",
    "X*X + 1",
    "(X)^(1/3)",
    "atan2(X, t)",
    "X + q(A)*X",
    "exp(-X)",
    "sqrt(X^2 + 1)",
    "X/(1 + X)",
    "dot(X*n1, a2) + 1",
    "abs(X) - sign(X)",
    "min(X, max(X, t))",
    "-X",
    "nominal(X) + X",
    "partial(X, q(A)) + X",
];

pub(crate) fn deep(rng: &mut Rng) -> String {
    let mut s = String::from("model Deep;\nparameters { k = 2, m = 1 }\n");
    s.push_str("body A { rotate: 1, mass: m, inertia: diag(1, 2, 3), cm: [0, 0, 1] }\n");
    match rng.below(7) {
        0 | 1 => {
            // A chain of `let`s, each wrapping the one before.
            let n = log_size(rng, 5000);
            let _ = writeln!(s, "let r0 = q(A) + t;");
            for i in 1..=n {
                let link = rng.pick(LINKS).replace('X', &format!("r{}", i - 1));
                let _ = writeln!(s, "let r{i} = {link};");
            }
            let _ = writeln!(s, "moment M1 {{ on: A, about: n1, magnitude: -k*r{n} }}");
            let _ = writeln!(s, "output y = r{n};\noutput z = dxdt(r{n});");
        }
        2 => {
            // A chain of points, each placed by the one before.
            let n = log_size(rng, 2000);
            let _ = writeln!(s, "point P0 in A at [1, 0, 0];");
            for i in 1..=n {
                let _ = writeln!(
                    s,
                    "point P{i} in A at [sin(dot(pos(P{}), a1)) + 1, q(A), 0];",
                    i - 1
                );
            }
            let _ = writeln!(s, "force F {{ on: P{n}, vector: -k*pos(P{n}) }}");
            let _ = writeln!(s, "output y = mag(vel(P{n}));");
        }
        3 => {
            // Nesting within one expression, up to and past the parser's limit.
            let n = log_size(rng, 150);
            let link = *rng.pick(&[
                "sin(X)",
                "(X)^2",
                "dxdt(X)",
                "partial(X, q(A))",
                "-X",
                "(X + t)",
                "2^X",
            ]);
            let mut e = "q(A)".to_string();
            for _ in 0..n {
                e = link.replace('X', &e);
            }
            let _ = writeln!(s, "output y = {e};");
        }
        4 => {
            // A long flat sum or product.
            let n = log_size(rng, 9000);
            let op = *rng.pick(&[" + ", "*", " - "]);
            let terms: Vec<String> = (0..n)
                .map(|i| match i % 4 {
                    0 => "q(A)".to_string(),
                    1 => format!("{}", i + 1),
                    2 => "sin(q(A))".to_string(),
                    _ => "u(A)^2".to_string(),
                })
                .collect();
            let _ = writeln!(s, "output y = {};", terms.join(op));
        }
        5 => {
            // Many bodies, each hinged on the one before.
            let n = log_size(rng, 24);
            let mut parent = "A".to_string();
            for i in 0..n {
                let axis = 1 + i % 3;
                let small = if rng.chance(30) { ", small: all" } else { "" };
                let _ = writeln!(
                    s,
                    "body L{i} {{ parent: {parent}, joint: [0, 0, 1], rotate: {axis}, mass: m, inertia: diag(1, 2, 3), cm: [0, 0, 0.5]{small} }}"
                );
                parent = format!("L{i}");
            }
            s.push_str("gravity = -9.81*n3;\n");
            let _ = writeln!(s, "output y = dot(pos({parent}.cm), n3);");
        }
        _ => {
            // Many states, each driven by the one before.
            let n = log_size(rng, 3000);
            for i in 0..n {
                let prev = if i == 0 {
                    "q(A)".to_string()
                } else {
                    format!("s{}", i - 1)
                };
                let _ = writeln!(s, "state s{i} {{ initial: 0, derivative: {prev} - s{i} }}");
            }
        }
    }
    s
}

//! Values of model expressions: scalars, vectors, dyadics, and the names of
//! points and bodies that some operations take. Arithmetic checks kinds and
//! says what was expected.

use crate::expr::ExprId;
use crate::mech::{BodyId, Dyadic, PointId, System, Vector};

/// The value of an expression in a model.
#[derive(Clone, Debug)]
pub enum Value {
    /// A scalar expression.
    Scalar(ExprId),
    /// A basis-free vector.
    Vector(Vector),
    /// A basis-free dyadic.
    Dyadic(Dyadic),
    /// A point (operations like `pos` and `vel` take points).
    Point(PointId),
    /// A body (operations like `rot` and `q` take bodies).
    Body(BodyId),
    /// A bracketed list `[a, b, c]` (coordinates, matrices).
    List(Vec<Value>),
}

impl Value {
    /// The kind, as said in messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Value::Scalar(_) => "scalar",
            Value::Vector(_) => "vector",
            Value::Dyadic(_) => "dyadic",
            Value::Point(_) => "point",
            Value::Body(_) => "body",
            Value::List(_) => "list",
        }
    }
}

/// A binary arithmetic operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

fn list_hint(v: &Value) -> &'static str {
    if matches!(v, Value::List(_)) {
        "; a list `[x, y, z]` has no axes: write `x*b1 + y*b2 + z*b3` with the unit vectors of a body"
    } else {
        ""
    }
}

/// `a op b` with kind checks.
pub fn binary(sys: &mut System, op: Op, a: Value, b: Value) -> Result<Value, String> {
    use Value::*;
    let ar = &mut sys.arena;
    Ok(match (op, a, b) {
        (Op::Add, Scalar(x), Scalar(y)) => Scalar(ar.add(x, y)),
        (Op::Sub, Scalar(x), Scalar(y)) => Scalar(ar.sub(x, y)),
        (Op::Mul, Scalar(x), Scalar(y)) => Scalar(ar.mul(x, y)),
        (Op::Div, Scalar(x), Scalar(y)) => {
            if ar.is_zero(y) {
                return Err("division by zero".to_string());
            }
            Scalar(ar.div(x, y))
        }
        (Op::Pow, Scalar(x), Scalar(y)) => Scalar(ar.pow(x, y)),
        (Op::Add, Vector(x), Vector(y)) => Vector(x.add(ar, &y)),
        (Op::Sub, Vector(x), Vector(y)) => Vector(x.sub(ar, &y)),
        (Op::Add, Dyadic(x), Dyadic(y)) => Dyadic(x.add(ar, &y)),
        (Op::Sub, Dyadic(x), Dyadic(y)) => {
            let m1 = ar.int(-1);
            let ny = y.scale(ar, m1);
            Dyadic(x.add(ar, &ny))
        }
        (Op::Mul, Scalar(s), Vector(v)) | (Op::Mul, Vector(v), Scalar(s)) => Vector(v.scale(ar, s)),
        (Op::Mul, Scalar(s), Dyadic(d)) | (Op::Mul, Dyadic(d), Scalar(s)) => Dyadic(d.scale(ar, s)),
        (Op::Div, Vector(v), Scalar(s)) => {
            if ar.is_zero(s) {
                return Err("division by zero".to_string());
            }
            let inv = ar.inv(s);
            Vector(v.scale(ar, inv))
        }
        (Op::Div, Dyadic(d), Scalar(s)) => {
            if ar.is_zero(s) {
                return Err("division by zero".to_string());
            }
            let inv = ar.inv(s);
            Dyadic(d.scale(ar, inv))
        }
        (Op::Mul, Vector(_), Vector(_)) => {
            return Err(
                "cannot multiply two vectors: use `dot(a, b)` for the scalar product or `cross(a, b)` for the vector product"
                    .to_string(),
            );
        }
        (op, a, b) => {
            let verb = match op {
                Op::Add => "add",
                Op::Sub => "subtract",
                Op::Mul => "multiply",
                Op::Div => "divide",
                Op::Pow => "raise",
            };
            let hint = if matches!(a, List(_)) {
                list_hint(&a)
            } else {
                list_hint(&b)
            };
            let msg = match op {
                Op::Pow => format!(
                    "cannot raise a {} to a {} power: `^` needs scalars{hint}",
                    a.kind(),
                    b.kind()
                ),
                Op::Div if matches!(b, Vector(_) | Dyadic(_)) => {
                    format!(
                        "cannot divide by a {}: the divisor must be a scalar{hint}",
                        b.kind()
                    )
                }
                _ => format!("cannot {verb} a {} and a {}{hint}", a.kind(), b.kind()),
            };
            return Err(msg);
        }
    })
}

/// `-a`.
pub fn negate(sys: &mut System, a: Value) -> Result<Value, String> {
    let ar = &mut sys.arena;
    Ok(match a {
        Value::Scalar(x) => Value::Scalar(ar.neg(x)),
        Value::Vector(v) => Value::Vector(v.neg(ar)),
        Value::Dyadic(d) => {
            let m1 = ar.int(-1);
            Value::Dyadic(d.scale(ar, m1))
        }
        other => {
            return Err(format!(
                "cannot negate a {}{}",
                other.kind(),
                list_hint(&other)
            ));
        }
    })
}

/// `dot(a, b)` for vectors and dyadics.
pub fn dot(sys: &mut System, a: Value, b: Value) -> Result<Value, String> {
    let (ar, fr) = (&mut sys.arena, &mut sys.frames);
    Ok(match (a, b) {
        (Value::Vector(x), Value::Vector(y)) => Value::Scalar(fr.dot_vec(ar, &x, &y)),
        (Value::Vector(x), Value::Dyadic(d)) => Value::Vector(fr.dot_vec_dyadic(ar, &x, &d)),
        (Value::Dyadic(d), Value::Vector(x)) => Value::Vector(fr.dot_dyadic_vec(ar, &d, &x)),
        (a, b) => {
            return Err(format!(
                "`dot` needs two vectors (or a vector and a dyadic), but got a {} and a {}",
                a.kind(),
                b.kind()
            ));
        }
    })
}

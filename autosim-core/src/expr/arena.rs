//! The expression arena: hash-consed, immutable nodes addressed by `u32` ids.
//!
//! Children always have smaller ids than their parents, so a loop over ids in
//! increasing order visits every node after its children (the evaluator uses
//! this). Equal expressions are one node, so equality is an id comparison.

use super::number::Number;
use indexmap::IndexSet;
use rustc_hash::{FxBuildHasher, FxHashMap};

crate::ids::id_type!(
    /// A scalar expression: an index into an [`Arena`].
    ExprId,
    "arena"
);

crate::ids::id_type!(
    /// A symbol of an [`Arena`].
    SymId,
    "symbol table"
);

crate::ids::id_type!(
    /// A user function (declared by name and arity) of an [`Arena`].
    UserFnId,
    "table of user functions"
);

/// Functions that may appear in expressions (the paper's `func` and `trig`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Func {
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
    /// Tangent.
    Tan,
    /// Arc sine.
    Asin,
    /// Arc cosine.
    Acos,
    /// Two-argument arc tangent `atan2(y, x)`.
    Atan2,
    /// Exponential.
    Exp,
    /// Natural logarithm.
    Ln,
    /// Absolute value.
    Abs,
    /// Sign (-1, 0, 1).
    Sign,
    /// Minimum of two values.
    Min,
    /// Maximum of two values.
    Max,
    /// A user function, called by name in generated code.
    User(UserFnId),
}

impl Func {
    /// The built-in function with this name, if any (`sqrt` is a power, not
    /// a function).
    pub fn builtin(name: &str) -> Option<Func> {
        Some(match name {
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "asin" => Func::Asin,
            "acos" => Func::Acos,
            "atan2" => Func::Atan2,
            "exp" => Func::Exp,
            "ln" => Func::Ln,
            "abs" => Func::Abs,
            "sign" => Func::Sign,
            "min" => Func::Min,
            "max" => Func::Max,
            _ => return None,
        })
    }

    /// Number of arguments of a built-in function (`None` for user functions,
    /// whose arity is declared).
    pub fn builtin_arity(self) -> Option<usize> {
        match self {
            Func::Atan2 | Func::Min | Func::Max => Some(2),
            Func::User(_) => None,
            _ => Some(1),
        }
    }

    /// The lower-case name of a built-in function.
    pub fn builtin_name(self) -> Option<&'static str> {
        Some(match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan2 => "atan2",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Abs => "abs",
            Func::Sign => "sign",
            Func::Min => "min",
            Func::Max => "max",
            Func::User(_) => return None,
        })
    }

    /// The numeric value of a built-in function at `args` (`None` for a
    /// user function, which only the caller can evaluate). The one
    /// numeric meaning of each function: the evaluator and the program
    /// interpreter both use it, and generated code calls the same `libm`/
    /// `std` functions.
    pub fn eval_builtin(self, args: &[f64]) -> Option<f64> {
        let x = args.first().copied().unwrap_or(f64::NAN);
        let y = args.get(1).copied().unwrap_or(f64::NAN);
        Some(match self {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan2 => x.atan2(y),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Abs => x.abs(),
            Func::Sign => {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            }
            Func::Min => x.min(y),
            Func::Max => x.max(y),
            Func::User(_) => return None,
        })
    }
}

/// One node of the expression DAG (the paper's Table 1, scalars only).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A number.
    Num(Number),
    /// A symbol.
    Sym(SymId),
    /// A sum of at least two terms, sorted by id.
    Sum(Box<[ExprId]>),
    /// A product of a non-zero coefficient and factors sorted by id (never
    /// numbers, never products); a coefficient of 1 implies two factors or more.
    Prod(Number, Box<[ExprId]>),
    /// `base ^ exponent`.
    Pow(ExprId, ExprId),
    /// A function applied to arguments.
    Func(Func, Box<[ExprId]>),
}

/// What a symbol stands for.
#[derive(Clone, Debug, PartialEq)]
pub enum SymbolKind {
    /// A constant parameter with a default value.
    Parameter {
        /// Default value.
        default: f64,
    },
    /// Generalized coordinate number `index` (0-based).
    Coordinate {
        /// 0-based index.
        index: usize,
    },
    /// Generalized speed number `index` (0-based).
    Speed {
        /// 0-based index.
        index: usize,
    },
    /// Time derivative of generalized speed `index` (0-based).
    SpeedRate {
        /// 0-based index.
        index: usize,
    },
    /// An added state variable number `index` (0-based, after the speeds).
    State {
        /// 0-based index.
        index: usize,
    },
    /// An input supplied by the caller at run time.
    Input {
        /// Default value.
        default: f64,
    },
    /// A discrete variable: constant between events, changed only by
    /// their actions.
    Discrete {
        /// Its value at the start of a run.
        default: f64,
    },
    /// Output `index` of user subroutine `sub` (by declaration order).
    ExternOutput {
        /// Subroutine index.
        sub: usize,
        /// Output index within the subroutine.
        index: usize,
    },
    /// Time.
    Time,
    /// A free symbol (text-form parsing and tests): a variable with no
    /// derivative.
    Free,
}

/// A named scalar symbol.
#[derive(Clone, Debug)]
pub struct Symbol {
    /// Name as written in the model and in generated code.
    pub name: String,
    /// What the symbol stands for.
    pub kind: SymbolKind,
    /// Order of smallness: 0 for ordinary symbols, 1 for "small" ones.
    pub order: i16,
    /// Unit text, if known.
    pub unit: Option<String>,
}

impl Symbol {
    /// `true` for parameters (the only constant symbols).
    pub fn is_constant(&self) -> bool {
        matches!(self.kind, SymbolKind::Parameter { .. })
    }
}

/// A user function declaration.
#[derive(Clone, Debug)]
pub struct UserFn {
    /// Name used in the model and in generated code.
    pub name: String,
    /// Number of arguments.
    pub arity: usize,
}

/// Facts computed once when a node is created.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Meta {
    /// Depends only on parameters and numbers.
    pub constant: bool,
    /// Order of smallness (may be negative for reciprocals of small values).
    pub order: i16,
}

/// Errors from arena operations.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprError {
    /// A symbol with this name already exists.
    DuplicateSymbol(String),
    /// A user function with this name already exists.
    DuplicateFunction(String),
    /// A function got the wrong number of arguments.
    Arity {
        /// Function name.
        name: String,
        /// Declared arity.
        expected: usize,
        /// Arguments given.
        got: usize,
    },
    /// The derivative of this symbol is unknown (an input or user output).
    NoDerivative(String),
    /// This function has no symbolic derivative.
    NotDifferentiable(String),
    /// A derivative would create more than this many nodes.
    TooLarge(usize),
}

impl core::fmt::Display for ExprError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ExprError::DuplicateSymbol(n) => write!(f, "the name `{n}` is already defined"),
            ExprError::DuplicateFunction(n) => {
                write!(f, "the function `{n}` is already declared")
            }
            ExprError::Arity {
                name,
                expected,
                got,
            } => write!(
                f,
                "`{name}` takes {expected} argument{}, but {got} {} given",
                if *expected == 1 { "" } else { "s" },
                if *got == 1 { "was" } else { "were" }
            ),
            ExprError::NoDerivative(n) => write!(
                f,
                "the time derivative of `{n}` is unknown (inputs and user-function outputs have no derivative)"
            ),
            ExprError::NotDifferentiable(n) => {
                write!(f, "`{n}` has no symbolic derivative")
            }
            ExprError::TooLarge(n) => write!(
                f,
                "this derivative would take more than {n} expression nodes (each `partial` or `dxdt` of a derivative multiplies its size)"
            ),
        }
    }
}

impl std::error::Error for ExprError {}

/// The store of all expressions and symbols of one model.
///
/// Owned per model: one compiler process expands many macros, so there is no
/// global interner.
#[derive(Clone, Debug)]
pub struct Arena {
    pub(crate) nodes: IndexSet<Node, FxBuildHasher>,
    pub(crate) meta: Vec<Meta>,
    /// Nesting depth of each node (a number or symbol is 1).
    pub(crate) depth: Vec<u32>,
    pub(crate) symbols: Vec<Symbol>,
    pub(crate) sym_nodes: Vec<ExprId>,
    pub(crate) sym_by_name: FxHashMap<String, SymId>,
    pub(crate) sym_dxdt: Vec<Option<ExprId>>,
    pub(crate) user_fns: Vec<UserFn>,
    pub(crate) threshold: i16,
    /// How many new nodes one derivative may create (see
    /// [`crate::limits::MAX_DERIVATIVE_NODES`]).
    pub(crate) derivative_limit: usize,
    /// The trigonometric normal form of each node asked for (`None`: too
    /// big to expand), see `trigpoly.rs`.
    pub(crate) poly_memo: FxHashMap<ExprId, Option<std::sync::Arc<super::trigpoly::Poly>>>,
}

impl Default for Arena {
    fn default() -> Self {
        Arena::new()
    }
}

impl Arena {
    /// An empty arena with the default small-term threshold of 2.
    pub fn new() -> Arena {
        let mut arena = Arena {
            nodes: IndexSet::default(),
            meta: Vec::new(),
            depth: Vec::new(),
            symbols: Vec::new(),
            sym_nodes: Vec::new(),
            sym_by_name: FxHashMap::default(),
            sym_dxdt: Vec::new(),
            user_fns: Vec::new(),
            threshold: 2,
            derivative_limit: crate::limits::MAX_DERIVATIVE_NODES,
            poly_memo: FxHashMap::default(),
        };
        // Ids 0 and 1 are always 0 and 1.
        arena.num(Number::ZERO);
        arena.num(Number::ONE);
        arena
    }

    /// The small-term threshold: a term of a sum is dropped when its order of
    /// smallness exceeds the lowest order in that sum by this much or more.
    pub fn threshold(&self) -> i16 {
        self.threshold
    }

    /// Sets the small-term threshold (at least 1). Affects expressions created
    /// afterwards only.
    pub fn set_threshold(&mut self, threshold: i16) {
        self.threshold = threshold.max(1);
    }

    /// The node of an expression.
    pub fn node(&self, e: ExprId) -> &Node {
        // Ids are only made by this arena, so the index is always valid.
        &self.nodes[e.index()]
    }

    /// Facts about an expression.
    pub fn meta(&self, e: ExprId) -> Meta {
        self.meta[e.index()]
    }

    /// `true` if the expression depends only on parameters and numbers.
    pub fn is_constant(&self, e: ExprId) -> bool {
        self.meta[e.index()].constant
    }

    /// Order of smallness of an expression.
    pub fn order(&self, e: ExprId) -> i16 {
        self.meta[e.index()].order
    }

    /// Nesting depth of an expression: 1 for a number or a symbol, one more
    /// than its deepest child otherwise. The passes over expressions recurse
    /// this deep, so the resolver bounds it.
    pub fn depth(&self, e: ExprId) -> u32 {
        self.depth[e.index()]
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// `true` if the arena has no nodes (never: 0 and 1 always exist).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The number, if the expression is one.
    pub fn as_number(&self, e: ExprId) -> Option<Number> {
        match self.node(e) {
            Node::Num(n) => Some(*n),
            _ => None,
        }
    }

    /// `true` if the expression is exactly zero.
    pub fn is_zero(&self, e: ExprId) -> bool {
        e == self.zero()
    }

    /// The expression 0.
    pub fn zero(&self) -> ExprId {
        ExprId(0)
    }

    /// The expression 1.
    pub fn one(&self) -> ExprId {
        ExprId(1)
    }

    /// Interns a node with precomputed facts. Children must already exist.
    pub(crate) fn intern(&mut self, node: Node, meta: Meta) -> ExprId {
        let depth = 1 + match &node {
            Node::Num(_) | Node::Sym(_) => 0,
            Node::Pow(b, x) => self.depth(*b).max(self.depth(*x)),
            Node::Sum(cs) | Node::Prod(_, cs) | Node::Func(_, cs) => {
                cs.iter().map(|c| self.depth(*c)).max().unwrap_or(0)
            }
        };
        let (index, inserted) = self.nodes.insert_full(node);
        if inserted {
            self.meta.push(meta);
            self.depth.push(depth);
        }
        ExprId(index as u32)
    }

    /// The id of a node if it already exists (never creates one).
    pub(crate) fn find(&self, node: &Node) -> Option<ExprId> {
        self.nodes.get_index_of(node).map(|i| ExprId(i as u32))
    }

    // ----- symbols -----

    /// Declares a new symbol; names are unique per arena.
    pub fn add_symbol(&mut self, name: &str, kind: SymbolKind) -> Result<SymId, ExprError> {
        if self.sym_by_name.contains_key(name) {
            return Err(ExprError::DuplicateSymbol(name.to_string()));
        }
        let id = SymId(self.symbols.len() as u32);
        let constant = matches!(kind, SymbolKind::Parameter { .. });
        let dxdt = match kind {
            SymbolKind::Parameter { .. } => Some(self.zero()),
            SymbolKind::Time => Some(self.one()),
            _ => None,
        };
        self.symbols.push(Symbol {
            name: name.to_string(),
            kind,
            order: 0,
            unit: None,
        });
        self.sym_by_name.insert(name.to_string(), id);
        self.sym_dxdt.push(dxdt);
        let node = self.intern(Node::Sym(id), Meta { constant, order: 0 });
        self.sym_nodes.push(node);
        Ok(id)
    }

    /// Whether any symbol is small (the model truncates small terms).
    pub fn has_small_symbols(&self) -> bool {
        self.symbols.iter().any(|s| s.order > 0)
    }

    /// Marks a symbol as small (order 1) or not. Only affects expressions
    /// created afterwards, so call it right after declaring the symbol.
    pub fn set_small(&mut self, s: SymId, small: bool) {
        let order = i16::from(small);
        self.symbols[s.index()].order = order;
        let node = self.sym_nodes[s.index()];
        self.meta[node.index()].order = order;
    }

    /// Sets the unit text of a symbol.
    pub fn set_unit(&mut self, s: SymId, unit: Option<String>) {
        self.symbols[s.index()].unit = unit;
    }

    /// Declares the time derivative of a symbol (used by `dxdt`).
    pub fn set_dxdt(&mut self, s: SymId, derivative: ExprId) {
        self.sym_dxdt[s.index()] = Some(derivative);
    }

    /// The declared time derivative of a symbol.
    pub fn dxdt_of_symbol(&self, s: SymId) -> Option<ExprId> {
        self.sym_dxdt[s.index()]
    }

    /// A symbol's declaration.
    pub fn symbol(&self, s: SymId) -> &Symbol {
        &self.symbols[s.index()]
    }

    /// All symbols in declaration order.
    pub fn symbols(&self) -> impl Iterator<Item = (SymId, &Symbol)> {
        self.symbols
            .iter()
            .enumerate()
            .map(|(i, s)| (SymId(i as u32), s))
    }

    /// Looks a symbol up by name.
    pub fn symbol_named(&self, name: &str) -> Option<SymId> {
        self.sym_by_name.get(name).copied()
    }

    /// The expression that is this symbol.
    pub fn sym(&self, s: SymId) -> ExprId {
        self.sym_nodes[s.index()]
    }

    /// The symbol, if the expression is one.
    pub fn as_symbol(&self, e: ExprId) -> Option<SymId> {
        match self.node(e) {
            Node::Sym(s) => Some(*s),
            _ => None,
        }
    }

    // ----- user functions -----

    /// Declares a user function by name and arity.
    pub fn add_user_fn(&mut self, name: &str, arity: usize) -> Result<UserFnId, ExprError> {
        if self.user_fns.iter().any(|f| f.name == name) || Func::builtin(name).is_some() {
            return Err(ExprError::DuplicateFunction(name.to_string()));
        }
        self.user_fns.push(UserFn {
            name: name.to_string(),
            arity,
        });
        Ok(UserFnId(self.user_fns.len() as u32 - 1))
    }

    /// A user function's declaration.
    pub fn user_fn(&self, f: UserFnId) -> &UserFn {
        &self.user_fns[f.index()]
    }

    /// Looks a user function up by name.
    pub fn user_fn_named(&self, name: &str) -> Option<UserFnId> {
        self.user_fns
            .iter()
            .position(|f| f.name == name)
            .map(|i| UserFnId(i as u32))
    }

    /// All user functions in declaration order.
    pub fn user_fns(&self) -> impl Iterator<Item = (UserFnId, &UserFn)> {
        self.user_fns
            .iter()
            .enumerate()
            .map(|(i, f)| (UserFnId(i as u32), f))
    }

    /// The name of a function as written in models.
    pub fn func_name(&self, f: Func) -> &str {
        match f {
            Func::User(u) => &self.user_fns[u.index()].name,
            other => other.builtin_name().unwrap_or("?"),
        }
    }

    /// The children of a node, in order.
    pub fn children(&self, e: ExprId) -> Vec<ExprId> {
        match self.node(e) {
            Node::Num(_) | Node::Sym(_) => Vec::new(),
            Node::Sum(ts) => ts.to_vec(),
            Node::Prod(_, fs) => fs.to_vec(),
            Node::Pow(b, x) => vec![*b, *x],
            Node::Func(_, args) => args.to_vec(),
        }
    }
}

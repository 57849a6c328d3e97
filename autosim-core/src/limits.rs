//! Every limit of the compiler, in one place (like egg's `Runner` limits).
//! Each protects the compiler from a model that would otherwise overflow
//! its stack or fill the memory, and each is reported as a diagnostic that
//! says which limit stopped it, never as a panic or a hang.

use std::ops::RangeInclusive;

/// Parser: how deeply delimiters and expressions may nest (parentheses,
/// brackets, signs, `^` chains) before the parser refuses, instead of
/// overflowing the stack.
pub const MAX_DEPTH: usize = 100;

/// Parser: how many binary operators one expression may have. A chain
/// `a + b + ...` is parsed in a loop but is as deep as it is long in the
/// AST, which is walked (and dropped) recursively.
pub const MAX_OPERATORS: usize = 10_000;

/// Resolver: how many `let`s and points may wait on one another (a `let`
/// using one defined later waits for it), before the resolver refuses
/// instead of overflowing its stack.
pub const MAX_PENDING: usize = 200;

/// Resolver: how deep the value of a `let` or the coordinates of a point
/// may nest (see `Arena::depth`): every later pass recurses that deep, and
/// a chain of thousands of `let`s each wrapping the one before overflowed
/// the stack.
pub const MAX_NESTING: u32 = 500;

/// Algebra: how many new nodes one derivative may create. Each `partial`
/// of a derivative multiplies its size, so a chain of them grows
/// exponentially; past this (50 times the whole arena of a 20-body spatial
/// chain) the derivative is refused instead of filling the memory.
pub const MAX_DERIVATIVE_NODES: usize = 500_000;

/// Scheduler: expressions nest at most this deep in generated code;
/// deeper values are named (which also bounds the printers' recursion).
pub const MAX_INLINE_DEPTH: usize = 24;

/// Emitter: a generated function binds at most this many values with
/// `let`; a bigger block keeps its intermediates in one local array
/// (`z[k]`). Every `let` opens a lexical scope, and rustc's debug info
/// recurses through them: a function with about 6000 crashed debug builds
/// with a stack overflow.
pub const MAX_LETS_IN_FUNCTION: usize = 3000;

/// The small-term thresholds a model or a scene may set.
pub const THRESHOLDS: RangeInclusive<i16> = 1..=20;

//! The set operations, as a rule on insideness: what CSG nodes, 2-D
//! combinations and drawings' fill rules combine by.

/// The set operations: OpenSCAD's three, and the symmetric difference
/// (even-odd parity) that a drawing's fill rule combines its paths by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    Union,
    Intersection,
    Difference,
    /// Inside an odd number of the children.
    Xor,
}

impl Op {
    /// The statement's name, in OpenSCAD and in POV-Ray alike.
    pub const fn name(self) -> &'static str {
        match self {
            Op::Union => "union",
            Op::Intersection => "intersection",
            Op::Difference => "difference",
            Op::Xor => "xor",
        }
    }

    pub fn apply(self, a: bool, b: bool) -> bool {
        match self {
            Op::Union => a || b,
            Op::Intersection => a && b,
            Op::Difference => a && !b,
            Op::Xor => a != b,
        }
    }

    /// Whether a span of B alone may hold the result where A holds none
    /// (so B is needed over the whole ray, not only over A's spans).
    pub const fn b_alone(self) -> bool {
        matches!(self, Op::Union | Op::Xor)
    }
}

/// The combination of `parts` by `op` (`None` for empty operands, with
/// OpenSCAD's meaning: an empty operand empties an intersection; a
/// difference with an empty first operand is empty).
pub fn combine_parts<T>(
    op: Op,
    parts: Vec<Option<T>>,
    mut wrap: impl FnMut(Op, Vec<T>) -> T,
) -> Option<T> {
    let mut live = Vec::new();
    for (i, p) in parts.into_iter().enumerate() {
        match p {
            Some(p) => live.push(p),
            None if op == Op::Intersection => return None,
            None if op == Op::Difference && i == 0 => return None,
            None => {}
        }
    }
    match live.len() {
        0 => None,
        1 => live.pop(),
        _ => Some(wrap(op, live)),
    }
}

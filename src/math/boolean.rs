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

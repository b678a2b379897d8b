//! Items: the operands of a model's top-level union, each compiled to a postfix boolean
//! program over part indices, with its exact (inside/outside) and soft (coverage)
//! evaluation. A program mentions only parts listed in its item's `parts`.

use crate::ir::CsgNode;

/// One step of an item's boolean program (postfix).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    Part(u32),
    Union(u32),
    /// The first of `n` operands minus the others.
    Difference(u32),
    Intersection(u32),
}

/// An operand of the top-level union.
#[derive(Debug, Clone, PartialEq)]
pub struct Item {
    pub program: Vec<Op>,
    /// The parts the program mentions, in order.
    pub parts: Vec<usize>,
    /// For `difference() { A; B; ... }` whose subtracted operands are parts or unions of
    /// parts: the length of `A`'s program (a prefix) and the subtracted parts. Their edges
    /// on `A`'s surface are then soft too (the rim of a mug's hollow).
    pub split: Option<(usize, Vec<usize>)>,
}

impl Item {
    pub fn is_single(&self) -> bool {
        self.program.len() == 1
    }

    /// The program of the first operand of a split difference.
    pub fn positive(&self) -> &[Op] {
        match &self.split {
            Some((k, _)) => &self.program[..*k],
            None => &self.program,
        }
    }
}

/// The split of a difference program (see [`Item::split`]).
fn split_difference(program: &[Op]) -> Option<(usize, Vec<usize>)> {
    let Some(&Op::Difference(n)) = program.last() else {
        return None;
    };
    // Start of each operand on the stack.
    let mut starts: Vec<usize> = Vec::new();
    for (i, op) in program[..program.len() - 1].iter().enumerate() {
        match *op {
            Op::Part(_) => starts.push(i),
            Op::Union(k) | Op::Difference(k) | Op::Intersection(k) => {
                let at = starts.len().checked_sub(k as usize)?;
                let s = starts[at];
                starts.truncate(at);
                starts.push(s);
            }
        }
    }
    if starts.len() != n as usize || n < 2 {
        return None;
    }
    let positive = starts[1];
    let mut negatives = Vec::new();
    for op in &program[positive..program.len() - 1] {
        match *op {
            Op::Part(i) => negatives.push(i as usize),
            Op::Union(_) => {}
            _ => return None,
        }
    }
    Some((positive, negatives))
}

/// Splits a CSG tree into the operands of its top-level union (nested unions flattened).
pub fn items_of(csg: &CsgNode) -> Vec<Item> {
    fn flatten<'a>(n: &'a CsgNode, out: &mut Vec<&'a CsgNode>) {
        match n {
            CsgNode::Union(c) => c.iter().for_each(|c| flatten(c, out)),
            other => out.push(other),
        }
    }
    fn compile(n: &CsgNode, prog: &mut Vec<Op>) -> bool {
        let (children, op): (&Vec<CsgNode>, fn(u32) -> Op) = match n {
            CsgNode::Part(i) => {
                prog.push(Op::Part(*i as u32));
                return true;
            }
            CsgNode::Union(c) => (c, Op::Union),
            CsgNode::Difference(c) => (c, Op::Difference),
            CsgNode::Intersection(c) => (c, Op::Intersection),
        };
        let mut n = 0;
        for c in children {
            if compile(c, prog) {
                n += 1;
            }
        }
        if n == 0 {
            return false;
        }
        if n > 1 {
            prog.push(op(n));
        }
        true
    }
    let mut tops = Vec::new();
    flatten(csg, &mut tops);
    tops.into_iter()
        .filter_map(|n| {
            let mut program = Vec::new();
            if !compile(n, &mut program) {
                return None;
            }
            let mut parts: Vec<usize> = Vec::new();
            for op in &program {
                if let Op::Part(i) = op
                    && !parts.contains(&(*i as usize))
                {
                    parts.push(*i as usize);
                }
            }
            let split = split_difference(&program);
            Some(Item {
                program,
                parts,
                split,
            })
        })
        .collect()
}

/// Evaluates a boolean program: is the point inside, given each part's membership?
pub fn eval_inside(program: &[Op], inside: &dyn Fn(usize) -> bool) -> bool {
    let mut stack: Vec<bool> = Vec::with_capacity(8);
    for op in program {
        match *op {
            Op::Part(i) => stack.push(inside(i as usize)),
            Op::Union(n) => {
                let at = stack.len() - n as usize;
                let v = stack[at..].iter().any(|&b| b);
                stack.truncate(at);
                stack.push(v);
            }
            Op::Difference(n) => {
                let at = stack.len() - n as usize;
                let v = stack[at] && !stack[at + 1..].iter().any(|&b| b);
                stack.truncate(at);
                stack.push(v);
            }
            Op::Intersection(n) => {
                let at = stack.len() - n as usize;
                let v = stack[at..].iter().all(|&b| b);
                stack.truncate(at);
                stack.push(v);
            }
        }
    }
    stack.pop().unwrap_or(false)
}

/// Soft coverage of a program from its parts' coverages, with the derivative with respect
/// to part `seed`'s coverage: union `1 − Π(1 − a)`, intersection `Π a`, difference: its
/// first operand (holes are decided exactly, not softly).
pub fn eval_soft(program: &[Op], alpha: &dyn Fn(usize) -> f64, seed: Option<usize>) -> (f64, f64) {
    let mut stack: Vec<(f64, f64)> = Vec::with_capacity(8);
    for op in program {
        match *op {
            Op::Part(i) => {
                let d = if seed == Some(i as usize) { 1.0 } else { 0.0 };
                stack.push((alpha(i as usize), d));
            }
            Op::Union(n) => {
                let at = stack.len() - n as usize;
                // 1 − Π(1 − a): value and forward derivative.
                let (mut p, mut dp) = (1.0, 0.0);
                for &(a, da) in &stack[at..] {
                    dp = dp * (1.0 - a) - p * da;
                    p *= 1.0 - a;
                }
                stack.truncate(at);
                stack.push((1.0 - p, -dp));
            }
            Op::Difference(n) => {
                let at = stack.len() - n as usize;
                let first = stack[at];
                stack.truncate(at);
                stack.push(first);
            }
            Op::Intersection(n) => {
                let at = stack.len() - n as usize;
                let (mut p, mut dp) = (1.0, 0.0);
                for &(a, da) in &stack[at..] {
                    dp = dp * a + p * da;
                    p *= a;
                }
                stack.truncate(at);
                stack.push((p, dp));
            }
        }
    }
    stack.pop().unwrap_or((0.0, 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn soft_union_derivative() {
        let prog = [Op::Part(0), Op::Part(1), Op::Union(2)];
        let a = |i: usize| [0.3, 0.6][i];
        let (v, d) = eval_soft(&prog, &a, Some(0));
        assert!((v - (1.0 - 0.7 * 0.4)).abs() < 1e-12);
        assert!((d - 0.4).abs() < 1e-12);
    }
}

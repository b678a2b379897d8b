//! Interval lists along one line, and the CSG tree flattened for evaluating them.
//!
//! An [`Iv`] is a stretch `t0 < t1` of a line inside a solid, with the surfaces ([`Surf`])
//! that bound it. Every list this module produces is *sorted and disjoint* up to a tolerance
//! `eps` (far below any feature, far above rounding): `t1` of one interval is more than `eps`
//! below `t0` of the next (touching intervals are merged), and every interval is longer than
//! `eps`. Booleans: union merges, intersection keeps common stretches, difference cuts and
//! flips the subtracted surfaces (their outward normals point into the result). Ends within
//! `eps` of each other are ordered by a canonical order of surfaces, so that coincident faces
//! (parts stacked on each other) give the same structure on every ray.
//!
//! A [`Program`] is a CSG tree over shape indices in prefix order, each node knowing how many
//! nodes its subtree spans, so a subtree can be skipped. An empty program is the empty solid.
//! [`Program::prune`] keeps only the shapes a region can see, simplifying booleans whose
//! operands vanish; evaluation appends the result to a caller's buffer and allocates nothing
//! once the buffer has grown.

use crate::ir::CsgNode;

/// The surface at one end of an interval: a face of a shape, possibly seen from inside.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) struct Surf {
    pub shape: u32,
    pub face: u8,
    /// The outward normal of the result is the face's inward one (a subtracted surface).
    pub flip: bool,
}

impl Surf {
    /// A total order on surfaces, for breaking ties canonically.
    pub fn key(self) -> u64 {
        u64::from(self.shape) << 16 | u64::from(self.face) << 1 | u64::from(self.flip)
    }

    fn flipped(self) -> Surf {
        Surf {
            flip: !self.flip,
            ..self
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Iv {
    pub t0: f64,
    pub t1: f64,
    pub s0: Surf,
    pub s1: Surf,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Op {
    Part(u32),
    Union,
    Inter,
    Diff,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Node {
    pub op: Op,
    /// Number of children (0 for a part).
    pub n: u32,
    /// Nodes in this subtree, itself included.
    pub len: u32,
}

/// A CSG tree in prefix order; empty means the empty solid.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Program {
    pub nodes: Vec<Node>,
}

/// Marks a part index that has no shape (a degenerate part, or one out of range).
const NO_SHAPE: u32 = u32::MAX;

impl Program {
    /// The tree of `csg`, with each part index mapped to a shape index (`None`: empty part).
    pub fn from_csg(csg: &CsgNode, shape_of: &dyn Fn(usize) -> Option<u32>) -> Program {
        fn walk(n: &CsgNode, shape_of: &dyn Fn(usize) -> Option<u32>, out: &mut Vec<Node>) {
            let at = out.len();
            let (op, kids) = match n {
                CsgNode::Part(i) => {
                    let s = shape_of(*i).unwrap_or(NO_SHAPE);
                    out.push(Node {
                        op: Op::Part(s),
                        n: 0,
                        len: 1,
                    });
                    return;
                }
                CsgNode::Union(c) => (Op::Union, c),
                CsgNode::Intersection(c) => (Op::Inter, c),
                CsgNode::Difference(c) => (Op::Diff, c),
            };
            out.push(Node { op, n: 0, len: 0 });
            for c in kids {
                walk(c, shape_of, out);
            }
            out[at].n = kids.len() as u32;
            out[at].len = (out.len() - at) as u32;
        }
        let mut raw = Program::default();
        walk(csg, shape_of, &mut raw.nodes);
        raw.prune(&|s| s != NO_SHAPE)
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Every shape index the program refers to (with repeats).
    pub fn shapes(&self) -> impl Iterator<Item = u32> + '_ {
        self.nodes.iter().filter_map(|n| match n.op {
            Op::Part(s) => Some(s),
            _ => None,
        })
    }

    /// The same solid where only shapes with `active(shape)` exist.
    pub fn prune(&self, active: &dyn Fn(u32) -> bool) -> Program {
        let mut out = Program {
            nodes: Vec::with_capacity(self.nodes.len()),
        };
        self.prune_into(active, &mut out);
        out
    }

    /// [`Program::prune`] into an existing program (reusing its storage).
    pub fn prune_into(&self, active: &dyn Fn(u32) -> bool, out: &mut Program) {
        out.nodes.clear();
        if !self.nodes.is_empty() {
            self.prune_at(0, active, &mut out.nodes);
        }
    }

    /// Emits the pruned subtree at `pos`; returns false (emitting nothing) when it is empty.
    fn prune_at(&self, pos: usize, active: &dyn Fn(u32) -> bool, out: &mut Vec<Node>) -> bool {
        let node = self.nodes[pos];
        if let Op::Part(s) = node.op {
            if active(s) {
                out.push(node);
            }
            return active(s);
        }
        let head = out.len();
        out.push(node);
        let mut kept = 0u32;
        let mut child = pos + 1;
        for k in 0..node.n {
            let nonempty = self.prune_at(child, active, out);
            child += self.nodes[child].len as usize;
            kept += u32::from(nonempty);
            let fatal = match node.op {
                Op::Inter => !nonempty,
                Op::Diff => k == 0 && !nonempty,
                _ => false,
            };
            if fatal {
                out.truncate(head);
                return false;
            }
        }
        match kept {
            0 => {
                out.truncate(head);
                false
            }
            1 => {
                out.remove(head);
                true
            }
            _ => {
                out[head].n = kept;
                out[head].len = (out.len() - head) as u32;
                true
            }
        }
    }

    /// Appends the solid's intervals along a line to `buf`; `hit(shape)` gives one shape's.
    /// Ends closer than `eps` are one point: touching intervals merge, slivers vanish.
    pub fn eval(&self, hit: &mut impl FnMut(u32) -> Option<Iv>, buf: &mut Vec<Iv>, eps: f64) {
        if !self.nodes.is_empty() {
            self.eval_at(0, hit, buf, eps);
        }
    }

    fn eval_at(
        &self,
        pos: usize,
        hit: &mut impl FnMut(u32) -> Option<Iv>,
        buf: &mut Vec<Iv>,
        eps: f64,
    ) {
        let node = self.nodes[pos];
        let start = buf.len();
        let mut child = pos + 1;
        match node.op {
            Op::Part(s) => buf.extend(hit(s)),
            Op::Union => {
                for _ in 0..node.n {
                    self.eval_at(child, hit, buf, eps);
                    child += self.nodes[child].len as usize;
                }
                union_tail(buf, start, eps);
            }
            Op::Inter | Op::Diff => {
                self.eval_at(child, hit, buf, eps);
                child += self.nodes[child].len as usize;
                for _ in 1..node.n {
                    if buf.len() == start {
                        break;
                    }
                    let mid = buf.len();
                    self.eval_at(child, hit, buf, eps);
                    child += self.nodes[child].len as usize;
                    if node.op == Op::Inter {
                        intersect_tail(buf, start, mid, eps);
                    } else if buf.len() > mid {
                        subtract_tail(buf, start, mid, eps);
                    }
                }
            }
        }
    }
}

/// `a` comes before `b`: earlier by more than `eps`, or within `eps` and first in the
/// canonical order of surfaces (so near-coincident ends are ordered the same way on every
/// ray, however rounding falls).
fn before(ta: f64, sa: Surf, tb: f64, sb: Surf, eps: f64) -> bool {
    ta < tb - eps || (ta <= tb + eps && sa.key() < sb.key())
}

/// `buf[start..]` holds several sorted lists one after another; makes it their union.
fn union_tail(buf: &mut Vec<Iv>, start: usize, eps: f64) {
    let v = &mut buf[start..];
    if v.len() <= 1 {
        return;
    }
    // Insertion sort: unions along one ray are short.
    for i in 1..v.len() {
        let mut j = i;
        while j > 0 && before(v[j].t0, v[j].s0, v[j - 1].t0, v[j - 1].s0, eps) {
            v.swap(j - 1, j);
            j -= 1;
        }
    }
    let mut w = 0;
    for r in 1..v.len() {
        if v[r].t0 <= v[w].t1 + eps {
            // The later end wins; of two within eps, the canonical one.
            if before(v[w].t1, v[r].s1, v[r].t1, v[w].s1, eps) {
                (v[w].t1, v[w].s1) = (v[r].t1, v[r].s1);
            }
        } else {
            w += 1;
            v[w] = v[r];
        }
    }
    buf.truncate(start + w + 1);
}

/// Replaces the lists `buf[start..mid]` and `buf[mid..]` by the result written after them.
fn replace_with_tail(buf: &mut Vec<Iv>, start: usize, end: usize) {
    let n = buf.len() - end;
    buf.copy_within(end.., start);
    buf.truncate(start + n);
}

/// `buf[start..mid] ∩ buf[mid..]`, left in `buf[start..]`.
fn intersect_tail(buf: &mut Vec<Iv>, start: usize, mid: usize, eps: f64) {
    let end = buf.len();
    let (mut i, mut j) = (start, mid);
    while i < mid && j < end {
        let (a, b) = (buf[i], buf[j]);
        // The later start and the earlier end.
        let (t0, s0) = if before(b.t0, a.s0, a.t0, b.s0, eps) {
            (a.t0, a.s0)
        } else {
            (b.t0, b.s0)
        };
        let (t1, s1) = if before(a.t1, a.s1, b.t1, b.s1, eps) {
            (a.t1, a.s1)
        } else {
            (b.t1, b.s1)
        };
        if t1 - t0 > eps {
            buf.push(Iv { t0, t1, s0, s1 });
        }
        if a.t1 < b.t1 {
            i += 1;
        } else {
            j += 1;
        }
    }
    replace_with_tail(buf, start, end);
}

/// `buf[start..mid] − buf[mid..]`, left in `buf[start..]`.
fn subtract_tail(buf: &mut Vec<Iv>, start: usize, mid: usize, eps: f64) {
    let end = buf.len();
    let mut j = mid;
    for i in start..mid {
        let a = buf[i];
        let (mut cur, mut cs) = (a.t0, a.s0);
        while j < end && buf[j].t1 <= cur + eps {
            j += 1;
        }
        let mut k = j;
        while k < end && buf[k].t0 < a.t1 - eps {
            let b = buf[k];
            if b.t0 > cur + eps {
                buf.push(Iv {
                    t0: cur,
                    t1: b.t0,
                    s0: cs,
                    s1: b.s0.flipped(),
                });
            }
            if b.t1 > cur {
                (cur, cs) = (b.t1, b.s1.flipped());
            }
            if b.t1 >= a.t1 - eps {
                break;
            }
            k += 1;
        }
        if cur < a.t1 - eps {
            buf.push(Iv {
                t0: cur,
                t1: a.t1,
                s0: cs,
                s1: a.s1,
            });
        }
        j = k;
    }
    replace_with_tail(buf, start, end);
}

/// Total length of a sorted list inside `[z0, z1]`.
pub(crate) fn clipped_len(v: &[Iv], z0: f64, z1: f64) -> f64 {
    v.iter()
        .map(|iv| (iv.t1.min(z1) - iv.t0.max(z0)).max(0.0))
        .sum()
}

/// Length of `a ∩ b ∩ [z0, z1]` for two sorted lists.
pub(crate) fn clipped_common_len(a: &[Iv], b: &[Iv], z0: f64, z1: f64) -> f64 {
    let (mut i, mut j, mut sum) = (0, 0, 0.0);
    while i < a.len() && j < b.len() {
        let lo = a[i].t0.max(b[j].t0).max(z0);
        let hi = a[i].t1.min(b[j].t1).min(z1);
        if hi > lo {
            sum += hi - lo;
        }
        if a[i].t1 < b[j].t1 {
            i += 1;
        } else {
            j += 1;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(t0: f64, t1: f64, shape: u32) -> Iv {
        let s = Surf {
            shape,
            face: 0,
            flip: false,
        };
        Iv {
            t0,
            t1,
            s0: s,
            s1: s,
        }
    }

    fn ends(v: &[Iv]) -> Vec<(f64, f64)> {
        v.iter().map(|i| (i.t0, i.t1)).collect()
    }

    fn run(csg: CsgNode, lists: Vec<Vec<(f64, f64)>>) -> Vec<Iv> {
        let n = lists.len();
        let prog = Program::from_csg(&csg, &|i| (i < n).then_some(i as u32));
        let mut buf = Vec::new();
        // Each "shape" is one interval here; a part with two uses its first only.
        prog.eval(
            &mut |s| lists[s as usize].first().map(|&(a, b)| iv(a, b, s)),
            &mut buf,
            0.0,
        );
        buf
    }

    #[test]
    fn union_merges_touching_and_overlapping() {
        let u = CsgNode::Union((0..3).map(CsgNode::Part).collect());
        let r = run(
            u,
            vec![vec![(2.0, 3.0)], vec![(0.0, 1.0)], vec![(1.0, 2.5)]],
        );
        assert_eq!(ends(&r), vec![(0.0, 3.0)]);
    }

    #[test]
    fn difference_cuts_and_flips() {
        let d = CsgNode::Difference((0..3).map(CsgNode::Part).collect());
        let r = run(
            d,
            vec![vec![(0.0, 10.0)], vec![(2.0, 3.0)], vec![(5.0, 12.0)]],
        );
        assert_eq!(ends(&r), vec![(0.0, 2.0), (3.0, 5.0)]);
        assert!(r[0].s1.flip && r[1].s0.flip && r[1].s1.flip && !r[0].s0.flip);
        // Subtracting something touching only an end removes nothing.
        let d = CsgNode::Difference((0..2).map(CsgNode::Part).collect());
        let r = run(d, vec![vec![(0.0, 1.0)], vec![(1.0, 2.0)]]);
        assert_eq!(ends(&r), vec![(0.0, 1.0)]);
    }

    #[test]
    fn intersection_and_pruning() {
        let n = CsgNode::Intersection((0..2).map(CsgNode::Part).collect());
        let r = run(n.clone(), vec![vec![(0.0, 2.0)], vec![(1.0, 3.0)]]);
        assert_eq!(ends(&r), vec![(1.0, 2.0)]);
        // A missing operand empties an intersection and is dropped from a union.
        let p = Program::from_csg(&n, &|i| (i == 0).then_some(0));
        assert!(p.is_empty());
        let u = CsgNode::Union(vec![CsgNode::Part(0), CsgNode::Part(1)]);
        let p = Program::from_csg(&u, &|i| (i == 0).then_some(0));
        assert_eq!(p.nodes.len(), 1);
        let d = CsgNode::Difference(vec![CsgNode::Part(1), CsgNode::Part(0)]);
        assert!(Program::from_csg(&d, &|i| (i == 0).then_some(0)).is_empty());
    }

    #[test]
    fn clipped_lengths() {
        let a = vec![iv(0.0, 2.0, 0), iv(3.0, 5.0, 0)];
        let b = vec![iv(1.0, 4.0, 1)];
        assert_eq!(clipped_len(&a, 1.0, 10.0), 3.0);
        assert_eq!(
            clipped_common_len(&a, &b, f64::NEG_INFINITY, f64::INFINITY),
            2.0
        );
        assert_eq!(clipped_common_len(&a, &b, 1.5, 3.5), 1.0);
    }
}

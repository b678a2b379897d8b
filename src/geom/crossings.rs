//! Where the break curves of shapes that meet on vertical lines cross each other.
//!
//! Along a line the length inside a boolean of shapes is smooth between the line's breaks
//! (`breaks`); as the line moves, each break slides along a curve of the plane (a rim, an
//! edge, a silhouette, a level curve where a curved surface meets another shape's flat
//! face). The integral along the line stays smooth while these curves keep their order, but
//! where two curves of shapes that overlap in z cross (two elliptic rims of a noisy copy of
//! the same part, a rim and a level curve), the integrand's kinks along the two curves
//! interact and the integral has a kink too. The shapes' own axis breaks do not see these
//! points: they involve two shapes. [`crossings`] finds them from the breaks alone (no ray
//! is cast): it compares the order of every pair of labelled breaks of overlapping shapes at
//! points across a strip, and bisects where the order changes. A crossing missed (two within
//! one step of the scan) only leaves a kink to the adaptive quadrature: slower, not wrong.

use super::breaks::LEVEL;
use super::shape::Shape;
use crate::tolerance::{GEOM_BISECTION, GEOM_SCAN_INSET, GEOM_SLIVER};

/// Scan points across a strip (plus one near each end).
const SCAN: usize = 30;
/// Most crossings located in one strip.
const MOST: usize = 64;

/// The break curves of one strip: its shapes and their level curves.
pub(crate) struct Curves<'a> {
    pub shapes: &'a [Shape],
    /// The strip's shapes.
    pub ids: &'a [u32],
    /// Level curves `(shape, height)` (see `Shape::level_breaks`).
    pub levels: &'a [(u32, f64)],
    /// `(outer, inner)` axes: lines run along `inner`.
    pub axes: (usize, usize),
    /// Ends within this are one point.
    pub eps: f64,
}

/// Scratch for [`crossings`]: the labelled breaks of one line, and which shapes of the
/// strip overlap in z.
#[derive(Default)]
pub(crate) struct Scratch {
    entries: Vec<(u32, f64)>,
    meets: Vec<u64>,
}

/// Pushes to `out` the outer coordinates in `(a, b)` where two break curves of shapes that
/// overlap in z cross, in increasing order.
pub(crate) fn crossings(cv: &Curves, a: f64, b: f64, sc: &mut Scratch, out: &mut Vec<f64>) {
    let n = cv.ids.len();
    if n > 64 || !(b > a) {
        return;
    }
    sc.meets.clear();
    for &i in cv.ids {
        let s = &cv.shapes[i as usize];
        let mut m = 0u64;
        for (q, &j) in cv.ids.iter().enumerate() {
            let t = &cv.shapes[j as usize];
            if s.lo[2] <= t.hi[2] + cv.eps && t.lo[2] <= s.hi[2] + cv.eps {
                m |= 1 << q;
            }
        }
        sc.meets.push(m);
    }
    let w = b - a;
    let first = out.len();
    let mut pts = Vec::with_capacity(SCAN + 2);
    pts.push(a + GEOM_SCAN_INSET * w);
    pts.extend((0..SCAN).map(|i| a + w * (i as f64 + 0.5) / SCAN as f64));
    pts.push(b - GEOM_SCAN_INSET * w);
    let mut prev = (pts[0], signature(cv, pts[0], sc));
    for &p in &pts[1..] {
        let next = (p, signature(cv, p, sc));
        // Every change between the two points, from the left.
        let mut lo = prev;
        while lo.1 != next.1 && out.len() - first < MOST {
            let (x, after) = locate(cv, lo, next, GEOM_BISECTION * w, sc);
            if x > a + GEOM_SLIVER * w && x < b - GEOM_SLIVER * w {
                out.push(x);
            }
            lo = after;
        }
        prev = next;
    }
    // Two changes closer than a sliver are one cut.
    let mut last = f64::NEG_INFINITY;
    let mut k = first;
    for i in first..out.len() {
        if out[i] - last > GEOM_SLIVER * w {
            last = out[i];
            out[k] = out[i];
            k += 1;
        }
    }
    out.truncate(k);
}

/// The first change of signature after `lo` towards `hi` (whose signatures differ), to
/// within `tol`: the cut, and the point just past it with its signature.
fn locate(
    cv: &Curves,
    lo: (f64, u64),
    hi: (f64, u64),
    tol: f64,
    sc: &mut Scratch,
) -> (f64, (f64, u64)) {
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..64 {
        let m = 0.5 * (lo.0 + hi.0);
        if !(hi.0 - lo.0 > tol) || m <= lo.0 || m >= hi.0 {
            break;
        }
        let s = signature(cv, m, sc);
        if s == lo.1 {
            lo = (m, s);
        } else {
            hi = (m, s);
        }
    }
    (0.5 * (lo.0 + hi.0), hi)
}

/// A hash of which breaks the line at `c` has and, for every two on different curves of
/// shapes that overlap in z, which comes first.
fn signature(cv: &Curves, c: f64, sc: &mut Scratch) -> u64 {
    let (o, _) = cv.axes;
    let e = &mut sc.entries;
    e.clear();
    for (p, &i) in cv.ids.iter().enumerate() {
        let s = &cv.shapes[i as usize];
        if !(c > s.lo[o] && c < s.hi[o]) {
            continue;
        }
        let key = (p as u32) << 16;
        s.labelled_breaks(o, c, &mut |y, l| e.push((key | u32::from(l), y)));
        let mut k = 0;
        for &(j, h) in cv.levels {
            if j == i {
                s.level_breaks(o, c, h, &mut |y, l| {
                    e.push((key | (u32::from(LEVEL) + 2 * k + u32::from(l)), y))
                });
                k += 1;
            }
        }
    }
    e.sort_unstable_by_key(|x| x.0);
    let mut h = Hasher::new();
    e.iter().for_each(|x| h.add(u64::from(x.0)));
    let (mut word, mut bits) = (0u64, 0);
    for (i, &(ki, yi)) in e.iter().enumerate() {
        let meets = sc.meets[(ki >> 16) as usize];
        for &(kj, yj) in &e[i + 1..] {
            if ki >> 1 == kj >> 1 || meets >> (kj >> 16) & 1 == 0 {
                continue;
            }
            // Within eps, the order of the keys.
            word = word << 1 | u64::from(yi <= yj + cv.eps);
            bits += 1;
            if bits == 64 {
                h.add(word);
                (word, bits) = (0, 0);
            }
        }
    }
    h.add(word);
    h.add(bits);
    h.finish()
}

/// A small non-cryptographic hash of a token sequence.
pub(crate) struct Hasher(u64);

impl Hasher {
    pub fn new() -> Self {
        Hasher(0x243f_6a88_85a3_08d3)
    }
    pub fn add(&mut self, token: u64) {
        self.0 = (self.0 ^ token).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        self.0 ^= self.0 >> 31;
    }
    pub fn finish(&self) -> u64 {
        self.0
    }
}

//! Roles of parts in their arrangement: names from geometry when the source says nothing.
//!
//! A part's role is read from where it stands among the others, never from its number:
//! - uprights whose tops meet the underside of a wider part are `leg`s under a `top`, or
//!   under a `seat` when a tall thin part (its `back`) stands on it; other upright boxes
//!   are `post`s;
//! - a long horizontal rod with round parts centred on its axis is an `axle` with `wheel`s;
//! - a thin board spanning most of the model on one of its outer faces is a `side`, `back`,
//!   `front`, `bottom` or `top` panel, and one inside is a `shelf` (horizontal) or a
//!   `divider`;
//! - what a difference takes away is a `hole` (round) or a `cutout`;
//! - anything else is named by its shape (`bar`, `board`, `block`, `rod`, `disc`,
//!   `cylinder`, `ball`).
//!
//! Parts of one role are told apart by side and order words ([`Label::place`]: `front`,
//! `left`, `upper`, `middle`, `second`), never by counters. Invariant: every label has a
//! role word, and two parts with the same role have different places unless they stand at
//! the same place (then order words tell them apart).

use crate::ir::feature::axial_axis;
use crate::ir::{CsgNode, Model, Primitive};
use crate::tolerance::ROLE_CONTACT;

/// A part's name from geometry: what it is and where it stands among its kind.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Label {
    pub role: &'static str,
    /// Side and order words, outermost axis first (`["front", "left"]`).
    pub place: Vec<String>,
}

impl Label {
    /// `front_left_leg`.
    pub fn words(&self) -> Vec<String> {
        let mut w = self.place.clone();
        w.push(self.role.to_string());
        w
    }
}

/// An upright is at least this many times taller than it is wide.
const UPRIGHT_RATIO: f64 = 1.5;
/// A rod is at least this many times longer than its diameter; a disc at most as long.
const ROD_RATIO: f64 = 3.0;
/// A board's thickness is at most this fraction of its next smallest extent.
const BOARD_RATIO: f64 = 0.25;
/// A panel spans at least this fraction of the model's extent along its two long sides.
const PANEL_SPAN: f64 = 0.5;

/// One part's box and what it is, at the input.
struct Shape {
    lo: [f64; 3],
    hi: [f64; 3],
    kind: Kind,
    /// Added to the model (not taken away by a difference).
    solid: bool,
}

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Cube,
    /// A cylinder with its axis along this world axis (`None`: turned off the axes).
    Cylinder(Option<usize>),
    Sphere,
}

impl Shape {
    fn ext(&self, a: usize) -> f64 {
        self.hi[a] - self.lo[a]
    }
    fn centre(&self, a: usize) -> f64 {
        0.5 * (self.lo[a] + self.hi[a])
    }
}

/// Which parts a difference takes away (every child after its first, and below them).
fn taken_away(node: &CsgNode, away: bool, out: &mut [bool]) {
    match node {
        CsgNode::Part(i) => {
            if let Some(o) = out.get_mut(*i) {
                *o = away;
            }
        }
        CsgNode::Union(c) | CsgNode::Intersection(c) => {
            c.iter().for_each(|n| taken_away(n, away, out));
        }
        CsgNode::Difference(c) => {
            for (k, n) in c.iter().enumerate() {
                taken_away(n, away || k > 0, out);
            }
        }
    }
}

fn shapes(model: &Model) -> Vec<Shape> {
    let mut away = vec![false; model.parts.len()];
    taken_away(&model.csg, false, &mut away);
    model
        .parts
        .iter()
        .zip(away)
        .map(|(p, away)| {
            let (lo, hi) = p.world_bounds();
            let kind = match p.primitive {
                Primitive::Cube { .. } => Kind::Cube,
                Primitive::Cylinder { .. } => Kind::Cylinder(axial_axis(p)),
                Primitive::Sphere { .. } => Kind::Sphere,
            };
            Shape {
                lo,
                hi,
                kind,
                solid: !away,
            }
        })
        .collect()
}

/// The role of every part, then its place among the parts of its role.
pub fn part_labels(model: &Model) -> Vec<Label> {
    let shapes = shapes(model);
    let (lo, hi) = model.bounds().unwrap_or(([0.0; 3], [0.0; 3]));
    let tol = ROLE_CONTACT * model.size().max(f64::MIN_POSITIVE);
    let mut roles: Vec<Option<&'static str>> = vec![None; shapes.len()];
    wheels_and_axles(&shapes, tol, &mut roles);
    legs_and_tops(&shapes, tol, &mut roles);
    panels(&shapes, (lo, hi), tol, &mut roles);
    for (r, s) in roles.iter_mut().zip(&shapes) {
        if r.is_none() {
            *r = Some(shape_word(s));
        }
    }
    let roles: Vec<&'static str> = roles.into_iter().map(|r| r.unwrap_or("part")).collect();
    places(&shapes, &roles, tol)
}

/// What a part is called by its shape alone.
fn shape_word(s: &Shape) -> &'static str {
    match s.kind {
        Kind::Cube if !s.solid => "cutout",
        Kind::Cube => {
            let mut e = [s.ext(0), s.ext(1), s.ext(2)];
            e.sort_by(f64::total_cmp);
            if e[2] >= ROD_RATIO * e[1] {
                "bar"
            } else if e[0] <= BOARD_RATIO * e[1] {
                "board"
            } else {
                "block"
            }
        }
        Kind::Cylinder(_) | Kind::Sphere if !s.solid => "hole",
        Kind::Sphere => "ball",
        Kind::Cylinder(Some(a)) => {
            let d = (0..3)
                .filter(|&b| b != a)
                .map(|b| s.ext(b))
                .fold(0.0, f64::max);
            if s.ext(a) >= ROD_RATIO * d {
                "rod"
            } else if s.ext(a) <= d / ROD_RATIO {
                "disc"
            } else {
                "cylinder"
            }
        }
        Kind::Cylinder(None) => "cylinder",
    }
}

/// Axles (long horizontal rods) and the round parts centred on their axis (wheels).
fn wheels_and_axles(shapes: &[Shape], tol: f64, roles: &mut [Option<&'static str>]) {
    for (i, axle) in shapes.iter().enumerate() {
        let Kind::Cylinder(Some(a)) = axle.kind else {
            continue;
        };
        let across: Vec<usize> = (0..3).filter(|&b| b != a).collect();
        let d = across.iter().map(|&b| axle.ext(b)).fold(0.0, f64::max);
        if !axle.solid || a == 2 || axle.ext(a) < ROD_RATIO * d {
            continue;
        }
        let wheels: Vec<usize> = shapes
            .iter()
            .enumerate()
            .filter(|&(j, w)| {
                let round = match w.kind {
                    Kind::Sphere => true,
                    Kind::Cylinder(Some(b)) => b == a,
                    _ => false,
                };
                j != i
                    && w.solid
                    && round
                    && across
                        .iter()
                        .all(|&b| (w.centre(b) - axle.centre(b)).abs() <= tol && w.ext(b) > d)
                    && w.centre(a) >= axle.lo[a] - w.ext(a)
                    && w.centre(a) <= axle.hi[a] + w.ext(a)
            })
            .map(|(j, _)| j)
            .collect();
        if wheels.len() >= 2 {
            roles[i] = Some("axle");
            for j in wheels {
                roles[j] = Some("wheel");
            }
        }
    }
}

/// Uprights under a wider part: legs, and the top (or seat, with the back standing on it)
/// they hold up; uprights under nothing are posts.
fn legs_and_tops(shapes: &[Shape], tol: f64, roles: &mut [Option<&'static str>]) {
    let free = |roles: &[Option<&str>], i: usize| roles[i].is_none() && shapes[i].solid;
    let upright = |s: &Shape| s.ext(2) >= UPRIGHT_RATIO * s.ext(0).max(s.ext(1)) && s.ext(2) > tol;
    // Each upright holds up the first part its top reaches: the lowest underside.
    let mut held: Vec<Vec<usize>> = vec![Vec::new(); shapes.len()];
    for (l, leg) in shapes.iter().enumerate() {
        if !free(roles, l) || !upright(leg) {
            continue;
        }
        let under = shapes
            .iter()
            .enumerate()
            .filter(|&(t, top)| {
                t != l
                    && free(roles, t)
                    && !upright(top)
                    && leg.hi[2] >= top.lo[2] - tol
                    && leg.hi[2] <= top.hi[2] + tol
                    && leg.lo[2] < top.lo[2] - tol
                    && (0..2).all(|a| {
                        leg.centre(a) >= top.lo[a] - tol && leg.centre(a) <= top.hi[a] + tol
                    })
            })
            .min_by(|a, b| a.1.lo[2].total_cmp(&b.1.lo[2]));
        if let Some((t, _)) = under {
            held[t].push(l);
        }
    }
    for (t, legs) in held.iter().enumerate() {
        if legs.len() < 2 {
            continue;
        }
        let top = &shapes[t];
        for &l in legs {
            roles[l] = Some("leg");
        }
        // A tall board standing on it makes it a seat with a back.
        let back = shapes.iter().enumerate().find(|&(b, s)| {
            free(roles, b)
                && b != t
                && s.lo[2] >= top.lo[2] - tol
                && s.lo[2] <= top.hi[2] + tol
                && s.ext(2) >= UPRIGHT_RATIO * top.ext(2)
                && s.ext(0).min(s.ext(1)) <= BOARD_RATIO * s.ext(0).max(s.ext(1))
        });
        roles[t] = Some(if back.is_some() { "seat" } else { "top" });
        if let Some((b, _)) = back {
            roles[b] = Some("back");
        }
    }
    for (i, s) in shapes.iter().enumerate() {
        if free(roles, i) && upright(s) && matches!(s.kind, Kind::Cube) {
            roles[i] = Some("post");
        }
    }
}

/// Thin boards: panels on the model's outer faces, shelves and dividers inside.
fn panels(
    shapes: &[Shape],
    (lo, hi): ([f64; 3], [f64; 3]),
    tol: f64,
    roles: &mut [Option<&'static str>],
) {
    for (i, s) in shapes.iter().enumerate() {
        if roles[i].is_some() || !s.solid {
            continue;
        }
        let mut axes = [0, 1, 2];
        axes.sort_by(|&a, &b| s.ext(a).total_cmp(&s.ext(b)));
        let [thin, mid, long] = axes;
        if s.ext(thin) > BOARD_RATIO * s.ext(mid) {
            continue;
        }
        let spans = [mid, long]
            .iter()
            .all(|&a| s.ext(a) >= PANEL_SPAN * (hi[a] - lo[a]));
        if !spans {
            continue;
        }
        let at_low = s.lo[thin] <= lo[thin] + tol;
        let at_high = s.hi[thin] >= hi[thin] - tol;
        roles[i] = Some(match (thin, at_low, at_high) {
            (0, true, _) | (0, _, true) => "side",
            (1, true, _) => "front",
            (1, _, true) => "back",
            (2, true, _) => "bottom",
            (2, _, true) => "top",
            (2, false, false) => "shelf",
            _ => "divider",
        });
    }
}

/// Words for the levels along one axis, low to high.
fn level_words(axis: usize, n: usize) -> Option<Vec<&'static str>> {
    let words: &[&[&'static str]] = match axis {
        0 => &[&["left", "right"], &["left", "middle", "right"]],
        1 => &[&["front", "back"], &["front", "middle", "back"]],
        _ => &[&["lower", "upper"], &["lower", "middle", "upper"]],
    };
    match n {
        2 | 3 => Some(words[n - 2].to_vec()),
        _ => None,
    }
}

/// The order word for place `k` from 0: `first`, `second`, …, `twenty_first`, … (words,
/// so never a counter; distinct for every `k`).
pub fn ordinal(k: usize) -> String {
    const ORD: [&str; 20] = [
        "",
        "first",
        "second",
        "third",
        "fourth",
        "fifth",
        "sixth",
        "seventh",
        "eighth",
        "ninth",
        "tenth",
        "eleventh",
        "twelfth",
        "thirteenth",
        "fourteenth",
        "fifteenth",
        "sixteenth",
        "seventeenth",
        "eighteenth",
        "nineteenth",
    ];
    const CARD: [&str; 20] = [
        "",
        "one",
        "two",
        "three",
        "four",
        "five",
        "six",
        "seven",
        "eight",
        "nine",
        "ten",
        "eleven",
        "twelve",
        "thirteen",
        "fourteen",
        "fifteen",
        "sixteen",
        "seventeen",
        "eighteen",
        "nineteen",
    ];
    const TENS: [&str; 10] = [
        "", "", "twenty", "thirty", "forty", "fifty", "sixty", "seventy", "eighty", "ninety",
    ];
    const TENTHS: [&str; 10] = [
        "",
        "",
        "twentieth",
        "thirtieth",
        "fortieth",
        "fiftieth",
        "sixtieth",
        "seventieth",
        "eightieth",
        "ninetieth",
    ];
    fn below_hundred(n: usize) -> String {
        match n {
            0..20 => ORD[n].to_string(),
            _ if n.is_multiple_of(10) => TENTHS[n / 10].to_string(),
            _ => format!("{}_{}", TENS[n / 10], ORD[n % 10]),
        }
    }
    fn cardinal(n: usize) -> String {
        match n {
            0..20 => CARD[n].to_string(),
            20..100 if n.is_multiple_of(10) => TENS[n / 10].to_string(),
            20..100 => format!("{}_{}", TENS[n / 10], CARD[n % 10]),
            _ => format!("{}_hundred_{}", cardinal(n / 100), cardinal(n % 100)),
        }
    }
    let n = k + 1;
    if n < 100 {
        below_hundred(n)
    } else if n.is_multiple_of(100) {
        format!("{}_hundredth", cardinal(n / 100))
    } else {
        format!("{}_hundred_{}", cardinal(n / 100), below_hundred(n % 100))
    }
}

/// The distinct levels of `values` (within `tol`), low to high, and each value's level.
fn levels(values: &[f64], tol: f64) -> (usize, Vec<usize>) {
    let mut sorted: Vec<f64> = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let mut reps: Vec<f64> = Vec::new();
    for v in sorted {
        if reps.last().is_none_or(|r| v - r > tol) {
            reps.push(v);
        }
    }
    let of = values
        .iter()
        .map(|v| reps.iter().rposition(|r| v - r >= -tol).unwrap_or(0))
        .collect();
    (reps.len(), of)
}

/// Side and order words telling apart the parts of each role.
fn places(shapes: &[Shape], roles: &[&'static str], tol: f64) -> Vec<Label> {
    let mut labels: Vec<Label> = roles
        .iter()
        .map(|&role| Label {
            role,
            place: Vec::new(),
        })
        .collect();
    let mut done = vec![false; roles.len()];
    for i in 0..roles.len() {
        if done[i] {
            continue;
        }
        let group: Vec<usize> = (i..roles.len()).filter(|&j| roles[j] == roles[i]).collect();
        group.iter().for_each(|&j| done[j] = true);
        if group.len() < 2 {
            continue;
        }
        // Front/back first, then left/right, then lower/upper, as people say it.
        let varying: Vec<(usize, usize, Vec<usize>)> = [1, 0, 2]
            .iter()
            .map(|&a| {
                let c: Vec<f64> = group.iter().map(|&j| shapes[j].centre(a)).collect();
                let (n, of) = levels(&c, tol);
                (a, n, of)
            })
            .filter(|(_, n, _)| *n > 1)
            .collect();
        let single = varying.len() == 1;
        for (a, n, of) in &varying {
            let words = level_words(*a, *n);
            for (k, &j) in group.iter().enumerate() {
                match &words {
                    Some(w) => labels[j].place.push(w[of[k]].to_string()),
                    None if single => labels[j].place.push(ordinal(of[k])),
                    None => {}
                }
            }
        }
        // Parts still sharing a place get order words in source order.
        let before: Vec<Vec<String>> = group.iter().map(|&j| labels[j].place.clone()).collect();
        for (k, &j) in group.iter().enumerate() {
            let same: Vec<usize> = group
                .iter()
                .zip(&before)
                .filter(|(_, p)| **p == before[k])
                .map(|(&m, _)| m)
                .collect();
            if same.len() > 1 {
                let rank = same.iter().position(|&m| m == j).unwrap_or(k);
                labels[j].place.insert(0, ordinal(rank));
            }
        }
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_cluster_within_the_tolerance() {
        let (n, of) = levels(&[0.0, 10.0, 0.0000001, 5.0], 0.001);
        assert_eq!(n, 3);
        assert_eq!(of, vec![0, 2, 0, 1]);
    }
}

//! The exact visible surface of a boolean item along one ray, by classifying the ray's
//! segments between its parts' entry and exit points. A surface found where the ray leaves a
//! subtracted part carries that part's normal turned inward.

use super::pixel::PartAt;
use crate::render::scene::{Op, eval_inside};
use glam::DVec3;

/// The first point at or after `t_start` where the item's solid begins (the point just
/// after `t_start` counts: it shows the surface being left there, turned inward).
pub(super) fn first_solid_from(
    program: &[Op],
    st: &[(u32, PartAt)],
    t_start: f64,
) -> Option<(f64, DVec3)> {
    let index_of = |p: usize| st.iter().position(|(q, _)| *q as usize == p);
    let mut inside: Vec<bool> = st
        .iter()
        .map(|(_, s)| s.hit.is_some_and(|h| h.t0 <= t_start && t_start < h.t1))
        .collect();
    let member =
        |inside: &[bool]| eval_inside(program, &|p| index_of(p).is_some_and(|k| inside[k]));
    if member(&inside) {
        // Solid right after leaving a part at t_start: that part's exit surface, inward.
        let k = st
            .iter()
            .position(|(_, s)| s.hit.is_some_and(|h| h.t1 == t_start))?;
        let h = st[k].1.hit?;
        return Some((t_start, -h.n1));
    }
    let mut events: Vec<(f64, usize, bool)> = Vec::new();
    for (k, (_, s)) in st.iter().enumerate() {
        if let Some(h) = s.hit {
            if h.t0 > t_start {
                events.push((h.t0, k, true));
            }
            if h.t1 > t_start {
                events.push((h.t1, k, false));
            }
        }
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    for &(t, k, entry) in &events {
        inside[k] = entry;
        if member(&inside) {
            let h = st[k].1.hit?;
            let n = if entry { h.n0 } else { -h.n1 };
            return Some((t, n));
        }
    }
    None
}

/// The first point along the ray where a boolean item's solid begins, with its outward
/// normal (an exit from a subtracted part shows that part's surface turned inward).
pub(super) fn visible_surface(program: &[Op], st: &[(u32, PartAt)]) -> Option<(f64, DVec3)> {
    visible_surface_at(program, st).map(|(t, n, _)| (t, n))
}

/// [`visible_surface`] with the state index of the part whose surface it is.
pub(super) fn visible_surface_at(
    program: &[Op],
    st: &[(u32, PartAt)],
) -> Option<(f64, DVec3, usize)> {
    // Entries and exits, each with the outward normal of the surface it shows.
    let mut events: Vec<(f64, usize, bool, DVec3)> = Vec::with_capacity(2 * st.len());
    let mut inside: Vec<bool> = vec![false; st.len()];
    for (k, (_, s)) in st.iter().enumerate() {
        if let Some(h) = s.hit {
            if h.t0 > 0.0 {
                events.push((h.t0, k, true, h.n0));
            } else {
                inside[k] = true;
            }
            events.push((h.t1, k, false, -h.n1));
        }
    }
    if events.is_empty() {
        return None;
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    let index_of = |p: usize| st.iter().position(|(q, _)| *q as usize == p);
    let member =
        |inside: &[bool]| eval_inside(program, &|p| index_of(p).is_some_and(|k| inside[k]));
    let mut was = member(&inside);
    for &(t, k, entry, n) in &events {
        inside[k] = entry;
        let now = member(&inside);
        if now && !was && t > 0.0 {
            return Some((t, n, k));
        }
        was = now;
    }
    None
}

//! Where to stop taking constraints: change-point detection on the distortion curve.
//!
//! The curve rises slowly while harmless relations are added, then jumps when a relation
//! fights the variations. The paper finds the jump on the curve's central-difference
//! derivative; the published code puts a single mean-shift change point on the curve
//! itself. Both are computed and reported; the paper's decides.

use super::noise::median;
use serde::Serialize;

#[derive(Debug, Clone, Serialize)]
pub struct Cutoff {
    /// Keep the first `keep` chosen constraints.
    pub keep: usize,
    /// The paper's change point (on the derivative), as a count of constraints kept.
    pub paper: usize,
    /// The published code's change point (on the curve), as a count of constraints kept.
    pub published: usize,
    /// Why, in words.
    pub reason: String,
}

/// The split `k` (1..n) minimising the squared deviation of `v[..k]` and `v[k..]` from
/// their means.
fn mean_shift(v: &[f64]) -> usize {
    let n = v.len();
    if n < 2 {
        return n;
    }
    let sse = |s: &[f64]| {
        let m = s.iter().sum::<f64>() / s.len() as f64;
        s.iter().map(|x| (x - m) * (x - m)).sum::<f64>()
    };
    (1..n)
        .min_by(|&a, &b| {
            let ca = sse(&v[..a]) + sse(&v[a..]);
            let cb = sse(&v[..b]) + sse(&v[b..]);
            ca.total_cmp(&cb)
        })
        .unwrap_or(n)
}

/// Central differences (one-sided at the ends).
fn derivative(curve: &[f64]) -> Vec<f64> {
    let n = curve.len();
    (0..n)
        .map(|i| {
            let lo = i.saturating_sub(1);
            let hi = (i + 1).min(n - 1);
            if hi == lo {
                0.0
            } else {
                (curve[hi] - curve[lo]) / (hi - lo) as f64
            }
        })
        .collect()
}

/// The paper's change point (on the curve's derivative) and the published code's (on the
/// curve itself), as counts of constraints kept, for the distortion `curve`.
pub fn change_points(curve: &[f64]) -> (usize, usize) {
    let steps = curve.len().saturating_sub(1);
    if steps == 0 {
        return (0, 0);
    }
    let published = mean_shift(curve).saturating_sub(1);
    let deriv = derivative(curve);
    // A jump between steps s−1 and s raises the central difference from index s−1 on,
    // so the derivative's level shift is at s−1: keep s−1 constraints.
    let paper = mean_shift(&deriv).min(steps);
    (paper, published)
}

/// How many times the typical step a step may cost before it counts as past the jump.
pub const OUTLIER_FACTOR: f64 = 3.0;

/// Whether a step's increment stands out from the `earlier` ones (their median). A step
/// costing no more than `tolerance` (the distortion the variations' noise explains) never
/// does.
fn is_outlier(increment: f64, earlier: &[f64], tolerance: f64) -> bool {
    increment > tolerance && increment > OUTLIER_FACTOR * median(earlier)
}

/// Decides how many chosen constraints to keep from the distortion `curve`
/// (`curve[s]` after `s` constraints). `tolerance` is the distortion the variations' own
/// noise explains: a curve that never exceeds it keeps everything. Only the first `plausible`
/// steps may be kept (later ones took relations the variations break beyond their noise).
pub fn cutoff(curve: &[f64], tolerance: f64, plausible: usize) -> Cutoff {
    let steps = curve.len().saturating_sub(1);
    if steps == 0 {
        return Cutoff {
            keep: 0,
            paper: 0,
            published: 0,
            reason: "no constraints were chosen".into(),
        };
    }
    let (paper, published) = change_points(curve);
    let max = curve.iter().copied().fold(0.0, f64::max);
    if max <= tolerance {
        return Cutoff {
            keep: steps.min(plausible),
            paper,
            published,
            reason: format!(
                "every constraint is compatible with the variations (distortion never exceeds {tolerance:.3})"
            ),
        };
    }
    // The last step kept must look like the steps before it: under noise the curve rises
    // all along, and the change point can land one step past the first relation that
    // fights the variations.
    let increments: Vec<f64> = curve.windows(2).map(|w| w[1] - w[0]).collect();
    let mut keep = paper.min(plausible);
    while keep > 0 && is_outlier(increments[keep - 1], &increments[..keep - 1], tolerance) {
        keep -= 1;
    }
    let mut reason = format!(
        "the distortion's derivative jumps after {paper} constraints (distortion {:.4} there, {:.4} one step later)",
        curve[paper],
        curve.get(paper + 1).copied().unwrap_or(curve[paper])
    );
    if plausible < paper {
        reason += &format!("; only the first {plausible} keep every variation within its noise");
    }
    if keep < paper.min(plausible) {
        let last = paper.min(plausible);
        let which = if keep + 1 == last {
            format!("step {last} costs")
        } else {
            format!("steps {} to {last} cost", keep + 1)
        };
        reason += &format!(
            "; {which} more than {OUTLIER_FACTOR} times the typical step, so {keep} are kept"
        );
    }
    Cutoff {
        keep,
        paper,
        published,
        reason,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_jump() {
        let mut curve = vec![0.0];
        for i in 1..=20 {
            curve.push(0.001 * i as f64);
        }
        for i in 0..10 {
            curve.push(0.3 + 0.05 * i as f64);
        }
        let c = cutoff(&curve, 0.01, usize::MAX);
        assert_eq!(c.keep, 20, "{c:?}");
    }

    /// A curve from 0 rising by `step` for `n` steps, then to `last`, then five points
    /// from `jump` on, 0.1 apart.
    fn steps_then_jump(n: usize, step: f64, last: f64, jump: f64) -> Vec<f64> {
        let mut curve: Vec<f64> = (0..=n).map(|i| step * i as f64).collect();
        curve.push(last);
        curve.extend((0..5).map(|i| jump + 0.1 * i as f64));
        curve
    }

    #[test]
    fn keeps_everything_when_nothing_fights() {
        let curve: Vec<f64> = (0..30).map(|i| 1e-6 * i as f64).collect();
        assert_eq!(cutoff(&curve, 0.01, usize::MAX).keep, 29);
        assert_eq!(cutoff(&curve, 0.01, 12).keep, 12);
    }

    #[test]
    fn under_noise_the_step_into_the_jump_is_not_kept() {
        // Every step costs about 0.01 (noise); step 21 costs 0.05 and step 22 jumps.
        let curve = steps_then_jump(20, 0.01, 0.25, 0.6);
        let c = cutoff(&curve, 0.01, usize::MAX);
        assert_eq!(c.keep, 20, "{c:?}");
        assert_eq!(cutoff(&curve, 0.01, 15).keep, 15);
    }

    #[test]
    fn a_step_within_the_noise_distortion_is_never_an_outlier() {
        // Steps of 0.001, then one of 0.005 (five times the typical step, but below the
        // 0.01 the noise explains), then the jump: the 0.005 step is kept.
        let curve = steps_then_jump(10, 0.001, 0.015, 0.4);
        let c = cutoff(&curve, 0.01, usize::MAX);
        assert_eq!(c.keep, 11, "{c:?}");
    }
}

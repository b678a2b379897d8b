//! The proportions search that opens a fit: the model stretched along each world axis
//! about the origin (every slot scaled by its axis weights, see
//! [`super::stages::axis_weights`]), one axis at a time over a ladder of factors, keeping a
//! factor when the loss drops. Gradients see only edges that are near their place in the
//! pictures; a stool four times shorter, or a table twice as tall, is out of their reach,
//! and its hidden parts (rungs inside the seat, a shelf behind the top) are lost once the
//! visible ones have moved past them. Stretching moves everything together first.
//!
//! Invariant: the search only returns points that `ok` accepts, and never one with a higher
//! loss than where it started.

/// Factors tried per axis in the first sweep; later sweeps take their square roots.
const LADDER: [f64; 6] = [0.5, 0.7, 0.85, 1.0 / 0.85, 1.0 / 0.7, 2.0];
/// Sweeps over the three axes.
const SWEEPS: usize = 3;

/// Slot values of `x` stretched by `factor` along `axis`.
pub fn stretched(x: &[f64], weights: &[[f64; 3]], axis: usize, factor: f64) -> Vec<f64> {
    x.iter()
        .zip(weights)
        .map(|(&v, w)| v * (1.0 + w[axis] * (factor - 1.0)))
        .collect()
}

/// Coordinate search over the three stretches from `x`.
pub fn search(
    x: Vec<f64>,
    weights: &[[f64; 3]],
    loss: &mut dyn FnMut(&[f64]) -> f64,
    ok: &dyn Fn(&[f64]) -> bool,
) -> Vec<f64> {
    let mut x = x;
    let mut best = loss(&x);
    for sweep in 0..SWEEPS {
        let power = 0.5f64.powi(sweep as i32);
        for axis in 0..3 {
            if weights.iter().all(|w| w[axis] == 0.0) {
                continue;
            }
            let ladder = LADDER.map(|f| stretched(&x, weights, axis, f.powf(power)));
            if let Some((l, cand)) = super::best_improvement(ladder, best, loss, ok) {
                best = l;
                x = cand;
            }
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_stretch_of_a_separable_loss() {
        // Slot 0 acts along x, slot 1 along z, slot 2 (an angle) along nothing.
        let weights = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0; 3]];
        let target = [30.0, 140.0, 7.0];
        let mut loss = |x: &[f64]| {
            x.iter()
                .zip(&target)
                .map(|(a, b)| (a / b).ln().powi(2))
                .sum::<f64>()
        };
        let x = search(vec![60.0, 70.0, 7.0], &weights, &mut loss, &|_| true);
        assert!((x[0] / 30.0 - 1.0).abs() < 0.1, "{x:?}");
        assert!((x[1] / 140.0 - 1.0).abs() < 0.1, "{x:?}");
        assert_eq!(x[2], 7.0);
    }

    #[test]
    fn never_leaves_what_ok_accepts() {
        let weights = [[1.0, 0.0, 0.0]];
        let mut loss = |x: &[f64]| (x[0] - 100.0).abs();
        let x = search(vec![10.0], &weights, &mut loss, &|x| x[0] <= 12.0);
        assert!(x[0] <= 12.0 && x[0] >= 10.0, "{x:?}");
    }
}

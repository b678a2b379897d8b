//! The best point a fit has stood on, judged by the loss its schedule ends with.
//!
//! A fit moves through stages whose losses differ (coarse, soft, hard-edged); each may end
//! at a point the final loss likes less than one before it, and a fit started at the
//! answer must not walk away from it. So the fit offers every point a stage or pass ends
//! at (its start first) and returns the one with the lowest final loss.
//!
//! Invariant: the kept point's loss never rises, and among equal losses the earliest point
//! stays (the start wins a tie).

/// The lowest-loss point offered so far.
#[derive(Debug, Clone, PartialEq)]
pub struct Best {
    pub x: Vec<f64>,
    pub loss: f64,
}

impl Best {
    /// Starts at `x` with loss `loss`.
    pub fn new(x: Vec<f64>, loss: f64) -> Best {
        Best { x, loss }
    }

    /// Keeps `x` when its loss is lower than the best so far (a NaN loss never is).
    /// Whether it was kept.
    pub fn offer(&mut self, x: &[f64], loss: f64) -> bool {
        if loss < self.loss {
            self.x = x.to_vec();
            self.loss = loss;
            true
        } else {
            false
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_strictly_lower_loss_replaces_the_point() {
        let mut b = Best::new(vec![0.0], 1.0);
        assert!(!b.offer(&[1.0], 1.0));
        assert!(!b.offer(&[2.0], f64::NAN));
        assert!(b.offer(&[3.0], 0.5));
        assert!(!b.offer(&[4.0], 0.7));
        assert_eq!(b, Best::new(vec![3.0], 0.5));
    }
}

//! The noise of training variations: Gaussian, σ a fraction of the model's size in WORLD
//! units, so a number's own σ is that divided by its leverage (how far one unit of it
//! moves a face). A dropped part's zero stays zero; held-out variations get none.

use super::rng::Rng;
use super::style::Number;

/// `values` (one per number) with noise of `sigma` world units added.
pub fn noisy(numbers: &[Number], values: &[f64], sigma: f64, rng: &mut Rng) -> Vec<f64> {
    numbers
        .iter()
        .zip(values)
        .map(|(n, &v)| {
            let dropped = n.drop.is_some() && v == 0.0;
            if dropped || n.leverage <= 0.0 || sigma <= 0.0 {
                v
            } else {
                v + sigma / n.leverage * rng.normal()
            }
        })
        .collect()
}

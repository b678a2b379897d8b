//! One stage's optimiser run as it goes: the space it moves in, the optimiser's state, its
//! position, and the trust region that bounds its steps in pixels.
//!
//! Invariant: with a positive reach, no step [`Descent::bound_reach`] passes moves any face
//! further than the reach times the softness it is given; a reach of 0 bounds nothing.

use super::Parametric;
use super::optimize::{OptState, Space};
use super::options::{REACH_GROW, REACH_SHRINK};

pub(super) struct Descent {
    pub space: Space,
    pub state: OptState,
    pub y: Vec<f64>,
    /// How far a step may carry a face, in edge softnesses ([`super::FitOptions::reach`]
    /// at a stage's start, 0 for no bound).
    pub reach: f64,
    /// The loss where the last step started (none at a round's start).
    pub last_loss: Option<f64>,
}

impl Descent {
    pub fn new(space: Space, state: OptState, reach: f64) -> Descent {
        let dim = space.dim();
        Descent {
            space,
            state,
            y: vec![0.0; dim],
            reach,
            last_loss: None,
        }
    }

    pub fn x(&self) -> Vec<f64> {
        self.space.x(&self.y)
    }

    /// A trust region on the step: the reach grows while steps lower the loss and halves
    /// when one raised it, so a stage starts with short steps (Adam's first moves every
    /// variable by the full rate), travels far where the loss keeps falling, and settles
    /// where steps start overshooting. `loss` is the loss where the last step landed.
    pub fn adapt_reach(&mut self, loss: f64) {
        if let Some(last) = self.last_loss {
            self.reach *= if loss > last {
                REACH_SHRINK
            } else {
                REACH_GROW
            };
        }
        self.last_loss = Some(loss);
    }

    /// Scales the step `delta` (the descent moves to `y − delta`) down so that no face of
    /// `problem` moves further than the reach times `softness` (world units).
    pub fn bound_reach(&self, problem: &Parametric, delta: &mut [f64], softness: f64) {
        if self.reach <= 0.0 {
            return;
        }
        let reach = self.reach * softness;
        let moved: Vec<f64> = self
            .y
            .iter()
            .zip(delta.iter())
            .map(|(a, d)| a - d)
            .collect();
        let far = problem.farthest_face_move(&self.x(), &self.space.x(&moved));
        if far > reach && far.is_finite() {
            delta.iter_mut().for_each(|d| *d *= reach / far);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::optimize::Optimizer;

    fn table() -> Parametric {
        Parametric::new(&crate::front::test_model(
            "cube([100, 60, 4]);\n\
             translate([0, 0, -70]) cube([4, 4, 70]);\n\
             translate([96, 56, -70]) cube([4, 4, 70]);\n",
        ))
    }

    /// A descent over every slot of `p`, with the reach `reach`.
    fn descent(p: &Parametric, reach: f64) -> Descent {
        let scales = vec![1.0; p.x0.len()];
        let state = OptState::new(Optimizer::adam(), p.x0.len());
        Descent::new(Space::slots(&p.x0, &scales), state, reach)
    }

    #[test]
    fn a_bounded_step_moves_no_face_further_than_its_reach() {
        let p = table();
        let mut d = descent(&p, 0.5);
        let mut delta: Vec<f64> = (0..p.x0.len()).map(|i| 3.0 - i as f64).collect();
        d.bound_reach(&p, &mut delta, 2.0);
        let after: Vec<f64> = d.y.iter().zip(&delta).map(|(a, b)| a - b).collect();
        let far = p.farthest_face_move(&d.x(), &d.space.x(&after));
        assert!((far - 1.0).abs() < 1e-9, "farthest face moved {far}");
        // Without a reach the step is left alone.
        d.reach = 0.0;
        let mut free = vec![5.0; p.x0.len()];
        d.bound_reach(&p, &mut free, 2.0);
        assert!(free.iter().all(|v| *v == 5.0));
    }

    #[test]
    fn the_reach_grows_while_the_loss_falls_and_halves_when_it_rises() {
        let mut d = descent(&table(), 0.5);
        d.adapt_reach(1.0);
        assert_eq!(
            d.reach, 0.5,
            "the first loss of a round has nothing to compare with"
        );
        d.adapt_reach(0.9);
        assert_eq!(d.reach, 0.5 * REACH_GROW);
        d.adapt_reach(0.95);
        assert_eq!(d.reach, 0.5 * REACH_GROW * REACH_SHRINK);
    }
}

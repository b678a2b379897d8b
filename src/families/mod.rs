//! Random model families: the measuring instrument of discovery (issue 20).
//!
//! A family is a parametric assembly of boxes, cylinders and cones in contact
//! (`assembly`), every number an affine form over `d` intent parameters (`intent`), written
//! in one of the styles people write (`style`). Its variations are draws from the intent
//! subspace, some dropping optional parts; training variations get Gaussian noise in world
//! units (`noise`), held-out ones stay exact. `score` runs the main job black-box on a
//! family and measures what a user relies on; `baseline` is the paper's plain method on
//! the same data; `rates` sums scores into the benchmark's table. Everything is
//! reproducible from a family's seed (`rng`).

pub mod assembly;
pub mod baseline;
pub mod intent;
pub mod lin;
pub mod noise;
pub mod part;
pub mod rates;
pub mod rng;
pub mod run;
pub mod score;
pub mod style;

use intent::{Params, draw};
use lin::Lin;
use part::{Part, bounds};
use rng::Rng;
use style::{Program, Style};

/// One variation of a family: intent values and the parts it does without.
#[derive(Debug, Clone)]
pub struct Draw {
    pub theta: Vec<f64>,
    pub dropped: Vec<usize>,
}

/// A generated family.
#[derive(Debug, Clone)]
pub struct Family {
    pub seed: u64,
    pub style: Style,
    pub parts: Vec<Part>,
    pub params: Params,
    /// Forms every variation keeps positive (sizes, clearances).
    pub positive: Vec<Lin>,
    /// The model's size (its bounding box's longest side) at the input.
    pub size: f64,
    pub training: Vec<Draw>,
    pub held_out: Vec<Draw>,
}

/// Held-out variations per family.
pub const HELD_OUT: usize = 2;

/// Further exact draws, beyond the input, training and held-out ones, that decide which
/// contacts the family's variations share (a contact four draws keep by chance is not one).
pub const CONTACT_DRAWS: usize = 12;

/// Probability that a variation drops each optional part.
pub const DROP_CHANCE: f64 = 0.3;

impl Family {
    /// The family of `seed` with `training` variations (`None` if no assembly of this seed
    /// allows variations, which the generator's retries make rare).
    pub fn generate(seed: u64, training: usize) -> Option<Family> {
        for attempt in 0..20 {
            let mut rng = Rng::fork(seed, attempt);
            let budget = rng.int(3, 8);
            let style = Style::ALL[rng.int(0, Style::ALL.len() - 1)];
            let asm = assembly::assemble(&mut rng, budget);
            let theta = asm.params.base();
            let d = asm.params.list.len();
            let n = asm.parts.len();
            if !(3..=8).contains(&d) || !(3..=60).contains(&n) {
                continue;
            }
            let b = bounds(&asm.parts, &theta);
            let size = b
                .iter()
                .map(|(lo, hi)| hi.eval(&theta) - lo.eval(&theta))
                .fold(0.0, f64::max);
            // Every size and clearance is at least a fifth of a percent of the model, at the
            // input and in every variation.
            let floor = 0.002 * size;
            if asm.positive.iter().any(|f| f.eval(&theta) <= floor) {
                continue;
            }
            let mut vrng = Rng::fork(seed, 1000 + attempt);
            let mut draws = Vec::new();
            for _ in 0..training + HELD_OUT {
                let Some(t) = draw(&asm.params, &asm.positive, floor, 1.0, &mut vrng) else {
                    break;
                };
                let dropped = (0..n)
                    .filter(|&p| asm.parts[p].optional && vrng.chance(DROP_CHANCE))
                    .collect();
                draws.push(Draw { theta: t, dropped });
            }
            if draws.len() < training + HELD_OUT {
                continue;
            }
            // Held-out draws first: the same whatever the number of training variations.
            let training_draws = draws.split_off(HELD_OUT);
            let held_out = draws;
            let draws = training_draws;
            return Some(Family {
                seed,
                style,
                parts: asm.parts,
                params: asm.params,
                positive: asm.positive,
                size,
                training: draws,
                held_out,
            });
        }
        None
    }

    /// `CONTACT_DRAWS` more exact draws from the intent subspace, no part dropped: with
    /// the others, the family's variations a contact must hold in to be the family's.
    pub fn contact_draws(&self) -> Vec<Draw> {
        let floor = 0.002 * self.size;
        let mut rng = Rng::fork(self.seed, 3000);
        (0..CONTACT_DRAWS)
            .filter_map(|_| draw(&self.params, &self.positive, floor, 1.0, &mut rng))
            .map(|theta| Draw {
                theta,
                dropped: Vec::new(),
            })
            .collect()
    }

    /// The intent dimension `d`.
    pub fn dimension(&self) -> usize {
        self.params.list.len()
    }

    pub fn names(&self) -> Vec<String> {
        self.params.list.iter().map(|p| p.name.clone()).collect()
    }

    /// The model written in `style`.
    pub fn program(&self, style: Style) -> Program {
        style::write(style, &self.parts, &self.names(), &self.params.base())
    }

    /// The input model's text in `style`.
    pub fn input_text(&self, style: Style) -> String {
        let p = self.program(style);
        p.render(&p.values(&self.params.base(), &[]))
    }
}

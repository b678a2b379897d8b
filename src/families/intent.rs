//! The family's intent: its parameters θ, the input's values of them, and variations drawn
//! from the intent subspace.
//!
//! A builder asks for a parameter of a kind (a length, a board's thickness, …). The pool
//! either shares an existing one of that kind — the parts' numbers are then equal by intent
//! — or makes a new one, up to the family's budget `d`. A new parameter's input value is a
//! round number and, now and then, on purpose the value of an existing parameter of its
//! kind: an ACCIDENTAL coincidence at the input that the variations break. A variation
//! moves every parameter by ±10–40% and keeps every form the family lists as positive
//! (sizes, clearances) positive.

use super::lin::Lin;
use super::rng::Rng;

/// What a parameter measures, which sets its range of input values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Length,
    Height,
    Thick,
    /// A thin board: about 2% of a model's size.
    Thin,
    Radius,
    Gap,
}

impl Kind {
    /// `(lowest, highest, step)` of input values.
    fn range(self) -> (f64, f64, f64) {
        match self {
            Kind::Length => (40.0, 200.0, 5.0),
            Kind::Height => (30.0, 150.0, 5.0),
            Kind::Thick => (3.0, 12.0, 1.0),
            Kind::Thin => (1.5, 4.0, 0.5),
            Kind::Radius => (6.0, 40.0, 1.0),
            Kind::Gap => (10.0, 60.0, 5.0),
        }
    }
}

/// One intent parameter.
#[derive(Debug, Clone)]
pub struct Param {
    pub name: String,
    pub kind: Kind,
    /// Its value in the input model.
    pub base: f64,
}

/// The pool of intent parameters a family's builders draw from.
#[derive(Debug, Clone)]
pub struct Params {
    pub list: Vec<Param>,
    /// The most parameters the family may have (its target `d`).
    pub budget: usize,
    /// Probability that a request shares an existing parameter of its kind.
    pub share: f64,
    /// Probability that a new parameter copies an existing value (an accidental coincidence).
    pub coincide: f64,
    /// Pairs of parameters whose input values are equal by accident.
    pub accidents: Vec<(usize, usize)>,
}

impl Params {
    pub fn new(budget: usize, rng: &mut Rng) -> Params {
        Params {
            list: Vec::new(),
            budget,
            share: rng.range(0.2, 0.6),
            coincide: rng.range(0.15, 0.45),
            accidents: Vec::new(),
        }
    }

    /// A parameter of `kind` named after `role`, shared or new (see the module doc).
    pub fn get(&mut self, rng: &mut Rng, kind: Kind, role: &str) -> Lin {
        let same: Vec<usize> = (0..self.list.len())
            .filter(|&i| self.list[i].kind == kind)
            .collect();
        let full = self.list.len() >= self.budget;
        if !self.list.is_empty() && (full || (!same.is_empty() && rng.chance(self.share))) {
            let from = if same.is_empty() {
                (0..self.list.len()).collect()
            } else {
                same
            };
            return Lin::param(from[rng.int(0, from.len() - 1)]);
        }
        let (lo, hi, step) = kind.range();
        let mut base = (rng.range(lo, hi) / step).round() * step;
        let mut twin = None;
        if !same.is_empty() && rng.chance(self.coincide) {
            let j = same[rng.int(0, same.len() - 1)];
            base = self.list[j].base;
            twin = Some(j);
        }
        let i = self.list.len();
        let mut name = role.to_string();
        if self.list.iter().any(|p| p.name == name) {
            name = format!("{role}_{i}");
        }
        self.list.push(Param { name, kind, base });
        if let Some(j) = twin {
            self.accidents.push((j, i));
        }
        Lin::param(i)
    }

    pub fn base(&self) -> Vec<f64> {
        self.list.iter().map(|p| p.base).collect()
    }
}

/// Drawn values are multiples of this (1/16 of a unit), as typed numbers are short. Every
/// form the generator writes has coefficients 2, 1, ½ or ¼ of them, so a relation that holds
/// in the family holds exactly in the written numbers (six decimals are enough) and in
/// OpenSCAD's arithmetic: a cut flush with a face stays flush, where a difference of one
/// in the sixth decimal is a lid sealing the hollow or a film over it in its pictures.
pub const VALUE_GRID: f64 = 1.0 / 16.0;

/// A draw of θ from the intent subspace: every parameter moved by ±10–40% (`scale` shrinks
/// the moves) to a multiple of [`VALUE_GRID`], keeping every form of `positive` above
/// `floor`; `None` when 60 draws fail.
pub fn draw(
    params: &Params,
    positive: &[Lin],
    floor: f64,
    scale: f64,
    rng: &mut Rng,
) -> Option<Vec<f64>> {
    for _ in 0..60 {
        let theta: Vec<f64> = params
            .list
            .iter()
            .map(|p| {
                let v = p.base * (1.0 + scale * rng.sign() * rng.range(0.1, 0.4));
                (v / VALUE_GRID).round() * VALUE_GRID
            })
            .collect();
        if positive.iter().all(|f| f.eval(&theta) > floor) {
            return Some(theta);
        }
    }
    None
}

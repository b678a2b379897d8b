//! The main job's report: every decision it made, as data and as JSON (`--report`).
//!
//! [`Report`] records what was kept and why (the method, each chosen relation with its
//! evidence, the noise model, the cutoff and the distortion curve), the free variables with
//! their ranges, how well each variation is reproduced and the part switches. It only
//! presents what the pipeline decided; nothing here computes analysis results.

use crate::analysis::cutoff::Cutoff;
use crate::analysis::noise::NoiseModel;
use crate::analysis::ranges::Range;
use serde::Serialize;

/// One free variable: its slider's name, the slot it is, its value and range.
#[derive(Debug, Clone, Serialize)]
pub struct FreeVariableReport {
    pub name: String,
    pub slot: String,
    pub description: String,
    pub value: f64,
    pub range: Range,
}

/// One variation: the parts it does without and how well the sliders reproduce it.
#[derive(Debug, Clone, Serialize)]
pub struct VariationReport {
    pub name: String,
    pub optional_parts: Vec<String>,
    /// IoU between the variation and its projection onto the kept constraints (measured
    /// only when the job was asked to measure it; `None` otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub projection_iou: Option<f64>,
}

/// One chosen relation and the evidence for it.
#[derive(Debug, Clone, Serialize)]
pub struct ChosenRelation {
    pub relation: String,
    /// The noise test's statistic (standard normal units): how far the variations are from
    /// keeping it, against their noise; at most the noise model's critical value is intent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    /// The probability that it is intent, given its class's learned share and its evidence.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub intent_probability: Option<f64>,
    /// Its largest residual over the variations (world units).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
}

impl ChosenRelation {
    /// Its evidence in words, as the page and the plot's tooltips give it. With exact
    /// variations the statistic measures nothing but the float tolerance, so only the
    /// largest residual (world units) is given; within the float tolerance every variation
    /// keeps it.
    pub fn evidence(&self, noise: Option<&NoiseModel>) -> String {
        let exact = noise.is_some_and(NoiseModel::exact);
        let floor = noise.map_or(0.0, |n| n.floor);
        let mut parts = Vec::new();
        match (self.z, self.residual) {
            (_, Some(r)) if exact && r <= floor => {
                parts.push("every variation keeps it exactly".to_string())
            }
            (_, Some(r)) if exact => {
                parts.push(format!("the variations leave it off by up to {r:.3}"))
            }
            (Some(z), _) if !exact => parts.push(format!("residuals {z:.1} noise deviations off")),
            (None, _) => parts.push("every variation keeps it exactly".to_string()),
            _ => {}
        }
        if let Some(p) = self.intent_probability.filter(|_| !exact) {
            parts.push(format!("P(intent) = {p:.2}"));
        }
        if let Some(r) = self.residual.filter(|_| !exact) {
            parts.push(format!("largest residual {r:.3}"));
        }
        parts.join("; ")
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct Report {
    pub model: String,
    pub parameter_count: usize,
    pub base_constraint_count: usize,
    /// How the kept constraints were chosen.
    pub method: String,
    /// Chosen constraints in order (all greedy steps, with variations).
    pub chosen: Vec<ChosenRelation>,
    /// The variations' estimated noise (world units) and the test it sets.
    pub noise: Option<NoiseModel>,
    pub kept_count: usize,
    pub cutoff: Option<Cutoff>,
    pub distortion_curve: Vec<f64>,
    pub dimension: usize,
    pub free_variables: Vec<FreeVariableReport>,
    pub variations: Vec<VariationReport>,
    pub toggles: Vec<Vec<String>>,
}

impl Report {
    /// The report as pretty JSON, ending in a newline.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default() + "\n"
    }

    /// How many chosen relations were kept: the cutoff's step, or all when there is none.
    pub fn keep_step(&self) -> usize {
        self.cutoff.as_ref().map_or(self.kept_count, |c| c.keep)
    }

    /// The one line the command prints when it is done, for the output `target`.
    pub fn summary_line(&self, target: &str) -> String {
        format!(
            "{target}: {} sliders drive {} numbers, keeping {} of {} relations ({}){}",
            self.dimension,
            self.parameter_count,
            self.kept_count,
            self.base_constraint_count,
            self.method,
            if self.toggles.is_empty() {
                String::new()
            } else {
                format!(", {} part switches", self.toggles.len())
            }
        )
    }
}

#[cfg(test)]
mod evidence_tests {
    use super::ChosenRelation;
    use crate::analysis::noise::{Evidence, NoiseModel};

    fn relation(z: f64, residual: f64) -> ChosenRelation {
        ChosenRelation {
            relation: "a equals b".into(),
            z: Some(z),
            intent_probability: Some(0.9),
            residual: Some(residual),
        }
    }

    #[test]
    fn exact_variations_give_residuals_in_world_units_not_deviations() {
        let exact = NoiseModel::estimate(&[Evidence::new(0.0, 3); 20], 1e-6, 1e6);
        let kept = relation(0.1, 0.0).evidence(Some(&exact));
        assert_eq!(kept, "every variation keeps it exactly");
        let broken = relation(4e6, 2.0).evidence(Some(&exact));
        assert_eq!(broken, "the variations leave it off by up to 2.000");
    }

    #[test]
    fn noisy_variations_give_the_statistic_and_the_odds() {
        let costs: Vec<Evidence> = (0..40)
            .map(|k| Evidence::new(0.5 + 0.05 * k as f64, 2))
            .collect();
        let noisy = NoiseModel::estimate(&costs, 1e-6, 1e6);
        assert!(!noisy.exact(), "{noisy:?}");
        let text = relation(1.25, 0.8).evidence(Some(&noisy));
        assert_eq!(
            text,
            "residuals 1.2 noise deviations off; P(intent) = 0.90; largest residual 0.800"
        );
    }
}

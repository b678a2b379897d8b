//! The benchmark's table: rates over families for one method and one condition.

use super::run::FamilyResult;
use super::score::{PRESET_HELD_SHARE, Score};

/// One row's rates (percentages of the families where they apply).
#[derive(Debug, Clone, Default)]
pub struct Rates {
    pub families: usize,
    pub reach: f64,
    pub coherence: f64,
    pub dim_within_d: f64,
    /// `None` when the paper's method was not run on these families.
    pub dim_within_paper: Option<f64>,
    pub no_false_toggle: f64,
    /// Over the families some training variation of which drops a part.
    pub optional_found: f64,
    pub optional_families: usize,
    pub presets_valid: f64,
    /// Families whose presets the box holds where they were projected
    /// ([`super::score::PRESET_HELD_SHARE`]).
    pub presets_held: f64,
    pub mean_sliders: f64,
    pub mean_d: f64,
    pub seconds: f64,
}

fn percent(n: usize, of: usize) -> f64 {
    if of == 0 {
        0.0
    } else {
        100.0 * n as f64 / of as f64
    }
}

/// Rates of the scores `pick` takes from each result.
pub fn rates(results: &[FamilyResult], pick: impl Fn(&FamilyResult) -> &Score) -> Rates {
    let n = results.len();
    let count = |f: &dyn Fn(&FamilyResult) -> bool| results.iter().filter(|r| f(r)).count();
    let with_optional: Vec<&FamilyResult> = results
        .iter()
        .filter(|r| pick(r).missed_optional.is_some())
        .collect();
    let found = with_optional
        .iter()
        .filter(|r| {
            pick(r)
                .missed_optional
                .as_ref()
                .is_some_and(|m| m.is_empty())
        })
        .count();
    let mean =
        |f: &dyn Fn(&FamilyResult) -> f64| results.iter().map(f).sum::<f64>() / n.max(1) as f64;
    Rates {
        families: n,
        reach: percent(count(&|r| pick(r).reached()), n),
        coherence: percent(count(&|r| pick(r).coherent()), n),
        dim_within_d: percent(count(&|r| pick(r).dimension <= pick(r).d + 1), n),
        // A score of a method that ran has an intent dimension (the generator's d ≥ 3).
        dim_within_paper: results
            .iter()
            .all(|r| r.paper.d > 0)
            .then(|| percent(count(&|r| pick(r).dimension <= r.paper.dimension + 1), n)),
        no_false_toggle: percent(count(&|r| pick(r).false_toggles.is_empty()), n),
        optional_found: percent(found, with_optional.len()),
        optional_families: with_optional.len(),
        presets_valid: percent(count(&|r| pick(r).bad_preset.is_none()), n),
        presets_held: percent(count(&|r| pick(r).preset_moved <= PRESET_HELD_SHARE), n),
        mean_sliders: mean(&|r| pick(r).dimension as f64),
        mean_d: mean(&|r| pick(r).d as f64),
        seconds: mean(&|r| pick(r).seconds),
    }
}

/// The table's header.
pub fn header() -> String {
    "| condition | method | families | reach | coherence | dim ≤ d+1 | dim ≤ paper+1 | no false toggle | optional found (n) | presets valid | presets held | sliders / d | s per family |\n\
     |---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
        .to_string()
}

/// One row of the table.
pub fn row(condition: &str, method: &str, r: &Rates) -> String {
    format!(
        "| {condition} | {method} | {} | {:.1}% | {:.1}% | {:.1}% | {} | {:.1}% | {:.1}% ({}) | {:.1}% | {:.1}% | {:.2} / {:.2} | {:.3} |\n",
        r.families,
        r.reach,
        r.coherence,
        r.dim_within_d,
        r.dim_within_paper
            .map_or_else(|| "–".to_string(), |p| format!("{p:.1}%")),
        r.no_false_toggle,
        r.optional_found,
        r.optional_families,
        r.presets_valid,
        r.presets_held,
        r.mean_sliders,
        r.mean_d,
        r.seconds
    )
}

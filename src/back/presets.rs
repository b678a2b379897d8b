//! OpenSCAD's parameter-set file (`<name>.json`): one set per variation.
//!
//! Each set gives every slider the variation's value, every blend weight 0 and every part
//! switch on unless the variation does without its parts, so choosing a set in the
//! Customizer shows the variation. Values are strings, as OpenSCAD writes them.

use super::emit::{EmitPlan, number};

/// The parameter-set file of `plan`: one set per blend (that is, per variation), named as
/// the blend.
pub fn presets_json(plan: &EmitPlan) -> String {
    let mut sets = serde_json::Map::new();
    for (j, blend) in plan.blends.iter().enumerate() {
        let mut set = serde_json::Map::new();
        for (i, s) in plan.sliders.iter().enumerate() {
            set.insert(s.name.clone(), number(blend.values[i]).into());
        }
        for b in &plan.blends {
            set.insert(b.name.clone(), "0".into());
        }
        for s in &plan.switches {
            let on = if s.toggle.off_in.contains(&j) {
                "false"
            } else {
                "true"
            };
            set.insert(s.name.clone(), on.into());
        }
        sets.insert(blend.name.clone(), serde_json::Value::Object(set));
    }
    let doc = serde_json::json!({ "fileFormatVersion": "1", "parameterSets": sets });
    serde_json::to_string_pretty(&doc).unwrap_or_default() + "\n"
}

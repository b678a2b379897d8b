//! The generator of model families (`reparamc::families`) keeps its promises on fixed
//! seeds: every style's text loads, its parts are the generator's (and OpenSCAD's), the
//! variations are the same program with other numbers whose geometry is the family's
//! intent forms exactly before noise, held-out variations are exact; and the main job's
//! rates on those seeds are printed (the thresholds come when discovery meets them).

mod common;

use common::{compare_parts, csg_parts, openscad_csg, our_part, tempfile};
use rayon::prelude::*;
use reparamc::families::rates::{header, rates, row};
use reparamc::families::run::{Case, Setup, evaluate_family};
use reparamc::families::style::Style;
use std::path::PathBuf;

const SEEDS: std::ops::Range<u64> = 0..20;

const MAIN: Setup = Setup {
    noise: 0.01,
    training: 3,
};

#[test]
fn every_style_loads_and_its_variations_are_the_intent_exactly() {
    let failures: Vec<String> = SEEDS
        .into_par_iter()
        .flat_map_iter(|seed| Style::ALL.into_iter().map(move |s| (seed, s)))
        .filter_map(|(seed, style)| {
            let case = match Case::load(seed, MAIN, Some(style)) {
                Ok(c) => c,
                Err(e) => return Some(format!("seed {seed} {}: {e}", style.name())),
            };
            let f = &case.family;
            let at = |x: &[f64], t: &[f64], dropped: &[usize]| case.differs(x, t, dropped);
            let mut why = at(&case.model.slot_values(), &f.params.base(), &[]);
            for (v, d) in case.training_exact.iter().zip(&f.training) {
                why = why.or_else(|| at(&v.values, &d.theta, &d.dropped));
            }
            for (v, d) in case.held_out.iter().zip(&f.held_out) {
                why = why.or_else(|| at(&v.values, &d.theta, &d.dropped));
            }
            // The noisy training variations are not the exact ones.
            let moved = case
                .training
                .iter()
                .zip(&case.training_exact)
                .all(|(n, e)| n.values != e.values);
            if !moved {
                why = why.or(Some("noise left a training variation exact".into()));
            }
            why.map(|w| format!("seed {seed} {}: {w}", style.name()))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn families_are_in_the_promised_ranges_and_reproducible() {
    for seed in SEEDS {
        let f = reparamc::families::Family::generate(seed, 3).expect("a family");
        let g = reparamc::families::Family::generate(seed, 3).expect("a family");
        assert!(
            (3..=8).contains(&f.dimension()),
            "seed {seed}: d {}",
            f.dimension()
        );
        assert!(
            (3..=60).contains(&f.parts.len()),
            "seed {seed}: {} parts",
            f.parts.len()
        );
        assert_eq!(f.input_text(f.style), g.input_text(g.style), "seed {seed}");
        assert_eq!(f.training.len(), 3);
        // Held-out draws do not depend on the number of training variations.
        let five = reparamc::families::Family::generate(seed, 5).expect("a family");
        assert_eq!(five.held_out[0].theta, f.held_out[0].theta, "seed {seed}");
    }
}

#[test]
fn openscad_reads_the_parts_the_generator_wrote() {
    let failures: Vec<String> = (0..4u64)
        .into_par_iter()
        .flat_map_iter(|seed| [Style::Csg, Style::Loops, Style::Modules].map(move |s| (seed, s)))
        .filter_map(|(seed, style)| {
            let case = Case::load(seed, MAIN, Some(style)).expect("the family loads");
            let text = case.family.input_text(style);
            let path = tempfile(&PathBuf::from(format!("family{seed}.scad")), "scad");
            std::fs::write(&path, &text).unwrap();
            let theirs = csg_parts(&openscad_csg(&path));
            std::fs::remove_file(&path).ok();
            let ours: Vec<_> = case.model.parts.iter().map(our_part).collect();
            let errs = compare_parts(&ours, &theirs);
            (!errs.is_empty()).then(|| format!("seed {seed} {}: {}", style.name(), errs.join("; ")))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn rates_of_the_main_job_on_the_fixed_seeds() {
    let results: Vec<_> = SEEDS
        .into_par_iter()
        .map(|seed| {
            let start = std::time::Instant::now();
            let r = evaluate_family(seed, MAIN, false);
            eprintln!("seed {seed} done in {:.1}s", start.elapsed().as_secs_f64());
            r
        })
        .collect();
    let failed: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
    assert!(failed.is_empty(), "families that did not run: {failed:?}");
    let ok: Vec<_> = results.into_iter().flatten().collect();
    for r in &ok {
        let s = &r.ours;
        assert!(
            (0.0..=1.0 + 1e-9).contains(&s.worst_iou),
            "seed {}: IoU {}",
            r.seed,
            s.worst_iou
        );
        eprintln!(
            "seed {:>2} {:<9} parts {:>2} d {} | dim {:>2} iou {:.3} broken {:>3} ({:?}) false toggles {:?} preset {:?} {:.2}s",
            r.seed,
            r.style.name(),
            r.parts,
            r.ours.d,
            r.ours.dimension,
            r.ours.worst_iou,
            r.ours.broken_settings,
            r.ours.first_break,
            r.ours.false_toggles,
            r.ours.bad_preset,
            r.ours.seconds,
        );
    }
    eprint!("{}", header());
    eprint!(
        "{}",
        row("1% noise, 3 training", "reparamc", &rates(&ok, |r| &r.ours))
    );
    // Where every literal is a number of its own (flat and `.csg` styles), the typed
    // variations' noise is the noise model's exactly, and its estimate must find it (on
    // 153 of 153 such families of seeds 200..600 it is within a factor of two).
    let off: Vec<String> = ok
        .iter()
        .filter(|r| matches!(r.style, Style::Flat | Style::Csg))
        .filter_map(|r| {
            let ratio = r.ours.sigma.unwrap_or(0.0) / r.sigma;
            (!(0.5..=2.0).contains(&ratio)).then(|| {
                format!(
                    "seed {}: noise estimated {:?}, added {}",
                    r.seed, r.ours.sigma, r.sigma
                )
            })
        })
        .collect();
    assert!(off.is_empty(), "{}", off.join("\n"));
    // Sliders never part what every variation keeps together, nor make a size negative
    // (issue 20's coherence; these seeds reach it since presets keep the contacts: 95%
    // before: seed 4 parted two of its parts at 158 of 200 settings).
    let broken: Vec<String> = ok
        .iter()
        .filter(|r| r.ours.broken_settings > 0)
        .map(|r| {
            format!(
                "seed {}: {} of 200 settings ({:?})",
                r.seed, r.ours.broken_settings, r.ours.first_break
            )
        })
        .collect();
    assert!(broken.is_empty(), "{}", broken.join("\n"));
}

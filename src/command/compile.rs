//! The main job: a model and its variations in, a re-parameterized model out.
//!
//! [`compile`] is the `reparamc` command's entry point (files in, texts and a report out);
//! [`reparameterize`] is the pipeline on a model already loaded, stage by stage: candidates
//! → optional parts → discovery and cutoff (or, without variations, the structural prior)
//! → Gauss–Jordan solve with anchors → projected variations → names, ranges and the emitted
//! file with its presets. Each stage lives where its kind does (`analysis`, `back`); this
//! file only composes them, and every decision is recorded in the [`Report`].

use super::pictures::{Progress, pictures};
use crate::analysis::anchors::{Anchors, Keeping, project_variations_keeping};
use crate::analysis::candidates::{Candidate, Candidates};
use crate::analysis::classes::sigmoid;
use crate::analysis::contact_vars::{fix_pinned, keep_contacts};
use crate::analysis::contacts::{ContactSide, NoiseGaps, Slack, common_contacts};
use crate::analysis::cutoff::{Cutoff, change_points};
use crate::analysis::details::pin_details;
use crate::analysis::discover::{Sample, Similarity};
use crate::analysis::find_candidates_for;
use crate::analysis::intent::{Selection, select};
use crate::analysis::noise::NoiseModel;
use crate::analysis::optional::{held_where_skipped, optional_parts, toggles};
use crate::analysis::precision::Precision;
use crate::analysis::prior::structural_prior;
use crate::analysis::project::Faces;
use crate::analysis::ranges::{Range, close_contacts, ranges, size_floors};
use crate::analysis::reparam::{Solution, solve};
use crate::analysis::similarity::VolumeSimilarity;
use crate::analysis::size_basis::exchange_for_sizes;
use crate::back::diff::unified_diff;
use crate::back::emit::{EmitPlan, emit};
use crate::back::gallery::Gallery;
use crate::back::plan::{PlanInputs, plan};
pub use crate::back::plot::PlotFormat;
use crate::back::presets::presets_json;
use crate::back::report::{ChosenRelation, FreeVariableReport, Report, VariationReport};
use crate::front::diag::{DResult, Diagnostic};
use crate::front::load::{Loaded, load_file_calling};
use crate::front::source::SourceMap;
use crate::front::{eval::evaluate, with_large_stack};
use crate::ir::{Affine, Model};
use crate::tolerance::{MIN_DISPLAY_SIZE, Tolerance};
use crate::variation::{Variation, load_variation_calling};
use std::path::PathBuf;

/// How the pipeline chooses and presents (what [`reparameterize`] can be told).
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Without variations, keep every base constraint (the paper's symbolic baseline).
    pub all_constraints: bool,
    /// The file name the parameter sets will have (for the comment that points to them).
    pub presets_name: Option<String>,
    /// Measure the IoUs only the report and the plot show: the distortion curve (1 − mean
    /// IoU after each relation taken) and each variation's IoU with its projection. The
    /// decisions do not depend on them, and on models of many curved parts they take
    /// nearly all of the time (exact volumes of solids that differ everywhere).
    pub measure: bool,
}

/// What the `compile` command is asked: the files, and what to make besides the model.
#[derive(Debug, Clone, Default)]
pub struct CompileOptions {
    /// The OpenSCAD model to re-parameterize.
    pub model: PathBuf,
    /// Its variant files: the same program with other numbers.
    pub variations: Vec<PathBuf>,
    /// A module call to draw at the end of the model (and of each variant): `chair()`.
    pub call: Option<String>,
    pub options: Options,
    /// Draw the distortion curve with the cutoff marked, in this format.
    pub plot: Option<PlotFormat>,
    /// Draw the presets gallery (PNG).
    pub gallery: bool,
    /// Write the report as an HTML page.
    pub page: bool,
    /// Told each stage as it starts, and each of discovery's steps.
    pub progress: Progress,
    /// Make a unified diff from the model to the output, which will be written as this
    /// name (the diff's `+++` header; the `---` header is the model's path).
    pub diff_to: Option<String>,
}

/// The results of the main job.
#[derive(Debug, Clone)]
pub struct Compiled {
    pub scad: String,
    /// OpenSCAD parameter sets (`<name>.json`), when there are variations.
    pub presets: Option<String>,
    pub report: Report,
    /// Every candidate of the model, and the kept ones, for tests and tools.
    pub candidates: Candidates,
    pub kept: Vec<Candidate>,
    pub solution: Solution,
    /// What the output file says (sliders, blends, switches).
    pub plan: EmitPlan,
    /// Slot values of each variation projected onto the kept constraints and anchors.
    pub projected: Vec<Vec<f64>>,
}

/// What the `compile` command makes: the job's results, the pictures and texts asked for,
/// and the warnings loading gave.
#[derive(Debug)]
pub struct CompileOutput {
    pub compiled: Compiled,
    /// The distortion plot (PNG or SVG), when asked.
    pub plot: Option<Vec<u8>>,
    /// The presets gallery, when asked.
    pub gallery: Option<Gallery>,
    /// The report as an HTML page, when asked.
    pub page: Option<String>,
    /// The unified diff from the model to the output, when asked.
    pub diff: Option<String>,
    pub warnings: Vec<Diagnostic>,
}

/// The `compile` command: loads the model and its variations into `sources`, runs the main
/// job and makes what `options` asks for. Prints nothing and writes no file; the error is
/// the diagnostic that stopped it.
pub fn compile(options: &CompileOptions, sources: &mut SourceMap) -> DResult<CompileOutput> {
    with_large_stack(|| {
        let call = options.call.as_deref();
        let extra = [options.plot.is_some(), options.gallery, options.page];
        let stages = 2 + options.variations.len() + extra.iter().filter(|&&b| b).count();
        let mut stage = 0;
        let mut tell = |what: &str| {
            stage += 1;
            options.progress.tell(stage, stages, what);
        };
        tell("reading the model");
        let loaded = load_file_calling(sources, &options.model, call)?;
        let evaluated = evaluate(sources, &loaded)?;
        let mut variations = Vec::new();
        for v in &options.variations {
            tell(&format!("reading {}", v.display()));
            let model = &evaluated.model;
            variations.push(load_variation_calling(
                sources,
                loaded.main,
                model,
                v,
                call,
            )?);
        }
        let mut job = options.options.clone();
        job.measure |= options.plot.is_some() || options.page;
        tell("choosing the relations to keep");
        let model = &evaluated.model;
        let mut step = |done, total| options.progress.step(done, total);
        let compiled =
            reparameterize_telling(sources, &loaded, model, &variations, &job, &mut step);
        let pictures = pictures(options, model, &compiled, &mut tell)?;
        let diff = options.diff_to.as_ref().map(|to| {
            let from = options.model.display().to_string();
            unified_diff(sources.text(loaded.main), &compiled.scad, &from, to)
        });
        Ok(CompileOutput {
            compiled,
            plot: pictures.plot,
            gallery: pictures.gallery,
            page: pictures.page,
            diff,
            warnings: evaluated.warnings,
        })
    })
}

/// Runs the main job on a loaded model.
pub fn reparameterize(
    sources: &SourceMap,
    loaded: &Loaded,
    model: &Model,
    variations: &[Variation],
    options: &Options,
) -> Compiled {
    reparameterize_telling(sources, loaded, model, variations, options, &mut |_, _| {})
}

/// [`reparameterize`], telling `step` how far discovery is: candidates decided, of how many
/// (`analysis::intent::select`).
pub fn reparameterize_telling(
    sources: &SourceMap,
    loaded: &Loaded,
    model: &Model,
    variations: &[Variation],
    options: &Options,
    step: &mut dyn FnMut(usize, usize),
) -> Compiled {
    // Candidates: every relation that holds on the input (and on the variations).
    let raw: Vec<Vec<f64>> = variations.iter().map(|v| v.values.clone()).collect();
    let candidates = find_candidates_for(model, &raw);
    // Optional parts: what each variation does without, kept at the input's shape.
    let sim = VolumeSimilarity::new(model);
    let faces = Faces::of(model);
    // A variation drops a part by a zero, so the absent test is exact (a part merely
    // covered by others keeps its numbers; a fitted variation's deviations weigh its faces
    // in discovery, not this test).
    let optional = optional_parts(model, &raw, &sim);
    let values = held_where_skipped(model, &raw, &optional);
    let samples = samples_of(model, &faces, (&values, &optional), variations);
    // Discovery (or the prior): which relations to keep.
    let choice = if variations.is_empty() {
        by_prior(model, &candidates, options.all_constraints)
    } else {
        let curve = options.measure.then_some(&sim);
        by_discovery(model, &candidates, &faces, curve, &samples, step)
    };
    // Reparameterization: the kept rows solved with anchors; the variations projected.
    let kept: Vec<Candidate> = choice
        .kept
        .iter()
        .map(|&i| candidates.list[i].clone())
        .collect();
    let rows: Vec<Affine> = kept.iter().flat_map(|c| c.rows.iter().cloned()).collect();
    let anchors = Anchors::of(model);
    // Without variations, the author's named variables say which numbers are the design's.
    let rows = if variations.is_empty() && !options.all_constraints {
        pin_details(model, &anchors, rows)
    } else {
        rows
    };
    let mut solution = solve(model, &anchors, &rows);
    let tolerance = Tolerance::for_size(model.size());
    let eps = tolerance.epsilon;
    // A contact is evidence where the variation shows both parts.
    let unshown: Vec<Vec<usize>> = samples.iter().map(Sample::unshown).collect();
    let contacts = match &choice.noise {
        Some(noise) => {
            let ceiling = crate::tolerance::noise_ceiling(model.size());
            let mut gaps = NoiseGaps::new(&faces, &samples, noise, ceiling);
            common_contacts(model, &raw, &unshown, &mut gaps)
        }
        None => common_contacts(model, &raw, &unshown, &mut Slack(eps)),
    };
    let floors = size_floors(model);
    let keeping = Keeping {
        contacts: &contacts,
        floors: &floors,
        tolerance: eps,
    };
    let projected =
        project_variations_keeping(&anchors, &faces, &rows, &values, &optional, &keeping);
    // Emit: sliders, blends and switches, the file and its presets.
    let (input_free, variation_free, slider_ranges) = slider_box(
        model,
        &mut solution,
        &projected,
        &contacts,
        choice.noise.as_ref(),
    );
    let plan = plan(&PlanInputs {
        sources,
        loaded,
        model,
        solution: &solution,
        variations,
        input_free: &input_free,
        variation_free: &variation_free,
        ranges: &slider_ranges,
        toggles: &toggles(model.parts.len(), &optional),
        kept: kept.len(),
        presets_name: options.presets_name.as_deref(),
    });
    let scad = emit(sources.text(loaded.main), &plan);
    let presets = (!variations.is_empty()).then(|| presets_json(&plan));
    let outcome = Outcome {
        sources,
        loaded,
        model,
        variations,
        candidates: &candidates,
        sim: options.measure.then_some(&sim),
        anchors: &anchors,
        optional: &optional,
        solution: &solution,
        projected: &projected,
        plan: &plan,
        kept: kept.len(),
    };
    let report = report(&outcome, choice);
    Compiled {
        scad,
        presets,
        report,
        candidates,
        kept,
        solution,
        plan,
        projected,
    }
}

/// Each variation as discovery sees it: its values with the numbers of parts it does without
/// held at the input's, those parts, and for a variation fitted to pictures how well they
/// show each face.
fn samples_of(
    model: &Model,
    faces: &Faces,
    (values, optional): (&[Vec<f64>], &[Vec<usize>]),
    variations: &[Variation],
) -> Vec<Sample> {
    values
        .iter()
        .zip(optional)
        .zip(variations)
        .map(|((v, o), var)| Sample {
            values: v.clone(),
            optional: o.clone(),
            precision: var
                .uncertainty
                .as_ref()
                .map(|u| Precision::of(faces, u, model.size())),
        })
        .collect()
}

/// The sliders' box: the free variables at the input and at each projected variation (the
/// presets), and their ranges. Contact sides the box cannot keep become free variables of
/// their own where that parts fewer of them, variables the contacts pin are fixed, free
/// slots are exchanged for dependent ones where that lets the box hold the presets with
/// every size positive (`size_basis`), and the box is closed on the contacts, a preset giving up at most what the noise explains
/// (nothing for exact variations). Presets are then clamped into the ranges: every size
/// positive and every kept contact closed there too.
fn slider_box(
    model: &Model,
    solution: &mut Solution,
    projected: &[Vec<f64>],
    contacts: &[ContactSide],
    noise: Option<&NoiseModel>,
) -> (Vec<f64>, Vec<Vec<f64>>, Vec<Range>) {
    let eps = Tolerance::for_size(model.size()).epsilon;
    let mut box_of = |sol: &Solution| {
        let (input_free, variation_free) = free_values(model, sol, projected);
        let r = ranges(model, sol, &input_free, &variation_free, contacts, eps);
        (input_free, variation_free, r)
    };
    let boxed = keep_contacts(model, solution, contacts, eps, &mut box_of);
    let mut boxed = fix_pinned(solution, eps, boxed, &mut box_of);
    if exchange_for_sizes(model, solution, projected) {
        boxed = fix_pinned(solution, eps, box_of(solution), &mut box_of);
    }
    let (input_free, mut variation_free, mut slider_ranges) = boxed;
    let allowance = noise.map_or(0.0, |n| n.critical_z * n.sigma);
    close_contacts(
        solution,
        (&input_free, &variation_free),
        allowance,
        contacts,
        eps,
        &mut slider_ranges,
    );
    for v in &mut variation_free {
        for (x, r) in v.iter_mut().zip(&slider_ranges) {
            *x = x.clamp(r.min, r.max);
        }
    }
    (input_free, variation_free, slider_ranges)
}

/// Which candidates are kept, and how they were chosen (for the report).
struct Choice {
    /// Indices into the candidates, in the order chosen.
    kept: Vec<usize>,
    method: String,
    chosen: Vec<ChosenRelation>,
    cutoff: Option<Cutoff>,
    curve: Vec<f64>,
    noise: Option<NoiseModel>,
}

/// Without variations: the structural prior, or every base constraint.
fn by_prior(model: &Model, candidates: &Candidates, all_constraints: bool) -> Choice {
    let (kept, method) = if all_constraints {
        (
            (0..candidates.list.len()).collect::<Vec<usize>>(),
            "all base constraints (the paper's symbolic baseline)",
        )
    } else {
        (
            structural_prior(model, candidates),
            "structural prior: contacts, coaxiality and equal sizes of repeated parts",
        )
    };
    let chosen = kept
        .iter()
        .map(|&i| ChosenRelation {
            relation: candidates.describe(&candidates.list[i]),
            z: None,
            intent_probability: None,
            residual: None,
        })
        .collect();
    Choice {
        kept,
        method: method.to_string(),
        chosen,
        cutoff: None,
        curve: Vec::new(),
        noise: None,
    }
}

/// With variations: the noise model's sequential test (`analysis::intent`), cut at the
/// first relation the noise does not explain.
fn by_discovery(
    model: &Model,
    candidates: &Candidates,
    faces: &Faces,
    sim: Option<&VolumeSimilarity>,
    samples: &[Sample],
    step: &mut dyn FnMut(usize, usize),
) -> Choice {
    let sel = select(model, faces, candidates, samples, sim, step);
    let chosen = sel
        .order
        .iter()
        .zip(sel.z.iter().zip(&sel.log_odds))
        .map(|(&i, (&z, &odds))| ChosenRelation {
            relation: candidates.describe(&candidates.list[i]),
            z: z.is_finite().then_some(z),
            intent_probability: Some(sigmoid(odds)),
            residual: Some(sel.residual[i]),
        })
        .collect();
    Choice {
        kept: sel.order[..sel.accepted].to_vec(),
        method: "noise-model test of relations against the variations".to_string(),
        chosen,
        cutoff: Some(test_cutoff(candidates, &sel)),
        curve: sel.curve,
        noise: Some(sel.noise),
    }
}

/// The cutoff the test made, with the paper's change points on the same curve beside it.
fn test_cutoff(candidates: &Candidates, sel: &Selection) -> Cutoff {
    let (paper, published) = change_points(&sel.curve);
    Cutoff {
        keep: sel.accepted,
        paper,
        published,
        reason: sel.cutoff_reason(&|c| candidates.describe(&candidates.list[c])),
    }
}

/// The free variables' values at the input and in each projected variation. Projections
/// are exact to round-off; they are shown to a millionth of the model's size.
fn free_values(
    model: &Model,
    solution: &Solution,
    projected: &[Vec<f64>],
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let free_at = |x: &[f64]| solution.free_values(x);
    let input = free_at(&model.slot_values());
    let quantum = 10f64.powf((model.size().max(MIN_DISPLAY_SIZE)).log10().floor() - 6.0);
    let tidy = |v: f64| (v / quantum).round() * quantum;
    let variations = projected
        .iter()
        .map(|p| free_at(p).into_iter().map(tidy).collect())
        .collect();
    (input, variations)
}

/// What the pipeline decided, for the report.
struct Outcome<'a> {
    sources: &'a SourceMap,
    loaded: &'a Loaded,
    model: &'a Model,
    variations: &'a [Variation],
    candidates: &'a Candidates,
    /// The similarity to measure the projections' IoUs with (`None`: not measured).
    sim: Option<&'a VolumeSimilarity<'a>>,
    /// Where the model is pinned: the projections stand where the input stands.
    anchors: &'a Anchors,
    optional: &'a [Vec<usize>],
    solution: &'a Solution,
    projected: &'a [Vec<f64>],
    plan: &'a EmitPlan,
    kept: usize,
}

/// The report of the job: its choice and what came of it.
fn report(o: &Outcome, choice: Choice) -> Report {
    let model = o.model;
    let free_variables = o
        .plan
        .sliders
        .iter()
        .zip(&o.solution.free)
        .enumerate()
        .map(|(i, (s, &slot))| FreeVariableReport {
            name: s.name.clone(),
            slot: match o.solution.contact(i) {
                Some(c) => format!(
                    "overlap of {} and {} along {} (in place of {})",
                    model.parts[c.parts[0]].name,
                    model.parts[c.parts[1]].name,
                    ["x", "y", "z"][c.axis as usize],
                    model.slots[slot as usize].name
                ),
                None => model.slots[slot as usize].name.clone(),
            },
            description: s.description.clone(),
            value: s.value,
            range: s.range,
        })
        .collect();
    let variations = o
        .variations
        .iter()
        .zip(o.projected)
        .zip(o.optional)
        .map(|((v, p), skip)| VariationReport {
            name: v.name.clone(),
            optional_parts: skip.iter().map(|&i| model.parts[i].name.clone()).collect(),
            // Both in the input's frame: the projection was moved there.
            projection_iou: o
                .sim
                .map(|sim| sim.similarity(p, &o.anchors.moved_to_input(&v.values), skip)),
        })
        .collect();
    let part_names = |parts: &[usize]| parts.iter().map(|&p| model.parts[p].name.clone()).collect();
    Report {
        model: o.sources.path(o.loaded.main).display().to_string(),
        parameter_count: model.slots.len(),
        base_constraint_count: o.candidates.total(),
        method: choice.method,
        chosen: choice.chosen,
        noise: choice.noise,
        kept_count: o.kept,
        cutoff: choice.cutoff,
        distortion_curve: choice.curve,
        dimension: o.solution.free.len(),
        free_variables,
        variations,
        toggles: o
            .plan
            .switches
            .iter()
            .map(|s| part_names(&s.toggle.parts))
            .collect(),
    }
}

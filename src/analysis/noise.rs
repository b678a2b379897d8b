//! The noise model: how far off the variations may be and a relation still be intent.
//!
//! Variations are noisy (fitted to images, nudged by hand). The model lives where the
//! variation was made, in world units: a typed variation's every number is off from what the
//! intended design has by independent Gaussian noise that moves the face it moves most by
//! one standard deviation `σ` (a number sizing twenty boards is one noisy number, so their
//! faces move together: `project::Faces::number_metric`); a variation fitted to pictures,
//! which see faces, has every face it shows displaced by independent noise of `σ`, weighed
//! by how well its pictures show it (`project::Faces::face_metric`, `precision`).
//! Projecting a variation onto a relation in its metric moves it by the least displacement
//! that makes the relation hold; if the relation is intent, that squared displacement over
//! `σ²` is χ²-distributed with one degree of freedom per independent row the noise moves
//! (`intent::noisy_rows`: rows the program holds identically, or over numbers no variation
//! moved, carry none) and per variation that has both parts.
//!
//! One decision rule follows, the same for every kind of object: a relation is intent when
//! that is more likely than not, weighing the likelihood of its residuals under the noise
//! against their likelihood when the variations changed it by any amount (a change of
//! unknown scale: [`NoiseModel::likelihood_ratio`]), with the prior odds of its class
//! (`classes`). A χ² statistic in normal units ([`NoiseModel::z`]) is reported beside it.
//!
//! `σ` is estimated from the variations themselves, over the relations they move, when
//! they can tell it (`intent::informative`: some relation's residuals cancel most of its
//! numbers' changes in every variation; where none does, `σ` stays at the floor and
//! [`NoiseModel::told`] says so): the pooled variance of the relations whose statistic
//! chance reaches in all but [`FALSE_REJECTION`] of intent ones (a one-sided test at
//! [`INTENT_Z`]), iterated from a start until that set stops changing. That iteration has
//! several fixed points (a cluster of relations seen once with small residuals, another
//! seen in every variation with larger ones); it is run from a ladder of starts, and the
//! fixed point kept is the one under which the relations' evidence is likeliest, intent
//! and broken mixed in the share that fits best ([`NoiseModel::estimate_told`]): the same
//! two hypotheses the decision weighs.
//! It never falls below `floor` (the model's float tolerance), so with exact variations
//! exactly the relations some variation breaks are rejected, nor rises above a ceiling (a
//! share of the model's size, `tolerance::NOISE_MAX_SHARE`): variations of one design are
//! not that far apart, and broken relations alone must not pass for the noise. A fixed
//! point at the ceiling has grown through broken relations and is kept only when every
//! start ends there.

use serde::Serialize;

/// The share of intent relations the test rejects by chance (each costs a slider).
pub const FALSE_REJECTION: f64 = crate::tolerance::NOISE_FALSE_REJECTION;

/// The standard normal quantile of `1 − FALSE_REJECTION`: a statistic above it rejects.
pub const INTENT_Z: f64 = 3.090_232_306;

/// The standard normal quantile of 1/4.
const LOWER_QUARTILE_Z: f64 = -0.674_489_750;

/// Points of the log-uniform grid of broken residual scales.
const SCALE_GRID: usize = 64;

/// At most this many re-estimations of `σ` (the accepted set settles in a few).
const MAX_ROUNDS: usize = 50;

/// What the variations say about one relation: the squared face displacement projecting
/// onto it costs (world units², summed over variations) and its degrees of freedom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evidence {
    pub cost: f64,
    pub dof: usize,
    /// What the cost would be had the relation's terms changed from the input as they did
    /// but not cancelled at all (each row's residual the root sum of squares of its terms'
    /// changes): the largest cost a change of design could give it. A relation whose
    /// numbers the variations barely move cannot be seen broken, whatever it is
    /// (`classes` keeps such relations apart). `f64::INFINITY` when unknown.
    pub change: f64,
}

impl Evidence {
    /// Evidence whose terms' change is unknown.
    pub fn new(cost: f64, dof: usize) -> Evidence {
        Evidence {
            cost,
            dof,
            change: f64::INFINITY,
        }
    }
}

/// The estimated noise and the test it sets.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct NoiseModel {
    /// One standard deviation of a face's displacement (world units).
    pub sigma: f64,
    /// The floor `sigma` never falls below (the model's float tolerance).
    pub floor: f64,
    /// How many relations the estimate was pooled over.
    pub pooled: usize,
    /// The statistic above which a relation is rejected.
    pub critical_z: f64,
    /// Whether any relation could tell the noise (see `intent::informative`). When none
    /// does, `sigma` sits at the floor as for exact variations: every relation the
    /// variations move counts as changed.
    pub told: bool,
}

/// The log-likelihood ratio of a relation's evidence between intent and broken for one
/// noise model and model size: each variance's `(ln 2πv, 2v)`, the noise's alone and the
/// log-uniform grid of broken scales (see [`NoiseModel::likelihood_ratio`]).
#[derive(Debug, Clone)]
pub struct LikelihoodRatio {
    intent: (f64, f64),
    broken: [(f64, f64); SCALE_GRID],
}

impl LikelihoodRatio {
    /// The two hypotheses for noise `sigma`: intent (the residual is the noise) and broken
    /// (the noise plus a change of scale log-uniform from `lo` to `hi`).
    fn between(sigma: f64, lo: f64, hi: f64) -> LikelihoodRatio {
        let noise = sigma * sigma;
        let (lo, hi) = (lo.ln(), hi.ln());
        let term = |v: f64| ((2.0 * std::f64::consts::PI * v).ln(), 2.0 * v);
        let mut broken = [(0.0, 0.0); SCALE_GRID];
        for (j, b) in broken.iter_mut().enumerate() {
            let u = lo + (hi - lo) * (j as f64 + 0.5) / SCALE_GRID as f64;
            *b = term(noise + (2.0 * u).exp());
        }
        LikelihoodRatio {
            intent: term(noise),
            broken,
        }
    }

    /// The log-likelihoods of `e` under intent and under broken.
    fn log_likelihoods(&self, e: Evidence) -> (f64, f64) {
        let k = e.dof as f64;
        let log_normal = |(ln_two_pi_v, two_v): (f64, f64)| -0.5 * k * ln_two_pi_v - e.cost / two_v;
        let mut broken = [0.0; SCALE_GRID];
        for (l, &v) in broken.iter_mut().zip(&self.broken) {
            *l = log_normal(v);
        }
        let top = broken.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mean = broken.iter().map(|l| (l - top).exp()).sum::<f64>() / SCALE_GRID as f64;
        (log_normal(self.intent), top + mean.ln())
    }

    /// The log-likelihood ratio of `e`: positive when the noise explains it better, 0 when
    /// nothing is seen.
    pub fn of(&self, e: Evidence) -> f64 {
        if e.dof == 0 {
            return 0.0;
        }
        let (intent, broken) = self.log_likelihoods(e);
        intent - broken
    }
}

/// The Wilson–Hilferty normal form of a χ² statistic `x` with `dof` degrees of freedom:
/// approximately standard normal under the null hypothesis (exact enough for a test at
/// three standard deviations from one degree of freedom on).
pub fn chi2_z(x: f64, dof: usize) -> f64 {
    if dof == 0 {
        return f64::NEG_INFINITY;
    }
    let k = dof as f64;
    let v = 2.0 / (9.0 * k);
    ((x.max(0.0) / k).cbrt() - (1.0 - v)) / v.sqrt()
}

/// A length in world units for people: three decimals, or three significant figures in
/// scientific notation when that would show no figure at all.
pub fn figures(v: f64) -> String {
    if v == 0.0 || v.abs() >= 0.01 {
        format!("{v:.3}")
    } else {
        format!("{v:.2e}")
    }
}

impl NoiseModel {
    /// Whether the variations are exact: no noise was seen, and `sigma` sits at the floor
    /// (the model's float tolerance), where a relation is kept only if it holds.
    pub fn exact(&self) -> bool {
        self.sigma <= self.floor
    }

    /// The noise in words: `σ = 0.120 world units`, or that the variations are exact.
    pub fn describe(&self) -> String {
        if !self.told {
            "no relation tells the variations' noise from a change of design".to_string()
        } else if self.exact() {
            "exact variations, no noise".to_string()
        } else {
            format!("σ = {} world units", figures(self.sigma))
        }
    }

    /// The test statistic of `e` under this noise.
    pub fn z(&self, e: Evidence) -> f64 {
        chi2_z(e.cost / (self.sigma * self.sigma), e.dof)
    }

    /// Whether the noise explains `e` (the relation is intent).
    pub fn explains(&self, e: Evidence) -> bool {
        self.z(e) <= self.critical_z
    }

    /// The log-likelihood ratio of a relation's evidence between "intent" (its residuals are
    /// the noise) and "broken" (the variations changed it by a residual of unknown scale `s`, anywhere from
    /// the noise to the model's `size` with no scale preferred — log-uniform — plus the
    /// noise). Positive when the noise explains `e` better; 0 when nothing is seen.
    ///
    /// Bounding `s` by what the relation's own terms' changes could make of it
    /// (`Evidence::change`) instead of the model's size was measured and left out: on
    /// seeds 200..400 it gained 1.5 points of reach and lost 12 of dimension within d + 1
    /// (README, "what the relation kinds can say"), since most intent relations among small
    /// numbers then fall to their class's prior.
    /// Whether the variations could test a relation at all decides its class instead
    /// (`classes`).
    ///
    /// The ratio is made for a model of size `size`, its grid of broken scales worked out
    /// once for the many relations it will weigh ([`LikelihoodRatio::of`]).
    pub fn likelihood_ratio(&self, size: f64) -> LikelihoodRatio {
        LikelihoodRatio::between(self.sigma, self.sigma, size.max(self.sigma))
    }

    /// The noise of the variations whose relations' evidence is `evidence`, never below
    /// `floor` nor above `ceiling` (see the module doc).
    pub fn estimate(evidence: &[Evidence], floor: f64, ceiling: f64) -> NoiseModel {
        NoiseModel::estimate_told(evidence, &[], floor, ceiling)
    }

    /// [`NoiseModel::estimate`], where `tellers` is the evidence of the relations that
    /// look like intent under noise (they cancel most of their numbers' changes in every
    /// variation: `intent::informative`).
    ///
    /// The re-pooling only grows an estimate that starts too low, up to the end of the
    /// cluster it starts in. So it starts from the lower quartile, from the tellers'
    /// pooled variance and from [`LADDER`] quantiles of the relations' variance per degree
    /// of freedom, and keeps the fixed point under which the evidence is likeliest as a
    /// mixture of intent and broken relations (`mixture_log_likelihood`). Fixed points at
    /// the ceiling, which no noise of variations of one design reaches
    /// (`tolerance::NOISE_MAX_SHARE`), are left out unless all are there: re-pooled
    /// through broken relations spread over every scale, exact variations would read as
    /// noise of 5% of the model.
    pub fn estimate_told(
        evidence: &[Evidence],
        tellers: &[Evidence],
        floor: f64,
        ceiling: f64,
    ) -> NoiseModel {
        let floor = floor.max(f64::MIN_POSITIVE);
        let ceiling = ceiling.max(floor);
        let seen: Vec<Evidence> = evidence.iter().copied().filter(|e| e.dof > 0).collect();
        let model = NoiseModel {
            sigma: floor,
            floor,
            pooled: 0,
            critical_z: INTENT_Z,
            told: !seen.is_empty(),
        };
        if seen.is_empty() {
            return model;
        }
        // Start from the lower quartile's variance per degree of freedom over the lower
        // quartile of χ²ₖ/k: low when many relations are broken, and the re-pooling below
        // only grows an estimate that is too low (a truncated χ² averages more than its
        // share of the truncation point), up to where the intent relations' cluster ends.
        let per_dof: Vec<f64> = seen.iter().map(|e| e.cost / e.dof as f64).collect();
        let dofs: Vec<f64> = seen.iter().map(|e| e.dof as f64).collect();
        let v = 2.0 / (9.0 * median(&dofs));
        let quartile_of_chi2 = (1.0 - v + LOWER_QUARTILE_Z * v.sqrt()).max(0.0).powi(3);
        let start = quantile(&per_dof, 0.25) / quartile_of_chi2.max(f64::MIN_POSITIVE);
        let (cost, dof) = tellers
            .iter()
            .fold((0.0, 0usize), |(c, d), e| (c + e.cost, d + e.dof));
        let mut starts = vec![start];
        if dof > 0 {
            starts.push(cost / dof as f64);
        }
        starts.extend((0..=LADDER).map(|i| quantile(&per_dof, i as f64 / LADDER as f64)));
        let mut points: Vec<NoiseModel> = Vec::new();
        for s in starts {
            let m = model.repooled(&seen, s, ceiling);
            if !points.iter().any(|p| p.sigma == m.sigma) {
                points.push(m);
            }
        }
        // A fixed point at the ceiling has pooled broken relations (no noise of one
        // design reaches it): it is chosen only when every start ends there.
        if points.iter().any(|p| p.sigma < ceiling) {
            points.retain(|p| p.sigma < ceiling);
        }
        let size = ceiling / crate::tolerance::NOISE_MAX_SHARE;
        points
            .into_iter()
            .map(|m| (mixture_log_likelihood(&seen, m.sigma, floor, size), m))
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .map_or(model, |(_, m)| m)
    }

    /// The estimate re-pooled from variance `start`: `σ` the pooled variance of the
    /// relations it explains, until that set stops changing.
    fn repooled(mut self, seen: &[Evidence], start: f64, ceiling: f64) -> NoiseModel {
        let mut variance = start;
        let mut accepted: Vec<bool> = Vec::new();
        for _ in 0..MAX_ROUNDS {
            self.sigma = variance.sqrt().clamp(self.floor, ceiling);
            let now: Vec<bool> = seen.iter().map(|&e| self.explains(e)).collect();
            if now == accepted {
                break;
            }
            let (cost, dof) = seen
                .iter()
                .zip(&now)
                .filter(|(_, a)| **a)
                .fold((0.0, 0usize), |(c, d), (e, _)| (c + e.cost, d + e.dof));
            self.pooled = now.iter().filter(|a| **a).count();
            accepted = now;
            if dof == 0 {
                break;
            }
            variance = cost / dof as f64;
        }
        self
    }
}

/// Starts of the re-pooling besides the lower quartile: this many quantiles of the
/// relations' variance per degree of freedom.
const LADDER: usize = 16;

/// The log-likelihood of the relations' evidence at noise `sigma` under the mixture of
/// intent (the residual is the noise) and broken (the noise plus a change of scale
/// log-uniform from the `floor` to the model's `size`, whatever `sigma`), with the intent
/// share fitted by expectation–maximisation.
fn mixture_log_likelihood(seen: &[Evidence], sigma: f64, floor: f64, size: f64) -> f64 {
    const MARGIN: f64 = crate::tolerance::NOISE_MIXTURE_SHARE_MARGIN;
    let ratio = LikelihoodRatio::between(sigma, floor, size.max(floor));
    let pairs: Vec<(f64, f64)> = seen.iter().map(|&e| ratio.log_likelihoods(e)).collect();
    let mut share: f64 = 0.5;
    let mut total = f64::NEG_INFINITY;
    for _ in 0..MAX_ROUNDS {
        let (mut sum, mut intent) = (0.0, 0.0);
        for &(n, b) in &pairs {
            let (a, c) = (share.ln() + n, (1.0 - share).ln() + b);
            let top = a.max(c);
            let l = top + ((a - top).exp() + (c - top).exp()).ln();
            sum += l;
            intent += (a - l).exp();
        }
        total = sum;
        share = (intent / pairs.len() as f64).clamp(MARGIN, 1.0 - MARGIN);
    }
    total
}

/// The median of `values` (0 for none).
pub fn median(values: &[f64]) -> f64 {
    quantile(values, 0.5)
}

/// The `q` quantile of `values`, interpolating between neighbours (0 for none).
pub fn quantile(values: &[f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let at = q.clamp(0.0, 1.0) * (v.len() - 1) as f64;
    let (i, t) = (at.floor() as usize, at.fract());
    let next = v[(i + 1).min(v.len() - 1)];
    v[i] + t * (next - v[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(median(&[]), 0.0);
    }

    /// A deterministic stream of standard normal draws (xorshift and Box–Muller).
    fn normals(seed: u64) -> impl Iterator<Item = f64> {
        let mut x = seed.max(1);
        let mut uniform = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            ((x >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        std::iter::repeat_with(move || {
            let (u, v) = (uniform(), uniform());
            (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
        })
    }

    /// `n` relations of `dof` degrees of freedom whose residuals are noise of `sigma`.
    fn intent(n: usize, dof: usize, sigma: f64, seed: u64) -> Vec<Evidence> {
        let mut z = normals(seed);
        (0..n)
            .map(|_| {
                let cost = (0..dof)
                    .map(|_| (sigma * z.next().unwrap_or(0.0)).powi(2))
                    .sum();
                Evidence::new(cost, dof)
            })
            .collect()
    }

    #[test]
    fn exact_variations_are_described_as_exact_and_noise_by_its_sigma() {
        // Exact variations: every residual is zero, the estimate sits at the floor.
        let exact = NoiseModel::estimate(&[Evidence::new(0.0, 3); 20], 1e-6, 1e6);
        assert!(exact.exact(), "{exact:?}");
        assert_eq!(exact.describe(), "exact variations, no noise");
        assert!(!exact.describe().contains("σ"));
        let noisy = NoiseModel::estimate(&intent(300, 3, 0.7, 9), 1e-6, 1e6);
        assert!(!noisy.exact(), "{noisy:?}");
        let text = noisy.describe();
        assert!(
            text.starts_with("σ = 0.") && text.ends_with(" world units"),
            "{text}"
        );
        // Noise too small for three decimals keeps its figures.
        let small = NoiseModel::estimate(&intent(300, 3, 4e-4, 9), 1e-6, 1e6);
        assert!(!small.exact(), "{small:?}");
        assert!(small.describe().contains("e-4"), "{}", small.describe());
        assert_eq!(figures(0.1234), "0.123");
        assert_eq!(figures(0.0), "0.000");
        assert_eq!(figures(0.000_456), "4.56e-4");
    }

    #[test]
    fn the_wilson_hilferty_form_puts_the_chi2_quantiles_where_they_are() {
        // χ²₁ at 10.83 and χ²₃ at 16.27 are the 0.999 quantiles.
        assert!((chi2_z(10.83, 1) - INTENT_Z).abs() < 0.1);
        assert!((chi2_z(16.27, 3) - INTENT_Z).abs() < 0.05);
        assert!(chi2_z(0.0, 3) < -2.0);
    }

    #[test]
    fn the_estimate_recovers_the_noise_among_broken_relations() {
        // 300 intent relations with σ = 0.7, and 120 the variations change by 5 to 50.
        let mut e = intent(300, 3, 0.7, 9);
        e.extend((0..120).map(|i| Evidence::new((5.0 + 0.4 * i as f64).powi(2), 3)));
        let m = NoiseModel::estimate(&e, 1e-6, 1e6);
        assert!((m.sigma - 0.7).abs() < 0.07, "{m:?}");
        let rejected_intent = e[..300].iter().filter(|&&x| !m.explains(x)).count();
        assert!(
            rejected_intent <= 3,
            "{rejected_intent} intent relations rejected"
        );
        assert!(e[300..].iter().all(|&x| !m.explains(x)));
    }

    /// Exact variations of a model whose relations are mostly broken, at every scale: a
    /// few relations cancel exactly (the tellers), the rest spread evenly from half a world
    /// unit to a hundred. Re-pooled from the lower quartile alone, the estimate grows
    /// through the broken ones to the ceiling; the fixed point the tellers start and the
    /// likelihood keep it at the floor.
    #[test]
    fn exact_variations_are_not_read_as_noise_of_the_ceiling() {
        let tellers = vec![Evidence::new(0.0, 1); 4];
        let mut e = tellers.clone();
        e.extend((1..=200).map(|i| Evidence::new((0.5 * i as f64).powi(2), 1)));
        let (floor, ceiling) = (1e-6, 20.0);
        let model = NoiseModel {
            sigma: floor,
            floor,
            pooled: 0,
            critical_z: INTENT_Z,
            told: true,
        };
        let quartile = quantile(&e.iter().map(|x| x.cost).collect::<Vec<_>>(), 0.25);
        assert_eq!(model.repooled(&e, quartile, ceiling).sigma, ceiling);
        let told = NoiseModel::estimate_told(&e, &tellers, floor, ceiling);
        assert!(told.exact(), "{told:?}");
    }

    /// Two fixed points: 60 relations of noise 0.05 seen once each (parts most variations
    /// do without), and 60 of noise 0.6 seen in five variations. Re-pooled from below,
    /// the estimate stops in the small cluster and rejects most of the large one; the
    /// likelihood of the whole evidence prefers the noise that explains both.
    #[test]
    fn the_estimate_is_the_likeliest_of_its_fixed_points() {
        let mut e = intent(60, 1, 0.05, 3);
        e.extend(intent(60, 5, 0.6, 5));
        e.extend((0..80).map(|i| Evidence::new(5.0 * (3.0 + 0.5 * i as f64).powi(2), 5)));
        let m = NoiseModel::estimate(&e, 1e-6, 1e3);
        assert!((m.sigma - 0.6).abs() < 0.15, "{m:?}");
    }

    #[test]
    fn the_estimate_holds_when_most_relations_are_broken() {
        // 60 intent relations with σ = 0.3 among 200 the variations change by 2 to 60.
        let mut e = intent(60, 5, 0.3, 4);
        e.extend((0..200).map(|i| Evidence::new(5.0 * (2.0 + 0.29 * i as f64).powi(2), 5)));
        let m = NoiseModel::estimate(&e, 1e-6, 1e6);
        assert!((m.sigma - 0.3).abs() < 0.05, "{m:?}");
        assert!(e[60..].iter().all(|&x| !m.explains(x)));
    }

    #[test]
    fn the_likelihood_ratio_favours_intent_for_noise_and_breakage_for_large_residuals() {
        let m = NoiseModel {
            sigma: 1.0,
            floor: 1e-6,
            pooled: 0,
            critical_z: INTENT_Z,
            told: true,
        };
        let ratio = m.likelihood_ratio(100.0);
        let at = |rms: f64| ratio.of(Evidence::new(3.0 * rms * rms, 3));
        assert!(at(1.0) > 2.0, "{}", at(1.0));
        assert!(at(4.0) < -2.0, "{}", at(4.0));
        assert!(at(0.5) > at(1.0) && at(1.0) > at(2.0));
        assert_eq!(ratio.of(Evidence::new(0.0, 0)), 0.0);
    }

    #[test]
    fn exact_variations_reject_every_broken_relation() {
        let mut e = vec![Evidence::new(0.0, 2); 50];
        e.push(Evidence::new(1e-8, 2));
        let m = NoiseModel::estimate(&e, 1e-6, 1e6);
        assert_eq!(m.sigma, 1e-6);
        assert!(!m.explains(e[50]));
        assert!(m.explains(e[0]));
    }
}

//! How well a variation's numbers are known: the uncertainty a fit reports beside the
//! variation it writes, and the sidecar file that carries it.
//!
//! A fit to pictures determines some numbers to a fraction of a pixel (a large face seen in
//! every view) and others not at all (a part no camera sees). It reports that as the Fisher
//! information of the numbers: a symmetric matrix `F` over the numbers the pictures can
//! show, whose inverse is their covariance. A combination of numbers `f` (a face of a part,
//! say) has variance `fᵀ F⁺ f` when `f` lies in `F`'s range, and is not determined at all
//! (infinite variance) when it has a component in `F`'s null space: a hidden part's
//! numbers, or two numbers of which only the sum shows.
//!
//! The sidecar of `v.scad` is `v.json`: `{"format": FORMAT, "numbers": [...],
//! "information": [[...]]}`, each number with its slot index, value and standard deviation
//! (`null` when undetermined), the matrix over the listed numbers in their order. A JSON file
//! beside a variant without that format tag is someone else's (OpenSCAD's parameter sets
//! share the name) and is ignored. Invariant: a loaded [`Uncertainty`] describes the
//! variation it was loaded with (same value at every listed slot) or loading fails.

use crate::tolerance::{INFORMATION_NULL_SHARE, INFORMATION_RANGE_SHARE, SIDECAR_VALUE_MATCH};
use nalgebra::{DMatrix, DVector, SymmetricEigen};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The format tag of a sidecar.
pub const FORMAT: &str = "reparamc-fit-uncertainty/1";

/// One number a fit reports on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NumberUncertainty {
    /// The model's slot index.
    pub slot: usize,
    /// The slot's name (`line:column` of the literal in the model's main file, or an
    /// author's name), for people reading the file.
    pub name: String,
    /// The fitted value.
    pub value: f64,
    /// One standard deviation, in the number's own units; `None` when the pictures do not
    /// determine it.
    pub std: Option<f64>,
}

/// The sidecar's contents.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sidecar {
    pub format: String,
    pub numbers: Vec<NumberUncertainty>,
    /// Fisher information over `numbers`, in their order (1 / units²).
    pub information: Vec<Vec<f64>>,
}

/// A variation's uncertainty, ready for questions about combinations of its numbers.
#[derive(Debug, Clone)]
pub struct Uncertainty {
    pub sidecar: Sidecar,
    /// Position of each model slot in `sidecar.numbers` (`None`: not reported, so not
    /// determined by the pictures).
    index: Vec<Option<usize>>,
    /// `F⁺` over the listed numbers.
    pseudo_inverse: DMatrix<f64>,
    /// An orthonormal basis of `F`'s null space, one column per direction.
    null: DMatrix<f64>,
}

impl Uncertainty {
    /// The uncertainty of a model of `slots` slots from an information matrix over `listed`
    /// of them (`values` their fitted values, `names` theirs).
    pub fn new(
        slots: usize,
        listed: &[(usize, String, f64)],
        information: DMatrix<f64>,
    ) -> Uncertainty {
        let (pseudo_inverse, null) = decompose(&information);
        let mut index = vec![None; slots];
        for (k, (s, _, _)) in listed.iter().enumerate() {
            if *s < slots {
                index[*s] = Some(k);
            }
        }
        let mut u = Uncertainty {
            sidecar: Sidecar {
                format: FORMAT.to_string(),
                numbers: Vec::new(),
                information: (0..information.nrows())
                    .map(|i| information.row(i).iter().copied().collect())
                    .collect(),
            },
            index,
            pseudo_inverse,
            null,
        };
        u.sidecar.numbers = listed
            .iter()
            .map(|(s, name, value)| NumberUncertainty {
                slot: *s,
                name: name.clone(),
                value: *value,
                std: u.std(*s),
            })
            .collect();
        u
    }

    /// From a parsed sidecar, for a model of `slots` slots.
    fn from_sidecar(slots: usize, sidecar: Sidecar) -> Result<Uncertainty, String> {
        let n = sidecar.numbers.len();
        if sidecar.information.len() != n || sidecar.information.iter().any(|r| r.len() != n) {
            return Err(format!(
                "its information matrix is not {n} × {n}, one row and column per number"
            ));
        }
        if let Some(bad) = sidecar.numbers.iter().find(|u| u.slot >= slots) {
            return Err(format!(
                "it names number {} but the model has {slots}",
                bad.slot
            ));
        }
        let m = DMatrix::from_fn(n, n, |i, j| sidecar.information[i][j]);
        if m.iter().any(|v| !v.is_finite()) {
            return Err("its information matrix holds a value that is not a number".into());
        }
        let listed: Vec<(usize, String, f64)> = sidecar
            .numbers
            .iter()
            .map(|u| (u.slot, u.name.clone(), u.value))
            .collect();
        Ok(Uncertainty::new(slots, &listed, m))
    }

    /// The variance of the combination `Σ c·x[slot]` of the numbers: `∞` when the pictures
    /// do not determine it.
    pub fn variance(&self, terms: &[(usize, f64)]) -> f64 {
        let n = self.pseudo_inverse.nrows();
        let mut f = DVector::zeros(n);
        for &(s, c) in terms {
            match self.index.get(s).copied().flatten() {
                Some(k) => f[k] += c,
                None if c != 0.0 => return f64::INFINITY,
                None => {}
            }
        }
        let norm = f.norm();
        if norm == 0.0 {
            return 0.0;
        }
        if self.null.ncols() > 0
            && (self.null.transpose() * &f).norm() > INFORMATION_RANGE_SHARE * norm
        {
            return f64::INFINITY;
        }
        f.dot(&(&self.pseudo_inverse * &f))
    }

    /// The standard deviation of one slot (`None`: undetermined).
    pub fn std(&self, slot: usize) -> Option<f64> {
        let v = self.variance(&[(slot, 1.0)]);
        v.is_finite().then(|| v.max(0.0).sqrt())
    }

    /// The sidecar as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.sidecar).unwrap_or_default() + "\n"
    }
}

/// `F⁺` and an orthonormal basis of `F`'s null space, from its eigen-decomposition.
fn decompose(f: &DMatrix<f64>) -> (DMatrix<f64>, DMatrix<f64>) {
    let n = f.nrows();
    if n == 0 {
        return (DMatrix::zeros(0, 0), DMatrix::zeros(0, 0));
    }
    let sym = (f + f.transpose()) * 0.5;
    let eig = SymmetricEigen::new(sym);
    let top = eig.eigenvalues.iter().fold(0.0f64, |m, v| m.max(*v));
    let cut = INFORMATION_NULL_SHARE * top;
    let mut pinv = DMatrix::zeros(n, n);
    let mut null_cols = Vec::new();
    for (k, &l) in eig.eigenvalues.iter().enumerate() {
        let e = eig.eigenvectors.column(k);
        if l > cut && l > 0.0 {
            pinv += e * e.transpose() / l;
        } else {
            null_cols.push(e.into_owned());
        }
    }
    let null = if null_cols.is_empty() {
        DMatrix::zeros(n, 0)
    } else {
        DMatrix::from_columns(&null_cols)
    };
    (pinv, null)
}

/// The sidecar path of a variant file: `v.scad` → `v.json`.
pub fn sidecar_path(variant: &Path) -> PathBuf {
    variant.with_extension("json")
}

/// The uncertainty beside `variant`, if it has a sidecar of ours: `Ok(None)` when there is
/// none (or the JSON there is not ours); an error (for the user) when ours does not parse
/// or does not describe `values`, the variant's numbers.
pub fn load_sidecar(variant: &Path, values: &[f64]) -> Result<Option<Uncertainty>, String> {
    let path = sidecar_path(variant);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(None);
    };
    let tagged = serde_json::from_str::<serde_json::Value>(&text)
        .ok()
        .and_then(|v| v.get("format").and_then(|f| f.as_str()).map(str::to_string));
    if tagged.as_deref() != Some(FORMAT) {
        return Ok(None);
    }
    let sidecar: Sidecar = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let u = Uncertainty::from_sidecar(values.len(), sidecar)?;
    for n in &u.sidecar.numbers {
        let here = values[n.slot];
        let tol = SIDECAR_VALUE_MATCH * here.abs().max(n.value.abs()).max(1.0);
        if (here - n.value).abs() > tol {
            return Err(format!(
                "it says number {} (`{}`) is {}, but the variant has {here}: the variant \
                 was changed after the fit (delete the sidecar or fit again)",
                n.slot, n.name, n.value
            ));
        }
    }
    Ok(Some(u))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn listed(n: usize) -> Vec<(usize, String, f64)> {
        (0..n).map(|s| (s, format!("n{s}"), s as f64)).collect()
    }

    #[test]
    fn a_combination_outside_the_information_is_undetermined() {
        // Numbers 0 and 1 only show through their sum; number 2 is seen alone; number 3 is
        // not listed (a hidden part's).
        let f = DMatrix::from_row_slice(3, 3, &[4.0, 4.0, 0.0, 4.0, 4.0, 0.0, 0.0, 0.0, 1.0]);
        let u = Uncertainty::new(4, &listed(3), f);
        assert!(u.variance(&[(0, 1.0)]).is_infinite());
        assert!(u.variance(&[(3, 1.0)]).is_infinite());
        // The sum x0 + x1 has information 8 along (1, 1)/√2: var((1,1)) = 2 / 8.
        assert!((u.variance(&[(0, 1.0), (1, 1.0)]) - 0.25).abs() < 1e-9);
        assert_eq!(u.std(2), Some(1.0));
        assert_eq!(u.std(0), None);
        assert_eq!(u.sidecar.numbers[2].std, Some(1.0));
        assert_eq!(u.sidecar.numbers[1].std, None);
    }

    #[test]
    fn the_sidecar_round_trips_and_must_describe_the_variant() {
        let dir = std::env::temp_dir().join(format!("reparamc-unc-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let variant = dir.join("v.scad");
        let f = DMatrix::from_row_slice(2, 2, &[2.0, 0.5, 0.5, 1.0]);
        let u = Uncertainty::new(3, &listed(2), f);
        std::fs::write(sidecar_path(&variant), u.to_json()).unwrap();
        let back = load_sidecar(&variant, &[0.0, 1.0, 7.0]).unwrap().unwrap();
        assert_eq!(back.sidecar, u.sidecar);
        assert!((back.variance(&[(1, 1.0)]) - u.variance(&[(1, 1.0)])).abs() < 1e-12);
        let stale = load_sidecar(&variant, &[0.0, 2.0, 7.0]).unwrap_err();
        assert!(stale.contains("changed after the fit"), "{stale}");
        // Someone else's JSON beside the variant is not ours.
        std::fs::write(sidecar_path(&variant), "{\"parameterSets\": {}}").unwrap();
        assert!(load_sidecar(&variant, &[0.0, 1.0, 7.0]).unwrap().is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

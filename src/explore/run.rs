//! The run folder (`--run runs/chair/`): `state.json` (the settings that fix the run, and
//! per prompt the rounds done and the current numbers), each round's guidance and render
//! images, and each prompt's variation as `<name>.scad`.
//!
//! Invariants: every file goes through [`write_atomic`], so an interrupt leaves the last
//! whole `state.json` and no partial file; a round's images are written before the state
//! that counts the round, so a resumed run redoes at most the round it was in. Numbers are
//! stored so they read back bit for bit (`serde_json`'s `float_roundtrip`).

use crate::output::write_atomic;
use crate::render::image::Rgb;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The version of `state.json` this build writes and reads.
pub const STATE_VERSION: u32 = 1;

/// What a run is: the settings that must match to resume it, and each prompt's progress.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct State {
    pub version: u32,
    /// The model's path, as given.
    pub model: String,
    pub object: String,
    pub seed: u64,
    /// Rounds each prompt runs to.
    pub rounds: usize,
    pub prompts: Vec<PromptState>,
}

/// One prompt's progress.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PromptState {
    pub prompt: String,
    /// Its file name stem (and preset name): `bar stool` → `bar_stool`.
    pub name: String,
    /// Rounds done.
    pub round: usize,
    /// The numbers after the last round done (the model's own before the first).
    pub x: Vec<f64>,
    /// The image loss after each round done.
    pub loss: Vec<f64>,
    /// The rounds of the schedule's last stage done so far, whose mean is the prompt's
    /// variation ([`PromptState::variation`]).
    #[serde(default)]
    pub tail: Tail,
}

/// The numbers after each round of the schedule's last stage, summed. Each round fits a
/// few steps towards pictures that disagree with each other in every detail (a sample
/// draws a leg a little longer, another leaves it out), so the rounds' ends scatter around
/// what the pictures agree on, and their mean is nearer to it than the last one is: the
/// iterate average of a stochastic descent. The early stages move in subspaces of their
/// own and are left out.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Tail {
    /// The round (from 0) the last stage starts at.
    pub from: usize,
    /// How many rounds `sum` holds.
    pub rounds: usize,
    pub sum: Vec<f64>,
}

impl PromptState {
    /// A prompt no round has run for, at the model's numbers `x`.
    pub fn new(prompt: String, name: String, x: Vec<f64>) -> PromptState {
        PromptState {
            prompt,
            name,
            round: 0,
            x,
            loss: Vec::new(),
            tail: Tail::default(),
        }
    }

    /// Counts the current numbers, those after round `round` (from 0), into the tail when
    /// the round is one of the last stage's, which starts at round `from`. A tail summed
    /// where the stage started elsewhere (a run resumed with other `--rounds`) starts again.
    pub fn tally(&mut self, round: usize, from: usize) {
        if round < from {
            return;
        }
        if self.tail.from != from || self.tail.sum.len() != self.x.len() {
            self.tail = Tail {
                from,
                rounds: 0,
                sum: vec![0.0; self.x.len()],
            };
        }
        for (a, v) in self.tail.sum.iter_mut().zip(&self.x) {
            *a += v;
        }
        self.tail.rounds += 1;
    }

    /// The prompt's variation: the mean of its tail's rounds, or the current numbers
    /// before the last stage has run a round.
    pub fn variation(&self) -> Vec<f64> {
        if self.tail.rounds == 0 || self.tail.sum.len() != self.x.len() {
            return self.x.clone();
        }
        let n = self.tail.rounds as f64;
        self.tail.sum.iter().map(|a| a / n).collect()
    }
}

impl State {
    /// Whether every prompt has run all its rounds.
    pub fn finished(&self) -> bool {
        self.prompts.iter().all(|p| p.round >= self.rounds)
    }
}

/// A prompt's name for files and presets: an identifier (`Bar stool!` → `bar_stool`).
pub fn name_of(prompt: &str) -> String {
    crate::analysis::names::sanitize(&prompt.to_lowercase())
}

/// Names for `prompts`, each distinct (a repeat gets `_2`, `_3`, …).
pub fn names_of(prompts: &[String]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for p in prompts {
        let base = name_of(p);
        let mut name = base.clone();
        let mut k = 2;
        while names.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        names.push(name);
    }
    names
}

/// A run folder.
#[derive(Debug, Clone, PartialEq)]
pub struct RunFolder {
    pub dir: PathBuf,
}

impl RunFolder {
    pub fn new(dir: &Path) -> RunFolder {
        RunFolder {
            dir: dir.to_path_buf(),
        }
    }

    pub fn state_path(&self) -> PathBuf {
        self.dir.join("state.json")
    }

    /// The variation file of prompt `name`.
    pub fn variation_path(&self, name: &str) -> PathBuf {
        self.dir.join(format!("{name}.scad"))
    }

    /// The folder of prompt `name`'s round images.
    pub fn rounds_dir(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// The image of round `round` (from 1), view `view`, of `kind` (`guide`, `render`).
    pub fn image_path(&self, name: &str, round: usize, view: usize, kind: &str) -> PathBuf {
        self.rounds_dir(name)
            .join(format!("round{round:04}_view{}_{kind}.png", view + 1))
    }

    /// Creates the folder and prompt `names`' image folders.
    pub fn create(&self, names: &[String]) -> Result<(), String> {
        for n in names {
            let d = self.rounds_dir(n);
            std::fs::create_dir_all(&d)
                .map_err(|e| format!("cannot create the folder `{}`: {e}", d.display()))?;
        }
        Ok(())
    }

    /// Reads `state.json`.
    pub fn load(&self) -> Result<State, String> {
        let p = self.state_path();
        let text = std::fs::read_to_string(&p)
            .map_err(|e| format!("cannot read `{}` to resume: {e}", p.display()))?;
        let state: State = serde_json::from_str(&text)
            .map_err(|e| format!("`{}` is not a run's state: {e}", p.display()))?;
        if state.version != STATE_VERSION {
            return Err(format!(
                "`{}` is of version {}; this build reads version {STATE_VERSION}",
                p.display(),
                state.version
            ));
        }
        Ok(state)
    }

    /// Writes `state.json` whole.
    pub fn save(&self, state: &State) -> Result<(), String> {
        let text = serde_json::to_string_pretty(state)
            .map_err(|e| format!("cannot write the run's state: {e}"))?;
        self.write(&self.state_path(), (text + "\n").as_bytes())
    }

    /// Writes a round's guidance and render images, view by view.
    pub fn save_round(
        &self,
        name: &str,
        round: usize,
        guides: &[Rgb],
        renders: &[Rgb],
    ) -> Result<(), String> {
        for (v, (g, r)) in guides.iter().zip(renders).enumerate() {
            self.write(&self.image_path(name, round, v, "guide"), &g.encode_png())?;
            self.write(&self.image_path(name, round, v, "render"), &r.encode_png())?;
        }
        Ok(())
    }

    /// Writes `bytes` to `path` whole or not at all.
    pub fn write(&self, path: &Path, bytes: &[u8]) -> Result<(), String> {
        write_atomic(path, bytes).map_err(|e| format!("cannot write `{}`: {e}", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_identifiers_and_distinct() {
        let prompts: Vec<String> = ["Bar stool", "bar-stool", "Bench!"]
            .map(String::from)
            .to_vec();
        assert_eq!(names_of(&prompts), ["bar_stool", "bar_stool_2", "bench"]);
    }

    #[test]
    fn state_reads_back_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("reparamc_run_{}", std::process::id()));
        let folder = RunFolder::new(&dir);
        folder.create(&["a".into()]).unwrap();
        let mut state = State {
            version: STATE_VERSION,
            model: "m.scad".into(),
            object: "chair".into(),
            seed: 7,
            rounds: 3,
            prompts: vec![PromptState {
                round: 1,
                loss: vec![0.5],
                ..PromptState::new(
                    "a".into(),
                    "a".into(),
                    vec![0.1 + 0.2, 1.0 / 3.0, -7.123456789012345e-7],
                )
            }],
        };
        state.prompts[0].tally(0, 0);
        folder.save(&state).unwrap();
        assert_eq!(folder.load().unwrap(), state);
        assert!(!state.finished());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_variation_is_the_mean_of_the_last_stages_rounds() {
        let mut p = PromptState::new("a".into(), "a".into(), vec![1.0, 10.0]);
        assert_eq!(p.variation(), [1.0, 10.0]);
        // Rounds 0 and 1 are the warm stages'; the last stage starts at round 2.
        for (round, x) in [[5.0, 50.0], [2.0, 20.0], [3.0, 30.0], [5.0, 40.0]]
            .into_iter()
            .enumerate()
        {
            p.x = x.to_vec();
            p.tally(round, 2);
        }
        assert_eq!(p.tail.rounds, 2);
        assert_eq!(p.variation(), [4.0, 35.0]);
        // Resumed with more rounds the last stage starts later: its mean starts again.
        p.x = vec![7.0, 70.0];
        p.tally(4, 3);
        assert_eq!(p.variation(), [7.0, 70.0]);
    }

    #[test]
    fn a_state_written_before_the_tail_existed_reads_with_an_empty_one() {
        let text = r#"{"version":1,"model":"m.scad","object":"chair","seed":7,"rounds":3,
            "prompts":[{"prompt":"a","name":"a","round":1,"x":[2.5],"loss":[0.5]}]}"#;
        let state: State = serde_json::from_str(text).unwrap();
        assert_eq!(state.prompts[0].tail, Tail::default());
        assert_eq!(state.prompts[0].variation(), [2.5]);
    }
}

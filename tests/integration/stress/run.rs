//! How a stress test is sized, seeded and replayed, and how it counts and reports.
//!
//! - `LINKAGE_STRESS=k` multiplies every test's case count by k (`LINKAGE_STRESS=1`, as
//!   `.ci/run` sets it: about 30 s for the whole suite in the dev profile on a 2-core machine).
//!   Unset, as on a plain `cargo test`, each test runs the first quarter of its ×1 cases: the
//!   same cases, every check, a quarter of the random machines.
//! - `LINKAGE_STRESS_SEED=s` changes the base seed (default: one fixed seed per test).
//! - `LINKAGE_STRESS_CASE=i` runs case i alone: every failure prints the line that replays it.
//! - `LINKAGE_STRESS_SHOW=n` prints the first n failures of each kind (default 12; all are
//!   counted).
//!
//! Case i draws from its own generator, seeded from (seed, i), so a case replays alone exactly
//! as it ran within the suite.

use linkage_tests::{env_number, Rng};
use std::collections::BTreeMap;

/// A stress test's sizing and seed.
pub struct Run {
    test: &'static str,
    pub seed: u64,
    /// `None`: a plain `cargo test` (a quarter of the ×1 cases).
    scale: Option<u64>,
    only: Option<Vec<u64>>,
}

impl Run {
    pub fn new(test: &'static str, default_seed: u64) -> Run {
        Run {
            test,
            seed: env_number("LINKAGE_STRESS_SEED").unwrap_or(default_seed),
            scale: env_number("LINKAGE_STRESS").map(|k| k.max(1)),
            only: env_number("LINKAGE_STRESS_CASE").map(|i| vec![i]),
        }
    }

    /// The listed cases of `test` at `seed` alone, whatever the environment: the cases that
    /// found a defect, kept as its regression test.
    pub fn listed(test: &'static str, seed: u64, cases: &[u64]) -> Run {
        Run {
            test,
            seed,
            scale: Some(1),
            only: Some(cases.to_vec()),
        }
    }

    /// The case indices to run: `default` times the scale (a quarter of `default` without
    /// one), or the ones asked for.
    pub fn cases(&self, default: u64) -> Vec<u64> {
        match (&self.only, self.scale) {
            (Some(list), _) => list.clone(),
            (None, Some(k)) => (0..default * k).collect(),
            (None, None) => (0..(default / 4).max(1)).collect(),
        }
    }

    /// Case `i`'s own generator.
    pub fn rng(&self, case: u64) -> Rng {
        let mut mix = Rng::new(self.seed ^ case.wrapping_mul(0xD1B5_4A32_D192_ED03));
        Rng::new(mix.next_u64())
    }

    pub fn replay(&self, case: u64) -> String {
        format!(
            "LINKAGE_STRESS_SEED={} LINKAGE_STRESS_CASE={case} cargo test -p linkage-tests --test integration stress::{} -- --nocapture",
            self.seed, self.test
        )
    }
}

/// Counts of outcomes and every failure, by kind.
pub struct Tally<'a> {
    run: &'a Run,
    cases: u64,
    counts: BTreeMap<String, u64>,
    failures: BTreeMap<&'static str, Vec<String>>,
}

/// Failures printed in full per kind (all are counted).
fn shown() -> usize {
    env_number("LINKAGE_STRESS_SHOW").map_or(12, |n| n as usize)
}

impl<'a> Tally<'a> {
    pub fn new(run: &'a Run) -> Self {
        Tally {
            run,
            cases: 0,
            counts: BTreeMap::new(),
            failures: BTreeMap::new(),
        }
    }

    pub fn case(&mut self) {
        self.cases += 1;
    }

    pub fn count(&mut self, key: impl Into<String>) {
        *self.counts.entry(key.into()).or_default() += 1;
    }

    /// Records a failure of `kind` in `case`, with what happened and the case's inputs.
    pub fn fail(
        &mut self,
        kind: &'static str,
        case: u64,
        what: String,
        inputs: &dyn std::fmt::Debug,
    ) {
        let list = self.failures.entry(kind).or_default();
        if list.len() < shown() {
            let text = format!(
                "[{kind}] seed {} case {case}: {what}\n    inputs: {inputs:?}\n    replay: {}",
                self.run.seed,
                self.run.replay(case)
            );
            eprintln!("{text}");
            list.push(text);
        } else {
            list.push(String::new());
        }
    }

    /// Prints the counts, then fails the test if anything failed.
    pub fn finish(self) {
        let scale = self.run.scale.map_or("¼".to_string(), |k| k.to_string());
        let mut out = format!(
            "stress::{} (seed {}, ×{scale}): {} cases",
            self.run.test, self.run.seed, self.cases
        );
        for (key, n) in &self.counts {
            out += &format!("\n    {key}: {n}");
        }
        for (kind, list) in &self.failures {
            out += &format!("\n    FAILED {kind}: {}", list.len());
        }
        if self.failures.is_empty() {
            out += "\n    no failures";
        }
        eprintln!("{out}");
        if !self.failures.is_empty() {
            let first: Vec<&String> = self.failures.values().filter_map(|l| l.first()).collect();
            panic!(
                "{out}\nfirst failure of each kind:\n{}",
                first
                    .iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join("\n")
            );
        }
    }
}

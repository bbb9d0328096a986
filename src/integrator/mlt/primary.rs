//! The primary sample space of Metropolis light transport: the uniform numbers a path
//! sampler draws, kept so that they can be mutated and restored (Kelemen, Szirmay-Kalos,
//! Antal, Csonka 2002, "A Simple and Robust Mutation Strategy for the Metropolis Light
//! Transport Algorithm", Computer Graphics Forum 21(3)).
//!
//! Values are stored per stream (camera subpath, light subpath, connections) and mutated
//! lazily, when first read in an iteration: a large step draws a fresh uniform value; a
//! small step adds a normal perturbation of standard deviation `σ·√n` for the `n`
//! iterations since the value last changed (the sum of `n` small steps), wrapped into
//! `[0, 1)`.

use crate::sampling::sampler::SampleSource;
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;

/// Streams the bidirectional estimators use (camera, light, connection).
const STREAMS: usize = 3;

/// One primary sample value with what a rejection restores.
#[derive(Debug, Clone, Copy)]
struct Value {
    value: f32,
    last_modified: u64,
    backup: f32,
    backup_modified: u64,
}

/// A point of primary sample space, mutated by small and large steps; a [`SampleSource`]
/// that reads it.
#[derive(Debug, Clone)]
pub struct PrimarySamples {
    rng: Pcg32,
    values: Vec<Value>,
    sigma: f32,
    large_step_prob: f32,
    iteration: u64,
    large_step: bool,
    last_large_step: u64,
    stream: usize,
    index: usize,
}

/// A uniform `f32` in `[0, 1)` from 24 random bits.
#[inline]
fn uniform(rng: &mut Pcg32) -> f32 {
    (rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
}

impl PrimarySamples {
    /// A fresh point (its first iteration is a large step) whose random numbers come from
    /// `seed`.
    pub fn new(seed: u64, sigma: f32, large_step_prob: f32) -> Self {
        Self {
            rng: Pcg32::seed_from_u64(seed),
            values: Vec::new(),
            sigma,
            large_step_prob,
            iteration: 0,
            large_step: true,
            last_large_step: 0,
            stream: 0,
            index: 0,
        }
    }

    /// Re-seeds the generator of mutations (the current point stays).
    pub fn reseed(&mut self, seed: u64) {
        self.rng = Pcg32::seed_from_u64(seed);
    }

    /// Begins a proposal: a large step with the large-step probability, else a small one.
    pub fn start_iteration(&mut self) {
        self.iteration += 1;
        self.large_step = uniform(&mut self.rng) < self.large_step_prob;
    }

    /// Whether the current proposal is a large step.
    pub fn is_large_step(&self) -> bool {
        self.large_step
    }

    /// Keeps the proposal.
    pub fn accept(&mut self) {
        if self.large_step {
            self.last_large_step = self.iteration;
        }
    }

    /// Discards the proposal: every value it changed goes back.
    pub fn reject(&mut self) {
        for v in &mut self.values {
            if v.last_modified == self.iteration {
                v.value = v.backup;
                v.last_modified = v.backup_modified;
            }
        }
        self.iteration -= 1;
    }

    /// A standard normal variate (Box–Muller).
    fn normal(&mut self) -> f32 {
        let u1 = 1.0 - uniform(&mut self.rng);
        let u2 = uniform(&mut self.rng);
        (-2.0 * u1.ln()).sqrt() * (std::f32::consts::TAU * u2).cos()
    }

    /// Brings value `i` up to the current iteration.
    fn update(&mut self, i: usize) {
        while self.values.len() <= i {
            // A dimension read for the first time: a fresh uniform value.
            let value = uniform(&mut self.rng);
            self.values.push(Value {
                value,
                last_modified: self.iteration,
                backup: value,
                backup_modified: self.iteration,
            });
        }
        let mut v = self.values[i];
        if v.last_modified == self.iteration {
            return;
        }
        // A value untouched since before the last accepted large step takes that step's
        // fresh value first.
        if v.last_modified < self.last_large_step {
            v.value = uniform(&mut self.rng);
            v.last_modified = self.last_large_step;
        }
        v.backup = v.value;
        v.backup_modified = v.last_modified;
        if self.large_step {
            v.value = uniform(&mut self.rng);
        } else {
            let n = (self.iteration - v.last_modified) as f32;
            let x = v.value + self.normal() * self.sigma * n.sqrt();
            v.value = x - x.floor();
            if v.value >= 1.0 {
                v.value = 0.0;
            }
        }
        v.last_modified = self.iteration;
        self.values[i] = v;
    }
}

impl SampleSource for PrimarySamples {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        let i = self.index * STREAMS + self.stream;
        self.index += 1;
        self.update(i);
        self.values[i].value
    }

    #[inline]
    fn start_stream(&mut self, stream: u32) {
        self.stream = (stream as usize).min(STREAMS - 1);
        self.index = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reject_restores_and_accept_keeps() {
        let mut p = PrimarySamples::new(3, 0.01, 0.3);
        p.start_stream(0);
        let a: Vec<f32> = (0..5).map(|_| p.next_1d()).collect();
        p.accept();
        for _ in 0..20 {
            p.start_iteration();
            p.start_stream(0);
            let b: Vec<f32> = (0..5).map(|_| p.next_1d()).collect();
            assert!(b.iter().all(|x| x.is_finite() && (0.0..1.0).contains(x)));
            p.reject();
            p.start_stream(0);
            // Reading again at the restored iteration gives the original values.
            let c: Vec<f32> = (0..5).map(|_| p.next_1d()).collect();
            assert_eq!(a, c);
        }
        p.start_iteration();
        p.start_stream(0);
        let d: Vec<f32> = (0..5).map(|_| p.next_1d()).collect();
        p.accept();
        p.start_stream(0);
        let e: Vec<f32> = (0..5).map(|_| p.next_1d()).collect();
        assert_eq!(d, e);
    }
}

//! One Markov chain of Metropolis light transport: proposals by small and large steps in
//! primary sample space, accepted with probability `min(1, y'/y)`, and both the proposal and
//! the current state splatted with their expected weights.

use super::{brightness, Mlt, MltPath, PrimarySamples};
use crate::integrator::{BdptBuffers, BidirectionalScene};
use glam::{Vec2, Vec3};
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;

/// A chain at a fixed path length, started from a bootstrap sample.
#[derive(Debug, Clone)]
pub struct MltChain {
    samples: PrimarySamples,
    accept_rng: Pcg32,
    segments: u32,
    current: MltPath,
    buf: BdptBuffers,
    /// Rays cast so far.
    pub rays: u64,
    /// Proposals accepted so far.
    pub accepted: u64,
    /// Proposals made so far.
    pub proposed: u64,
}

impl MltChain {
    /// Starts a chain at the bootstrap sample of seed `start_seed` (from
    /// [`Mlt::bootstrap_seed`]) with `segments` segments; its mutations come from
    /// `chain_seed`.
    pub fn new<S: BidirectionalScene>(
        mlt: &Mlt,
        scene: &S,
        segments: u32,
        start_seed: u64,
        chain_seed: u64,
    ) -> Self {
        let mut samples = PrimarySamples::new(start_seed, mlt.sigma, mlt.large_step_prob);
        let mut buf = BdptBuffers::default();
        let mut rays = 0u32;
        let current = mlt.path(scene, segments, &mut samples, &mut buf, &mut rays);
        samples.accept();
        samples.reseed(chain_seed);
        Self {
            samples,
            accept_rng: Pcg32::seed_from_u64(chain_seed ^ 0x5bd1_e995),
            segments,
            current,
            buf,
            rays: rays as u64,
            accepted: 0,
            proposed: 0,
        }
    }

    /// Runs `n` mutations; `splat(raster, value)` receives every splat, in the chain's own
    /// units (the caller scales the image by `b / mutations_per_pixel`).
    pub fn run<S: BidirectionalScene>(
        &mut self,
        mlt: &Mlt,
        scene: &S,
        n: u64,
        mut splat: impl FnMut(Vec2, Vec3),
    ) {
        for _ in 0..n {
            self.samples.start_iteration();
            let mut rays = 0u32;
            let proposal = mlt.path(
                scene,
                self.segments,
                &mut self.samples,
                &mut self.buf,
                &mut rays,
            );
            self.rays += rays as u64;
            self.proposed += 1;
            let (y_new, y_cur) = (brightness(proposal.value), brightness(self.current.value));
            let accept = if y_cur > 0.0 {
                (y_new / y_cur).min(1.0)
            } else {
                1.0
            };
            if y_new > 0.0 {
                splat(proposal.raster, proposal.value * (accept / y_new));
            }
            if y_cur > 0.0 && accept < 1.0 {
                splat(
                    self.current.raster,
                    self.current.value * ((1.0 - accept) / y_cur),
                );
            }
            let u = (self.accept_rng.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0);
            if u < accept {
                self.current = proposal;
                self.samples.accept();
                self.accepted += 1;
            } else {
                self.samples.reject();
            }
        }
    }
}

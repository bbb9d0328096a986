//! The training schedule of path guiding: passes of doubling sample counts.

/// One pass of a [`GuidingSchedule`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidingPass {
    /// The pass's index k (0 for the first).
    pub index: u32,
    /// Samples per pixel of the pass: `2^k` for a training pass, the rest of the budget for
    /// the final one.
    pub spp: u32,
    /// Whether this is the final pass, whose image is the result (and which need not record).
    pub is_final: bool,
    /// The spatial threshold with which to refine the tree this pass trained
    /// ([`SdTree::refined`](super::SdTree::refined)): `c·√(2^k)`.
    pub spatial_threshold: f64,
}

/// The training schedule of Müller et al. 2017: pass k renders `2^k` samples per pixel,
/// guided by the tree trained in pass k − 1, and records into a fresh tree with the refined
/// structure; training stops when the rest of the budget is less than twice the next pass,
/// and the final pass renders the rest. The image is the final pass's alone (the training
/// passes' images are discarded, the paper's simplest choice).
///
/// The renderer drives it, since it owns the pixel loop:
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::sampling::guiding::{GuidingSchedule, SdTree};
///
/// let schedule = GuidingSchedule::new(16);
/// let spp: Vec<u32> = schedule.passes().map(|p| p.spp).collect();
/// assert_eq!(spp, [1, 2, 4, 9]);
/// let mut guide = SdTree::new(Vec3::splat(-1.0), Vec3::ONE); // uniform
/// let mut training = guide.clone();
/// for pass in schedule.passes() {
///     // render pass.spp samples per pixel guided by `guide`, recording into per-tile
///     // `GuidingRecords` merged into `training` in tile order...
///     if !pass.is_final {
///         let next = schedule.next_tree(&training, &pass);
///         guide = std::mem::replace(&mut training, next);
///     }
/// }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidingSchedule {
    /// The whole budget in samples per pixel.
    pub total_spp: u32,
    /// `c` of the spatial threshold `c·√(2^k)` (the paper's 12000).
    pub spatial_c: f64,
    /// The energy fraction ρ above which a quadrant is subdivided (the paper's 0.01).
    pub rho: f64,
    /// The deepest directional quadtree (the paper's 20).
    pub max_depth: u32,
}

impl GuidingSchedule {
    /// The paper's settings for a budget of `total_spp` samples per pixel.
    pub fn new(total_spp: u32) -> Self {
        Self {
            total_spp,
            spatial_c: 12_000.0,
            rho: 0.01,
            max_depth: 20,
        }
    }

    /// The passes, in order; the last is final. A budget of 0 has no passes.
    pub fn passes(&self) -> impl Iterator<Item = GuidingPass> + '_ {
        let mut remaining = self.total_spp;
        let mut k = 0u32;
        let mut done = remaining == 0;
        std::iter::from_fn(move || {
            if done {
                return None;
            }
            let spp = 1u32.checked_shl(k).unwrap_or(u32::MAX);
            let next = spp.saturating_mul(2);
            let threshold = self.spatial_c * 2f64.powi(k as i32).sqrt();
            let pass = if k < 31 && remaining.saturating_sub(spp) >= next {
                remaining -= spp;
                GuidingPass {
                    index: k,
                    spp,
                    is_final: false,
                    spatial_threshold: threshold,
                }
            } else {
                done = true;
                GuidingPass {
                    index: k,
                    spp: remaining,
                    is_final: true,
                    spatial_threshold: threshold,
                }
            };
            k += 1;
            Some(pass)
        })
    }

    /// The tree that records the pass after `pass`, from the tree `trained` that recorded
    /// `pass`: [`SdTree::refined`](super::SdTree::refined) with this schedule's settings.
    pub fn next_tree(&self, trained: &super::SdTree, pass: &GuidingPass) -> super::SdTree {
        trained.refined(pass.spatial_threshold, self.rho, self.max_depth)
    }
}

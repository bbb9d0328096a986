//! A worker's buffer of radiance records, merged into an [`SdTree`](super::SdTree) in a fixed
//! order.

use glam::{Vec2, Vec3};

/// One radiance record: radiance arriving at `p` along `dir`, sampled with density `pdf`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidingRecord {
    /// Where the radiance arrives.
    pub p: Vec3,
    /// The unit direction it arrives from (world space, pointing away from `p`).
    pub dir: Vec3,
    /// The radiance, a scalar (the mean of the RGB channels).
    pub radiance: f32,
    /// The density per steradian with which `dir` was sampled.
    pub pdf: f32,
}

/// A buffer of [`GuidingRecord`]s that one worker (one tile) fills while it renders, so that
/// the training tree can be shared read-only and updated afterwards in a fixed order
/// ([`SdTree::merge`](super::SdTree::merge)): deterministic at any thread count. It also holds
/// the guided path tracer's scratch space for the vertices of the current path.
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::sampling::guiding::{GuidingRecord, GuidingRecords, SdTree};
///
/// let mut buf = GuidingRecords::new();
/// buf.push(GuidingRecord { p: Vec3::ZERO, dir: Vec3::Z, radiance: 1.0, pdf: 0.5 });
/// let mut tree = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
/// tree.merge(&buf);
/// assert_eq!(tree.sample_count(), 1);
/// buf.clear();
/// assert!(buf.is_empty());
/// ```
#[derive(Debug, Clone, Default)]
pub struct GuidingRecords {
    /// The records, each with its direction's point of the square and, if the guided path
    /// tracer made it, what the learning of the selection probability needs: one vector, so
    /// that a merge reads each record once, in order.
    records: Vec<StoredRecord>,
    pub(crate) scratch: Vec<PathVertex>,
}

/// A [`GuidingRecord`] as the buffer holds it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StoredRecord {
    pub record: GuidingRecord,
    /// [`sphere_to_square`](super::sphere_to_square) of `record.dir`, mapped once.
    pub square: Vec2,
    /// What the guided path tracer saw of its choice between guide and BSDF, for a tree that
    /// learns its selection probability ([`SdTree::learn_selection`](super::SdTree::learn_selection)).
    pub selection: Option<SelectionRecord>,
}

/// One direction sampled from the mixture of guide and BSDF, as the learning of the
/// selection probability needs it: the integrand `F = T·f·|cos θ|·L` (channels averaged;
/// `T` the path's throughput before the vertex, so that each vertex counts as much as its
/// part of the pixel's variance) and the guide's and the BSDF's densities (the mixture's is
/// the record's `pdf`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SelectionRecord {
    pub integrand: f32,
    pub p_guide: f32,
    pub p_bsdf: f32,
}

/// A vertex of a guided path, while its incident radiance is being summed.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PathVertex {
    pub p: Vec3,
    pub dir: Vec3,
    pub pdf: f32,
    /// The direction's point of the square ([`sphere_to_square`](super::sphere_to_square)).
    pub square: Vec2,
    /// The path throughput before the vertex times `f·|cos θ|` of the sampled direction,
    /// per channel, and the guide's and the BSDF's densities of the direction.
    pub path_f_cos: Vec3,
    pub p_guide: f32,
    pub p_bsdf: f32,
    /// The reciprocal of the path throughput after the vertex's sampling weight (and
    /// Russian roulette), 0 in a channel where the throughput is 0.
    pub inv_throughput: Vec3,
    /// The contributions of the path after the vertex, summed.
    pub radiance: Vec3,
}

impl GuidingRecords {
    /// An empty buffer.
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends a record.
    #[inline]
    pub fn push(&mut self, r: GuidingRecord) {
        let square = super::sphere_to_square(r.dir);
        self.records.push(StoredRecord {
            record: r,
            square,
            selection: None,
        });
    }

    /// Appends a record whose direction's point of the square is `square`, with what the
    /// guided path tracer saw of its choice.
    #[inline]
    pub(crate) fn push_stored(&mut self, r: StoredRecord) {
        self.records.push(r);
    }

    /// The records, in the order they were pushed.
    pub fn iter(&self) -> impl Iterator<Item = &GuidingRecord> {
        self.records.iter().map(|r| &r.record)
    }

    /// The records as stored, in order.
    pub(crate) fn stored(&self) -> &[StoredRecord] {
        &self.records
    }

    /// The number of records.
    pub fn len(&self) -> usize {
        self.records.len()
    }

    /// Whether there are no records.
    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }

    /// Removes every record (keeping the allocation).
    pub fn clear(&mut self) {
        self.records.clear();
    }
}

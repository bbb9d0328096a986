//! A uniform grid traversed with a 3D digital differential analyser.
//!
//! Resolution: `res_a = extent_a · ∛(λ n / V)` cells along axis `a` (n primitives, V the
//! volume of the scene box, λ = [`DENSITY`] cells per primitive), clamped to
//! `[1, MAX_RES]`. The grid's size is then bounded by the primitive count: while it has more
//! than [`MAX_CELLS_PER_PRIM`]` · n + `[`MIN_CELLS`] cells (a flat or thin scene, whose
//! small volume asks for many cells), or its cells would list more than
//! [`MAX_REFS_PER_PRIM`]` · n + `[`MIN_REFS`] primitives in all (primitives that overlap, as
//! copies of one triangle, each listed in every cell of their common box), the finest axis
//! is halved. So a grid takes O(n) memory for any input. A primitive is listed in every cell its box overlaps (the box grown by a
//! thousandth of a cell, so that rounding at cell faces cannot lose it). Traversal steps
//! cell by cell in the order the ray crosses them (Amanatides & Woo 1987, "A Fast Voxel
//! Traversal Algorithm for Ray Tracing", Eurographics; Cleary & Wyvill 1988, "Analysis of an
//! algorithm for fast ray tracing using uniform space subdivision", The Visual Computer),
//! and stops once the nearest hit lies before the exit of the current cell.

use super::aabb::{Aabb, RayBoxTest};
use glam::Vec3;

/// Cells per primitive (λ).
pub(crate) const DENSITY: f32 = 3.0;
/// Largest resolution along one axis.
pub(crate) const MAX_RES: u32 = 128;
/// Most cells per primitive, beyond [`MIN_CELLS`].
pub(crate) const MAX_CELLS_PER_PRIM: u64 = 16;
/// Cells a grid may have whatever its primitive count.
pub(crate) const MIN_CELLS: u64 = 1 << 12;
/// Most cell entries per primitive on average, beyond [`MIN_REFS`].
pub(crate) const MAX_REFS_PER_PRIM: u64 = 16;
/// Cell entries a grid may have whatever its primitive count.
pub(crate) const MIN_REFS: u64 = 1 << 16;

/// A uniform grid over primitives given by their bounds (in stored order).
#[derive(Debug, Clone)]
pub(crate) struct Grid {
    bounds: Aabb,
    res: [i32; 3],
    cell: Vec3,
    inv_cell: Vec3,
    /// Cell `c` lists `items[offsets[c]..offsets[c + 1]]`.
    offsets: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    /// Builds the grid over primitives with the given bounds.
    pub(crate) fn build(prims: &[Aabb]) -> Self {
        let mut bounds = prims.iter().fold(Aabb::EMPTY, |b, p| b.union(*p));
        if bounds.is_empty() {
            bounds = Aabb {
                min: Vec3::ZERO,
                max: Vec3::ONE,
            };
        }
        // Give flat scenes some thickness so every axis has a positive cell size.
        let pad = bounds.extent().max_element().max(1e-6) * 1e-4;
        bounds.min -= Vec3::splat(pad);
        bounds.max += Vec3::splat(pad);
        let ext = bounds.extent();
        let per_len = (DENSITY * prims.len().max(1) as f32 / (ext.x * ext.y * ext.z)).cbrt();
        let mut res =
            [0, 1, 2].map(|a| ((ext[a] * per_len).round() as u32).clamp(1, MAX_RES) as i32);
        let live = prims.iter().filter(|p| !p.is_empty()).count() as u64;
        let cells = |r: &[i32; 3]| r.iter().map(|&r| r as u64).product::<u64>();
        while cells(&res) > MAX_CELLS_PER_PRIM * live + MIN_CELLS {
            halve_finest(&mut res);
        }
        let mut g = Self::empty(bounds, res);
        while g.refs(prims) > MAX_REFS_PER_PRIM * live + MIN_REFS && res != [1, 1, 1] {
            halve_finest(&mut res);
            g = Self::empty(bounds, res);
        }
        g.fill(prims);
        g
    }

    /// The grid over `bounds` with resolution `res`, its cells not yet filled.
    fn empty(bounds: Aabb, res: [i32; 3]) -> Self {
        let cell = bounds.extent() / Vec3::new(res[0] as f32, res[1] as f32, res[2] as f32);
        Self {
            bounds,
            res,
            cell,
            inv_cell: cell.recip(),
            offsets: Vec::new(),
            items: Vec::new(),
        }
    }

    /// The number of cell entries [`Grid::fill`] would make: O(1) per primitive.
    fn refs(&self, prims: &[Aabb]) -> u64 {
        prims
            .iter()
            .filter(|p| !p.is_empty())
            .map(|p| {
                let (lo, hi) = self.cell_range(p);
                (0..3).map(|a| (hi[a] - lo[a] + 1) as u64).product::<u64>()
            })
            .sum()
    }

    /// Heap bytes held (cell offsets and entries).
    pub(crate) fn heap_bytes(&self) -> usize {
        super::vec_bytes(&self.offsets) + super::vec_bytes(&self.items)
    }

    /// The number of cell entries (each primitive once per cell it overlaps).
    #[cfg(test)]
    pub(crate) fn ref_count(&self) -> usize {
        self.items.len()
    }

    #[cfg(test)]
    /// The resolution along each axis.
    pub(crate) fn resolution(&self) -> [u32; 3] {
        self.res.map(|r| r as u32)
    }

    fn cell_range(&self, b: &Aabb) -> ([i32; 3], [i32; 3]) {
        let margin = self.cell * 1e-3;
        let lo = ((b.min - margin - self.bounds.min) * self.inv_cell).floor();
        let hi = ((b.max + margin - self.bounds.min) * self.inv_cell).floor();
        let c = |v: f32, a: usize| (v as i32).clamp(0, self.res[a] - 1);
        (
            [c(lo.x, 0), c(lo.y, 1), c(lo.z, 2)],
            [c(hi.x, 0), c(hi.y, 1), c(hi.z, 2)],
        )
    }

    #[inline]
    fn index(&self, c: [i32; 3]) -> usize {
        (c[0] + self.res[0] * (c[1] + self.res[1] * c[2])) as usize
    }

    fn for_cells(&self, b: &Aabb, mut f: impl FnMut(usize)) {
        let (lo, hi) = self.cell_range(b);
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    f(self.index([x, y, z]));
                }
            }
        }
    }

    fn fill(&mut self, prims: &[Aabb]) {
        let cells = (self.res[0] * self.res[1] * self.res[2]) as usize;
        let mut counts = vec![0u32; cells + 1];
        for p in prims.iter().filter(|p| !p.is_empty()) {
            self.for_cells(p, |c| counts[c + 1] += 1);
        }
        for c in 0..cells {
            counts[c + 1] += counts[c];
        }
        let mut items = vec![0u32; counts[cells] as usize];
        let mut cursor = counts.clone();
        for (i, p) in prims.iter().enumerate().filter(|(_, p)| !p.is_empty()) {
            self.for_cells(p, |c| {
                items[cursor[c] as usize] = i as u32;
                cursor[c] += 1;
            });
        }
        self.offsets = counts;
        self.items = items;
    }

    /// Like [`super::Bvh4::closest`]: visits primitives along the ray, `test` returns a hit
    /// distance below its bound, and the nearest distance found is returned.
    #[inline]
    pub(crate) fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        let mut best: (Option<f32>, f32) = (None, t_max);
        self.walk(
            origin,
            dir,
            t_max,
            &mut best,
            |best, i| {
                if let Some(t) = test(i, best.1) {
                    *best = (Some(t), t);
                }
                false
            },
            |best, exit| best.0.is_some_and(|b| b <= exit),
        );
        best.0
    }

    /// Like [`super::Bvh4::any`]: true as soon as `test(i, t_max)` holds for a primitive.
    #[inline]
    pub(crate) fn any(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        self.walk(
            origin,
            dir,
            t_max,
            &mut (),
            |_, i| test(i, t_max),
            |_, _| false,
        )
    }

    /// The DDA loop: `visit(state, prim)` returns true to stop at once; after each
    /// cell, `done(state, cell_exit)` returns true to stop.
    #[inline(always)]
    fn walk<S>(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        state: &mut S,
        mut visit: impl FnMut(&mut S, u32) -> bool,
        done: impl Fn(&S, f32) -> bool,
    ) -> bool {
        let rb = RayBoxTest::new(origin, dir);
        let Some((t0, t1)) = rb.clip(self.bounds.min.into(), self.bounds.max.into(), t_max) else {
            return false;
        };
        let p = origin + dir * t0;
        let rel = (p - self.bounds.min) * self.inv_cell;
        let mut c = [0usize, 1, 2].map(|a| (rel[a].floor() as i32).clamp(0, self.res[a] - 1));
        let step = [0usize, 1, 2].map(|a| if dir[a] < 0.0 { -1 } else { 1 });
        let next_t = |c: &[i32; 3], a: usize| {
            if dir[a] == 0.0 {
                return f32::INFINITY;
            }
            let face = c[a] + i32::from(step[a] > 0);
            (self.bounds.min[a] + face as f32 * self.cell[a] - origin[a]) / dir[a]
        };
        let mut t_next = [next_t(&c, 0), next_t(&c, 1), next_t(&c, 2)];
        loop {
            let cell = self.index(c);
            let exit = t_next[0].min(t_next[1]).min(t_next[2]);
            let (s, e) = (self.offsets[cell] as usize, self.offsets[cell + 1] as usize);
            for &i in &self.items[s..e] {
                if visit(state, i) {
                    return true;
                }
            }
            if done(state, exit) || exit > t1 {
                return false;
            }
            let a = if t_next[0] <= t_next[1] && t_next[0] <= t_next[2] {
                0
            } else if t_next[1] <= t_next[2] {
                1
            } else {
                2
            };
            c[a] += step[a];
            if c[a] < 0 || c[a] >= self.res[a] {
                return false;
            }
            t_next[a] = next_t(&c, a);
        }
    }
}

/// Halves the resolution along the axis with the most cells (the first of equals).
fn halve_finest(res: &mut [i32; 3]) {
    let a = (0..3).fold(0, |m, a| if res[a] > res[m] { a } else { m });
    res[a] = (res[a] / 2).max(1);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolution_grows_with_count() {
        let boxes: Vec<Aabb> = (0..1000)
            .map(|i| {
                let p = Vec3::new((i % 10) as f32, (i / 10 % 10) as f32, (i / 100) as f32);
                Aabb::from_points(&[p, p + Vec3::splat(0.5)])
            })
            .collect();
        let g = Grid::build(&boxes);
        let r = g.resolution();
        assert!(r.iter().all(|&r| (10..=20).contains(&r)), "{r:?}");
        // A ray along a row visits exactly the 10 boxes of that row.
        let mut seen = std::collections::BTreeSet::new();
        g.any(
            Vec3::new(-1.0, 0.25, 0.25),
            Vec3::X,
            f32::INFINITY,
            |i, _| {
                seen.insert(i);
                false
            },
        );
        assert_eq!(seen.len(), 10);
    }

    #[test]
    fn flat_scene_builds() {
        let b = Aabb::from_points(&[Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0)]);
        let g = Grid::build(&[b]);
        assert!(g.any(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z, 2.0, |_, _| true));
    }

    /// Copies of one flat triangle's box and shifted copies overlapping in one plane: the
    /// cells and entries stay within their bounds (the plane alone asked for 128 × 128
    /// cells, each listing every copy), and a ray through them still meets every one.
    #[test]
    fn overlapping_flat_boxes_stay_bounded() {
        let n = 20_000;
        let flat = |d: f32| {
            Aabb::from_points(&[Vec3::new(-0.5 + d, -0.5, 0.0), Vec3::new(0.5 + d, 0.5, 0.0)])
        };
        let same = vec![flat(0.0); n];
        let shifted: Vec<Aabb> = (0..n).map(|i| flat(i as f32 * 1e-5)).collect();
        for boxes in [same, shifted] {
            let g = Grid::build(&boxes);
            let cells: u64 = g.resolution().iter().map(|&r| u64::from(r)).product();
            assert!(
                cells <= MAX_CELLS_PER_PRIM * n as u64 + MIN_CELLS,
                "{cells}"
            );
            let refs = g.ref_count() as u64;
            assert!(refs <= MAX_REFS_PER_PRIM * n as u64 + MIN_REFS, "{refs}");
            let mut seen = std::collections::BTreeSet::new();
            g.any(Vec3::new(0.3, 0.1, 1.0), -Vec3::Z, 2.0, |i, _| {
                seen.insert(i);
                false
            });
            assert_eq!(seen.len(), n);
        }
    }

    /// A few primitives in a plane keep a fine grid (the bounds leave small inputs alone).
    #[test]
    fn small_flat_scene_keeps_its_resolution() {
        let b = Aabb::from_points(&[Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, 1.0, 0.0)]);
        let r = Grid::build(&[b, b]).resolution();
        assert!(r[0] > 8 && r[1] > 8 && r[2] == 1, "{r:?}");
    }
}

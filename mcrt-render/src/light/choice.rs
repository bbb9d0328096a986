//! Which light next-event estimation samples: by power, or, when every light has a position
//! (area lights on shapes, point lights) and there are few of them, by an estimate of each
//! light's contribution at the shading point.
//!
//! The estimate is power over squared distance to the light's bounding sphere, clamped at
//! its radius: `w_i(p) = Φ_i / max(|c_i − p|², r_i²)` (the point-light falloff; the clamp
//! keeps it bounded inside and near a light). It ignores orientation and occlusion, so it
//! is mixed with the power distribution: `P(i | p) = (1 − ε)·w_i(p)/Σw + ε·Φ_i/ΣΦ` with
//! ε = [`DEFENSIVE`], which keeps every emitting light's probability at least ε times its
//! power share (Hesterberg 1995, "Weighted Average Importance Sampling and Defensive
//! Mixture Distributions", Technometrics 37(2)). Any choice with nonzero probability for
//! every emitting light leaves the estimator unbiased; this one only moves samples toward
//! the lights that matter where the path is. Scenes with an environment light keep the
//! power choice (an environment has no position).

use glam::{Vec3, Vec4};
use mcrt::sampling::distribution::AliasTable;
use mcrt::sampling::ONE_MINUS_EPSILON;

/// Lights up to which the choice is made per shading point (its cost is linear in them).
pub(crate) const MAX_SPATIAL: usize = 16;

/// Share of the power distribution in the spatial choice.
pub(crate) const DEFENSIVE: f32 = 0.1;

/// A light's place for the spatial choice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LightPlace {
    /// Centre of a sphere bounding the light.
    pub(crate) center: Vec3,
    /// Its radius (0 for a point light).
    pub(crate) radius: f32,
}

/// The distribution that chooses a light.
#[derive(Debug, Clone)]
pub(crate) enum LightChoice {
    /// By power alone.
    Power(AliasTable),
    /// By power over squared distance at the shading point, mixed with the power shares.
    Spatial {
        /// Four lights at a time (structure of arrays, for 4-wide arithmetic): centres' x, y
        /// and z, squared radii (with a floor), powers; unused lanes have power 0.
        lights: Vec<[Vec4; 5]>,
        /// Per light: ε · Φ_i / ΣΦ.
        floor: Vec<f32>,
        /// The power distribution, for points where the weights are not finite.
        power: AliasTable,
    },
}

impl LightChoice {
    /// The choice for lights of power `power` at `places` (`None` for a light without a
    /// position, which forces the power choice); `None` when no light emits.
    pub(crate) fn new(power: &[f32], places: &[Option<LightPlace>]) -> Option<Self> {
        let table = AliasTable::new(power).ok()?;
        let placed: Option<Vec<LightPlace>> = places.iter().copied().collect();
        let spatial = power.len() > 1 && power.len() <= MAX_SPATIAL;
        match placed {
            Some(placed) if spatial && placed.len() == power.len() => {
                let total: f32 = power.iter().sum();
                let lights = placed
                    .chunks(4)
                    .zip(power.chunks(4))
                    .map(|(places, powers)| {
                        let mut g = [Vec4::ZERO, Vec4::ZERO, Vec4::ZERO, Vec4::ONE, Vec4::ZERO];
                        for (k, (l, &phi)) in places.iter().zip(powers).enumerate() {
                            g[0][k] = l.center.x;
                            g[1][k] = l.center.y;
                            g[2][k] = l.center.z;
                            g[3][k] = (l.radius * l.radius).max(f32::MIN_POSITIVE);
                            g[4][k] = phi;
                        }
                        g
                    })
                    .collect();
                let floor = power.iter().map(|&phi| DEFENSIVE * phi / total).collect();
                Some(Self::Spatial {
                    lights,
                    floor,
                    power: table,
                })
            }
            _ => Some(Self::Power(table)),
        }
    }

    /// The unnormalised weights `w_i(p)` into `w`, four lights at a time, and their sum;
    /// `None` where the sum is not a positive finite number (then the power choice stands
    /// in, at both sampling and density evaluation, so the two always agree). A NaN
    /// distance gives way to the radius floor (`max` returns its second operand then).
    #[inline]
    fn weights(lights: &[[Vec4; 5]], p: Vec3, w: &mut [f32; MAX_SPATIAL]) -> Option<f32> {
        let mut sum = Vec4::ZERO;
        for (slot, g) in w.chunks_exact_mut(4).zip(lights) {
            let (dx, dy, dz) = (
                g[0] - Vec4::splat(p.x),
                g[1] - Vec4::splat(p.y),
                g[2] - Vec4::splat(p.z),
            );
            let d2 = dx * dx + dy * dy + dz * dz;
            let wk = g[4] / d2.max(g[3]);
            wk.write_to_slice(slot);
            sum += wk;
        }
        let sum = sum.element_sum();
        (sum.is_finite() && sum > 0.0).then_some(sum)
    }

    /// The power distribution (the whole choice, or the spatial choice's fallback).
    pub(crate) fn power(&self) -> &AliasTable {
        match self {
            Self::Power(t) | Self::Spatial { power: t, .. } => t,
        }
    }

    /// At `p`: the unnormalised weights `w_i(p)`, the scale `(1 − ε)/Σw` that makes them
    /// the spatial part of each light's probability, and the power floors `ε·Φ_i/ΣΦ` to
    /// add to it: light `i`'s probability is `w_i·scale + floor_i`. `None` for the power
    /// choice (always, or at a point where the weights are not finite). Sampling and
    /// [`LightChoice::pmf`] both go through here, so they agree bit for bit.
    #[inline]
    fn spatial_at(&self, p: Vec3) -> Option<([f32; MAX_SPATIAL], f32, &[f32])> {
        let Self::Spatial { lights, floor, .. } = self else {
            return None;
        };
        let mut w = [0.0; MAX_SPATIAL];
        let scale = (1.0 - DEFENSIVE) / Self::weights(lights, p, &mut w)?;
        Some((w, scale, floor))
    }

    /// A light chosen at shading point `p` with `u ∈ [0, 1)`, its probability, and `u`
    /// reused: rescaled from the light's share of `[0, 1)` to all of it (uniform there
    /// given the light), for the light's own sampling. With a stratified `u` the points each
    /// light receives are then stratified too, as they would not be from a second,
    /// decorrelated sample value (Mitsuba 3 chooses its emitters this way).
    #[inline]
    pub(crate) fn sample(&self, p: Vec3, u: f32) -> (usize, f32, f32) {
        let Some((w, scale, floor)) = self.spatial_at(p) else {
            return self.power().sample_reusing(u);
        };
        let mut last = (0, 0.0, 0.0);
        let mut cdf = 0.0;
        for (i, (&wi, &fi)) in w.iter().zip(floor).enumerate() {
            let pi = wi * scale + fi;
            if pi > 0.0 {
                last = (i, pi, cdf);
                cdf += pi;
                if u < cdf {
                    break;
                }
            }
        }
        // Rounding can leave the sum of probabilities just under `u`: the last light with a
        // nonzero probability takes that sliver (its reused value is clamped below 1).
        let (i, pi, below) = last;
        let rest = ((f64::from(u) - f64::from(below)) / f64::from(pi)) as f32;
        (i, pi, rest.clamp(0.0, ONE_MINUS_EPSILON))
    }

    /// The probability that [`LightChoice::sample`] at `p` returns light `i`.
    #[inline]
    pub(crate) fn pmf(&self, p: Vec3, i: usize) -> f32 {
        match self.spatial_at(p) {
            Some((w, scale, floor)) => floor.get(i).map_or(0.0, |&fi| w[i] * scale + fi),
            None => self.power().pmf(i),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn place(x: f32, radius: f32) -> Option<LightPlace> {
        Some(LightPlace {
            center: Vec3::new(x, 0.0, 0.0),
            radius,
        })
    }

    /// Veach's MIS scene: four lights of equal power in a row and a far, brighter fill.
    fn veach_like() -> LightChoice {
        let power = [0.75, 0.75, 0.75, 0.75, 1.2];
        let mut places = vec![place(-3.75, 0.05), place(-1.25, 0.15), place(1.25, 0.45)];
        places.push(place(3.75, 1.0));
        places.push(Some(LightPlace {
            center: Vec3::new(0.0, 12.0, 14.0),
            radius: 1.0,
        }));
        LightChoice::new(&power, &places).unwrap()
    }

    #[test]
    fn probabilities_sum_to_one_and_match_the_sampling_frequencies() {
        let c = veach_like();
        assert!(matches!(c, LightChoice::Spatial { .. }));
        for p in [
            Vec3::new(-3.0, -2.5, -1.0),
            Vec3::new(3.75, 0.0, 0.0),
            Vec3::new(0.0, 12.0, 14.0),
            Vec3::new(100.0, 0.0, 0.0),
        ] {
            let pmf: Vec<f32> = (0..5).map(|i| c.pmf(p, i)).collect();
            let sum: f32 = pmf.iter().sum();
            assert!(sum.is_finite() && (sum - 1.0).abs() < 1e-5, "{p}: {pmf:?}");
            // Every emitting light keeps at least the defensive share of its power.
            for (i, &q) in pmf.iter().enumerate() {
                let share = if i == 4 { 1.2 / 4.2 } else { 0.75 / 4.2 };
                assert!(
                    q.is_finite() && q >= DEFENSIVE * share * 0.999,
                    "{p}: {pmf:?}"
                );
            }
            // A fine grid of u: each light's frequency is its probability, and the
            // probability sampling reports is the one `pmf` gives.
            let n = 100_000;
            let mut count = [0usize; 5];
            for k in 0..n {
                let (i, q, rest) = c.sample(p, (k as f32 + 0.5) / n as f32);
                assert_eq!(q, pmf[i], "{p}: light {i}");
                assert!(
                    rest.is_finite() && (0.0..1.0).contains(&rest),
                    "{p}: {rest}"
                );
                count[i] += 1;
            }
            for i in 0..5 {
                let f = count[i] as f32 / n as f32;
                assert!(
                    (f - pmf[i]).abs() < 2e-4,
                    "{p}: light {i}: {f} against {}",
                    pmf[i]
                );
            }
        }
    }

    /// The reused values of an evenly spaced `u` are evenly spaced for every light: the
    /// light's share of `[0, 1)` is one interval, mapped linearly onto `[0, 1)`, so the
    /// widest gap between a light's sorted reused values (including the ends) is one step
    /// `1 / (n · P(light))`, up to rounding.
    #[test]
    fn reused_values_keep_the_stratification() {
        let c = veach_like();
        let p = Vec3::new(-1.0, -2.0, 0.5);
        let n = 4096;
        let mut rests: Vec<Vec<f64>> = vec![Vec::new(); 5];
        for k in 0..n {
            let (i, _, rest) = c.sample(p, (k as f32 + 0.5) / n as f32);
            rests[i].push(f64::from(rest));
        }
        for (i, r) in rests.iter().enumerate() {
            let step = 1.0 / (f64::from(n) * f64::from(c.pmf(p, i)));
            let mut edges = vec![0.0];
            edges.extend(r);
            edges.push(1.0);
            let widest = edges.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
            assert!(
                r.len() > 10 && widest.is_finite() && widest <= step * 1.001,
                "light {i}: {} values, widest gap {widest} against a step of {step}",
                r.len()
            );
        }
    }

    #[test]
    fn nearer_lights_are_chosen_more_often() {
        let c = veach_like();
        // Below the first light the near light dominates; the far fill light stays low.
        let p = Vec3::new(-3.75, -2.0, 0.0);
        assert!(c.pmf(p, 0) > 0.5, "{}", c.pmf(p, 0));
        assert!(c.pmf(p, 4) < 0.05, "{}", c.pmf(p, 4));
    }

    #[test]
    fn dark_lights_are_never_chosen_and_odd_points_stay_consistent() {
        let c = LightChoice::new(
            &[1.0, 0.0, 3.0],
            &[place(0.0, 0.1), place(1.0, 0.1), place(2.0, 0.0)],
        )
        .unwrap();
        for k in 0..1000 {
            let (i, q, _) = c.sample(Vec3::new(0.5, 0.3, 0.0), k as f32 / 1000.0);
            assert!(i != 1 && q.is_finite() && q > 0.0);
        }
        assert_eq!(c.pmf(Vec3::ZERO, 1), 0.0);
        // At a point light's position the weight is at its largest (power over the radius
        // floor); sampling and density still agree.
        let at = Vec3::new(2.0, 0.0, 0.0);
        let (i, q, _) = c.sample(at, 0.9);
        assert!(q.is_finite() && q > 0.0);
        assert_eq!(q, c.pmf(at, i));
        // A NaN point (f32::max drops the NaN distance, leaving the radius floor) still
        // gives finite probabilities that sampling and density agree on.
        let (i, q, _) = c.sample(Vec3::NAN, 0.5);
        assert!(q.is_finite() && q > 0.0);
        assert_eq!(q, c.pmf(Vec3::NAN, i));
        assert_eq!(c.pmf(Vec3::ZERO, 7), 0.0);
    }

    #[test]
    fn one_light_or_an_unplaced_light_keeps_the_power_choice() {
        assert!(matches!(
            LightChoice::new(&[1.0], &[place(0.0, 1.0)]),
            Some(LightChoice::Power(_))
        ));
        assert!(matches!(
            LightChoice::new(&[1.0, 2.0], &[place(0.0, 1.0), None]),
            Some(LightChoice::Power(_))
        ));
        assert!(LightChoice::new(&[0.0, 0.0], &[place(0.0, 1.0), place(1.0, 1.0)]).is_none());
    }
}

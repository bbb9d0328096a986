//! The f32-against-f64 warp study: for each warp, the error of our f32 sample and pdf in f32
//! ulps against the f64 reference, and nanoseconds per sample of each.

use crate::measure::{ns_per_call, ulps, unit_square_points, ErrorStats};
use crate::naive::{NaiveCone, NaivePowerCosine};
use crate::reference::{self as r, Reference};
use crate::reference_microfacet::{RefBeckmann, RefGgx, RefGgxVisible};
use mcrt::glam::{DVec2, DVec3, Vec2, Vec3};
use mcrt::sampling::warp::{
    Beckmann, CosineHemisphere, Ggx, GgxVisible, PowerCosineHemisphere, ThetaOverSinHemisphere,
    UniformCone, UniformDisk, UniformDiskConcentric, UniformHemisphere, UniformSphere,
    UniformTriangle, Warp,
};

/// A point of a warp's domain seen in f64 (planar points get `z = 0`).
pub trait AsF64: Copy {
    /// The exact f64 value of the point.
    fn as_f64(self) -> DVec3;
}

impl AsF64 for Vec2 {
    fn as_f64(self) -> DVec3 {
        DVec3::new(f64::from(self.x), f64::from(self.y), 0.0)
    }
}

impl AsF64 for Vec3 {
    fn as_f64(self) -> DVec3 {
        self.as_dvec3()
    }
}

/// The coordinate whose *relative* accuracy matters for a warp.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    /// Polar angle θ of a direction (its distance from the pole).
    Theta,
    /// Distance from the disk's centre.
    Radius,
    /// First barycentric coordinate (1 − √u₁, which cancels as u₁ → 1).
    B0,
}

impl Key {
    /// The coordinate's value at `p`.
    pub fn of(self, p: DVec3) -> f64 {
        match self {
            Key::Theta => r::theta(p),
            Key::Radius => p.x.hypot(p.y),
            Key::B0 => p.x,
        }
    }

    /// Its symbol in the tables.
    pub fn name(self) -> &'static str {
        match self {
            Key::Theta => "θ",
            Key::Radius => "r",
            Key::B0 => "b₀",
        }
    }
}

/// How much work the study does.
#[derive(Debug, Clone, Copy)]
pub struct Effort {
    /// Low-discrepancy points (edge points come on top).
    pub points: usize,
    /// Timed runs (the median is reported).
    pub runs: usize,
    /// Sweeps over the timing set per run.
    pub reps: usize,
}

/// Points per timed run: short runs (about 10–50 µs) mostly fit in one scheduler time slice,
/// so on a loaded machine the median over many runs stays close to the unloaded time.
pub const TIMING_POINTS: usize = 1024;

/// One line of the warp table.
#[derive(Debug, Clone)]
pub struct WarpRow {
    /// Warp name (with "naive" for the contrast formulations).
    pub warp: String,
    /// Parameter, or empty.
    pub param: String,
    /// The relative coordinate.
    pub key: Key,
    /// Sample error: max over components, in ulps of the point's largest component.
    pub sample: ErrorStats,
    /// Relative error of the key coordinate, in its own ulps.
    pub key_err: ErrorStats,
    /// Error of the pdf returned with the sample.
    pub pdf: ErrorStats,
    /// Error of `pdf(p)` evaluated at our own f32 point (against f64 at the same point).
    pub pdf_at: ErrorStats,
    /// ns per `sample_with_pdf`, f32.
    pub ns_f32: f64,
    /// ns per reference sample, f64.
    pub ns_f64: f64,
}

/// Errors of one f32 sample against its reference.
fn errors<W: Warp>(w: &W, rf: &impl Reference, key: Key, u: [f32; 2]) -> [f64; 4]
where
    W::Point: AsF64,
{
    let (p, pdf) = w.sample_with_pdf(Vec2::from(u));
    let (q, qpdf) = rf.sample(DVec2::new(f64::from(u[0]), f64::from(u[1])));
    let pd = p.as_f64();
    let scale = q.abs().max_element();
    let sample = (0..3).map(|i| ulps(pd[i], q[i], scale)).fold(0.0, f64::max);
    let (k, kq) = (key.of(pd), key.of(q));
    let at = rf.pdf(pd);
    [
        sample,
        ulps(k, kq, kq),
        ulps(f64::from(pdf), qpdf, qpdf),
        ulps(f64::from(w.pdf(p)), at, at),
    ]
}

/// Measures one warp against its reference.
pub fn measure<W: Warp>(
    warp: &str,
    param: &str,
    key: Key,
    w: &W,
    rf: &impl Reference,
    effort: Effort,
) -> WarpRow
where
    W::Point: AsF64,
{
    let pts = unit_square_points(effort.points);
    let mut cols: [Vec<f64>; 4] = Default::default();
    for &u in &pts {
        for (c, e) in cols.iter_mut().zip(errors(w, rf, key, u)) {
            c.push(e);
        }
    }
    let [s, k, p, a] = cols.map(|mut c| ErrorStats::of(&mut c));
    let timing: Vec<[f32; 2]> = pts.iter().take(TIMING_POINTS).copied().collect();
    let u32s: Vec<Vec2> = timing.iter().map(|&u| Vec2::from(u)).collect();
    let u64s: Vec<DVec2> = u32s.iter().map(|u| u.as_dvec2()).collect();
    WarpRow {
        warp: warp.to_string(),
        param: param.to_string(),
        key,
        sample: s,
        key_err: k,
        pdf: p,
        pdf_at: a,
        ns_f32: ns_per_call(&u32s, effort.runs, effort.reps, |u| w.sample_with_pdf(u)),
        ns_f64: ns_per_call(&u64s, effort.runs, effort.reps, |u| rf.sample(u)),
    }
}

/// Every case of the study, in table order.
pub fn run(effort: Effort) -> Vec<WarpRow> {
    use Key::*;
    let mut rows = vec![
        measure("UniformDisk", "", Radius, &UniformDisk, &r::RefDisk, effort),
        measure(
            "UniformDiskConcentric",
            "",
            Radius,
            &UniformDiskConcentric,
            &r::RefConcentric,
            effort,
        ),
        measure(
            "UniformTriangle",
            "",
            B0,
            &UniformTriangle,
            &r::RefTriangle,
            effort,
        ),
        measure(
            "UniformHemisphere",
            "",
            Theta,
            &UniformHemisphere,
            &r::RefUniformHemisphere,
            effort,
        ),
        measure(
            "CosineHemisphere",
            "",
            Theta,
            &CosineHemisphere,
            &r::RefCosineHemisphere,
            effort,
        ),
        measure(
            "UniformSphere",
            "",
            Theta,
            &UniformSphere,
            &r::RefSphere,
            effort,
        ),
        measure(
            "ThetaOverSinHemisphere",
            "",
            Theta,
            &ThetaOverSinHemisphere,
            &r::RefThetaOverSin,
            effort,
        ),
    ];
    for theta in [1.0f32, 1e-2, 1e-4] {
        let rf = r::RefCone::from_angle(f64::from(theta));
        let param = format!("θmax = {theta:e} rad");
        if let Ok(cone) = UniformCone::from_angle(theta) {
            rows.push(measure("UniformCone", &param, Theta, &cone, &rf, effort));
        }
        let naive = NaiveCone::from_angle(theta);
        rows.push(measure(
            "naive cone (f32 cos θ)",
            &param,
            Theta,
            &naive,
            &rf,
            effort,
        ));
    }
    for n in [10.0f32, 1e3, 1e6] {
        let rf = r::RefPowerCosine { n: f64::from(n) };
        let param = format!("n = {n:e}");
        if let Ok(lobe) = PowerCosineHemisphere::new(n) {
            rows.push(measure(
                "PowerCosineHemisphere",
                &param,
                Theta,
                &lobe,
                &rf,
                effort,
            ));
        }
        let naive = NaivePowerCosine { n };
        rows.push(measure(
            "naive power cosine (powf)",
            &param,
            Theta,
            &naive,
            &rf,
            effort,
        ));
    }
    for alpha in [0.5f32, 1e-3] {
        let param = format!("α = {alpha:e}");
        let a = f64::from(alpha);
        if let Ok(d) = Beckmann::new(alpha) {
            rows.push(measure(
                "Beckmann",
                &param,
                Theta,
                &d,
                &RefBeckmann { alpha: a },
                effort,
            ));
        }
        if let Ok(d) = Ggx::new(alpha) {
            rows.push(measure(
                "Ggx",
                &param,
                Theta,
                &d,
                &RefGgx { alpha: a },
                effort,
            ));
        }
    }
    for (alpha, deg) in [(0.5f32, 60.0f32), (1e-3, 89.0)] {
        let wi = Vec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
        let rf = RefGgxVisible::new(f64::from(alpha), wi.as_dvec3());
        if let Ok(d) = GgxVisible::new(alpha, wi) {
            let param = format!("α = {alpha:e}, θᵢ = {deg}°");
            rows.push(measure("GgxVisible", &param, Theta, &d, &rf, effort));
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    const QUICK: Effort = Effort {
        points: 256,
        runs: 1,
        reps: 1,
    };

    #[test]
    fn accurate_warps_stay_within_a_few_ulps() {
        let row = measure(
            "UniformSphere",
            "",
            Key::Theta,
            &UniformSphere,
            &r::RefSphere,
            QUICK,
        );
        assert!(
            row.sample.max.is_finite() && row.sample.max < 64.0,
            "{row:?}"
        );
        assert!(row.pdf.max.is_finite() && row.pdf.max <= 1.0, "{row:?}");
        assert!(row.ns_f32.is_finite() && row.ns_f32 > 0.0);
    }

    #[test]
    fn the_study_sees_the_naive_cone_fail() {
        let rf = r::RefCone::from_angle(f64::from(1e-4f32));
        let naive = measure(
            "naive",
            "",
            Key::Theta,
            &NaiveCone::from_angle(1e-4),
            &rf,
            QUICK,
        );
        let stable = UniformCone::from_angle(1e-4).expect("valid cone");
        let good = measure("stable", "", Key::Theta, &stable, &rf, QUICK);
        assert!(naive.pdf.max.is_infinite());
        assert!(
            good.key_err.p99.is_finite() && good.key_err.p99 < 16.0,
            "{good:?}"
        );
        assert!(
            naive.key_err.p99 > 1e3 * good.key_err.p99.max(1.0),
            "{naive:?}"
        );
    }
}

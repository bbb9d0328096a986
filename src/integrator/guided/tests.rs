//! What the guided tracer records for the learning of the selection probability.

use super::GuidedPathTracer;
use crate::integrator::test_scene::InsideSphere;
use crate::sampling::guiding::{GuidingRecords, SdTree};
use crate::sampling::sampler::{IndependentSampler, Sampler};
use glam::Vec3;
use std::f32::consts::FRAC_1_PI;

/// Each selection record's integrand is `T·f·|cos θ|·L`: the throughput `T` of the path
/// before the vertex (rebuilt here from the earlier records' `f·|cos|/pdf`, there being no
/// Russian roulette), times the sampled direction's `f·|cos θ|` (Lambertian, albedo ½, the
/// sphere's normal `−p`), times the radiance recorded along it. Without `T` every vertex
/// past the first would be recorded as if it were the first.
#[test]
fn selection_records_weigh_each_vertex_by_the_throughput_before_it() {
    let scene = InsideSphere::new(1.0, 1.0);
    let guide = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    let gpt = GuidedPathTracer {
        max_depth: 6,
        rr_depth: 100,
        ..GuidedPathTracer::default()
    };
    let mut sampler = IndependentSampler::new(64, 3).expect("a valid sampler");
    let (mut checked, mut deep) = (0, 0);
    for s in 0..64 {
        sampler.start_pixel_sample([0, 0], s);
        let dir = Vec3::new(0.3 * (s as f32 / 64.0 - 0.5), 0.2, -1.0).normalize();
        let mut records = GuidingRecords::new();
        gpt.li(
            &scene,
            &guide,
            Vec3::ZERO,
            dir,
            f32::INFINITY,
            &mut sampler,
            Some(&mut records),
        );
        let mut t = 1.0f32;
        for r in records.stored() {
            let sel = r
                .selection
                .expect("every record carries its selection record");
            let cos = r.record.dir.dot(-r.record.p).max(0.0);
            let f_cos = 0.5 * FRAC_1_PI * cos;
            let expected = t * f_cos * r.record.radiance;
            assert!(
                sel.integrand.is_finite() && expected.is_finite(),
                "{sel:?} {expected}"
            );
            assert!(
                (sel.integrand - expected).abs() <= 1e-4 * expected.abs() + 1e-9,
                "integrand {} against T·f·cos·L = {expected} (T = {t})",
                sel.integrand
            );
            checked += 1;
            if (t - 1.0).abs() > 0.1 && expected > 0.0 {
                deep += 1;
            }
            t *= f_cos / r.record.pdf;
        }
    }
    assert!(
        checked > 100 && deep > 50,
        "{checked} records, {deep} with T far from 1"
    );
}

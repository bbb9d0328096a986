//! Every selectable sampler renders the same expected image: the Cornell box (32×32, 16 spp)
//! with each `SamplerKind`, through the path tracer and through BDPT, has an image mean
//! within a few standard errors of the path tracer's with the independent sampler. The
//! standard errors come from the films' per-pixel variances (pixels are independent: each
//! pixel's sample values are scrambled on their own), which overstate a low-discrepancy
//! sampler's error, so the test is conservative for them.

use mcrt::glam::DVec3;
use mcrt_render::description::{IntegratorKind, SamplerKind};
use mcrt_render::render::{RenderOptions, Renderer};
use std::sync::atomic::AtomicBool;

const KINDS: [SamplerKind; 7] = [
    SamplerKind::Independent,
    SamplerKind::Stratified,
    SamplerKind::LowDiscrepancy,
    SamplerKind::Halton,
    SamplerKind::R2,
    SamplerKind::MultiJitter,
    SamplerKind::Sobol,
];

/// The image mean and its variance, per channel.
fn image_mean(kind: SamplerKind, integrator: IntegratorKind, seed: u64) -> (DVec3, DVec3) {
    let scene = mcrt_render::cornell_box::cornell_box_with(16, 32, -1);
    let opts = RenderOptions {
        seed: Some(seed),
        sampler: Some(kind),
        integrator: Some(integrator),
        ..RenderOptions::default()
    };
    let r = Renderer::new(&scene, &opts).expect("scene builds");
    assert_eq!(r.spp(), 16, "{kind:?}");
    let out = r.render(&|_, _| {}, &AtomicBool::new(false));
    let (image, var) = (out.image(), out.film.variance());
    let n = image.len() as f64;
    let mean = image.iter().map(|p| p.as_dvec3()).sum::<DVec3>() / n;
    let var = var.iter().map(|v| v.as_dvec3()).sum::<DVec3>() / (n * n);
    assert!(
        mean.is_finite() && var.is_finite(),
        "{kind:?} {integrator:?}"
    );
    (mean, var)
}

#[test]
fn every_sampler_renders_the_same_expected_image() {
    let (reference, ref_var) = image_mean(SamplerKind::Independent, IntegratorKind::Path, 1);
    assert!(reference.min_element() > 0.01, "{reference}");
    let runs = KINDS.iter().map(|&k| (k, IntegratorKind::Path)).chain(
        [
            SamplerKind::Halton,
            SamplerKind::R2,
            SamplerKind::MultiJitter,
        ]
        .map(|k| (k, IntegratorKind::Bdpt)),
    );
    for (kind, integrator) in runs {
        let (mean, var) = image_mean(kind, integrator, 2);
        let z = (mean - reference) / (var + ref_var).map(f64::sqrt);
        // 10 renders × 3 channels; |z| < 4 is a family-wise false alarm rate below 0.2%.
        assert!(
            z.is_finite() && z.abs().max_element() < 4.0,
            "{kind:?} {integrator:?}: mean {mean} vs {reference}, z {z}"
        );
        assert!(var.max_element() > 0.0, "{kind:?}: no variance");
    }
}

//! The anisotropic microfacet warps of `mcrt::sampling::warp` (`GgxAnisotropic`,
//! `BeckmannAnisotropic` and their visible normals) against their own pdf: chi-square
//! (which includes ∫ pdf = 1) at the suite's settings, 12 runs.

use crate::common;

use common::{chi2, hemisphere};
use mcrt::glam::Vec3;
use mcrt::sampling::warp::*;
use mcrt::stats::{Directions, Domain, StatPoint};

/// Roughness pairs: rough along x, and rough along y.
const PAIRS: [(f32, f32); 2] = [(0.5, 0.1), (0.05, 0.3)];

/// The hemisphere, or a cap 8 × the larger roughness wide about the pole.
fn lobe_domain(au: f32, av: f32) -> Directions {
    let theta = 8.0 * au.max(av);
    if theta >= 1.2 {
        hemisphere()
    } else {
        Directions::cap(Vec3::Z, theta)
            .resolution(61, 64)
            .refinement(1.5)
    }
}

fn incident(theta_deg: f32) -> Vec3 {
    let (s, c) = theta_deg.to_radians().sin_cos();
    let phi = 0.7f32;
    Vec3::new(s * phi.cos(), s * phi.sin(), c)
}

fn run<W, D>(failures: &mut Vec<String>, name: &str, warp: &W, domain: D, samples: usize)
where
    W: Warp + Sync,
    W::Point: StatPoint,
    D: Domain<Point = W::Point>,
{
    let o = chi2(domain, name).samples(samples).run_warp(warp);
    if !o.passed() {
        failures.push(o.report());
    }
}

#[test]
fn anisotropic_microfacet_normals() {
    let mut f = Vec::new();
    for (au, av) in PAIRS {
        let g = GgxAnisotropic::new(au, av).expect("valid alphas");
        let b = BeckmannAnisotropic::new(au, av).expect("valid alphas");
        let d = || lobe_domain(au, av);
        run(
            &mut f,
            &format!("GgxAnisotropic-{au}-{av}"),
            &g,
            d(),
            common::SAMPLES,
        );
        run(
            &mut f,
            &format!("BeckmannAnisotropic-{au}-{av}"),
            &b,
            d(),
            common::SAMPLES,
        );
        for theta in [45.0f32, 80.0] {
            let wi = incident(theta);
            let gv = GgxAnisotropicVisible::new(g, wi).expect("valid");
            let bv = BeckmannAnisotropicVisible::new(b, wi).expect("valid");
            let n = format!("{au}-{av}-{theta}deg");
            run(
                &mut f,
                &format!("GgxAnisotropicVisible-{n}"),
                &gv,
                d(),
                common::SAMPLES,
            );
            // Beckmann visible normals are slow (a Newton inversion): a quarter of the samples.
            let quarter = common::SAMPLES / 4;
            run(
                &mut f,
                &format!("BeckmannAnisotropicVisible-{n}"),
                &bv,
                d(),
                quarter,
            );
        }
    }
    assert!(f.is_empty(), "{} failed:\n{}", f.len(), f.join("\n"));
}

//! Fresnel reflectance of dielectric and conductor interfaces (unpolarised light).

use glam::Vec3;

/// Fresnel reflectance at a dielectric interface of relative index `eta` (inside / outside)
/// for a direction with cosine `cos_i` against the normal (negative: from the inside).
///
/// Returns `(R, cos_t, eta_it, eta_ti)`: the reflectance, the signed cosine of the
/// refracted direction (opposite sign to `cos_i`; 0 under total internal reflection), and
/// the relative indices of the transmitted over the incident side and its inverse.
#[inline]
pub fn fresnel_dielectric(cos_i: f32, eta: f32) -> (f32, f32, f32, f32) {
    let outside = cos_i >= 0.0;
    let eta_it = if outside { eta } else { 1.0 / eta };
    let eta_ti = 1.0 / eta_it;
    let ci = cos_i.abs();
    let ct2 = 1.0 - (1.0 - ci * ci).max(0.0) * eta_ti * eta_ti;
    if ct2 <= 0.0 {
        return (1.0, 0.0, eta_it, eta_ti);
    }
    let ct = ct2.sqrt();
    let rs = (ci - eta_it * ct) / (ci + eta_it * ct);
    let rp = (eta_it * ci - ct) / (eta_it * ci + ct);
    let r = (0.5 * (rs * rs + rp * rp)).clamp(0.0, 1.0);
    (r, if outside { -ct } else { ct }, eta_it, eta_ti)
}

/// Fresnel reflectance of a conductor with complex index `eta + i k` (per RGB channel) for
/// a direction with cosine `cos_i > 0`: the exact expression for unpolarised light (Born and
/// Wolf 1999, "Principles of Optics", 7th ed., section 14.2).
#[inline]
pub fn fresnel_conductor(cos_i: f32, eta: Vec3, k: Vec3) -> Vec3 {
    let c = cos_i.clamp(0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - Vec3::splat(s2);
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).max(Vec3::ZERO);
    let a2b2 = Vec3::new(a2b2.x.sqrt(), a2b2.y.sqrt(), a2b2.z.sqrt());
    let t1 = a2b2 + Vec3::splat(c2);
    let a = (0.5 * (a2b2 + t0)).max(Vec3::ZERO);
    let a = Vec3::new(a.x.sqrt(), a.y.sqrt(), a.z.sqrt());
    let t2 = 2.0 * c * a;
    let rs = (t1 - t2) / (t1 + t2).max(Vec3::splat(1e-30));
    let t3 = c2 * a2b2 + Vec3::splat(s2 * s2);
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4).max(Vec3::splat(1e-30));
    (0.5 * (rs + rp)).clamp(Vec3::ZERO, Vec3::ONE)
}

/// Hemispherical average of the dielectric Fresnel reflectance, `2 ∫₀¹ F(μ, η) μ dμ`, for
/// light arriving at an interface of relative index `eta` (far side over near side) from
/// every direction with a cosine-weighted distribution: the fraction of diffuse light it
/// reflects. Polynomial fits, as Mitsuba 3 evaluates it: for η < 1, Egan and Hilgeman 1973,
/// "Optical Properties of Inhomogeneous Materials", Academic Press; for η ≥ 1, d'Eon and
/// Irving 2011, "A Quantized-Diffusion Model for Rendering Translucent Materials", ACM TOG
/// 30(4) (both within 0.6% for η in [1/2, 2]).
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    if eta < 1.0 {
        -1.4399 * eta * eta + 0.7099 * eta + 0.6681 + 0.0636 / eta
    } else {
        let r = 1.0 / eta;
        let (r2, r3) = (r * r, r * r * r);
        0.919317 - 3.4793 * r + 6.75335 * r2 - 7.80989 * r3 + 4.98554 * r2 * r2 - 1.36881 * r2 * r3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dielectric_normal_incidence_and_tir() {
        let (r, ct, eit, eti) = fresnel_dielectric(1.0, 1.5);
        let want = (0.5f32 / 2.5).powi(2);
        assert!(r.is_finite() && (r - want).abs() < 1e-6);
        assert!((ct + 1.0).abs() < 1e-6 && eit == 1.5 && (eti - 1.0 / 1.5).abs() < 1e-7);
        // From inside at a grazing angle: total internal reflection.
        let (r, ct, _, _) = fresnel_dielectric(-0.1, 1.5);
        assert_eq!((r, ct), (1.0, 0.0));
        // Same reflectance from both sides at corresponding angles.
        let (r1, ct1, _, _) = fresnel_dielectric(0.8, 1.5);
        let (r2, _, _, _) = fresnel_dielectric(ct1, 1.5);
        assert!(r1.is_finite() && (r1 - r2).abs() < 1e-5);
    }

    #[test]
    fn conductor_matches_dielectric_when_k_is_zero() {
        for c in [1.0f32, 0.7, 0.3, 0.05] {
            let rc = fresnel_conductor(c, Vec3::splat(1.5), Vec3::ZERO);
            let (rd, _, _, _) = fresnel_dielectric(c, 1.5);
            assert!(
                rc.x.is_finite() && (rc.x - rd).abs() < 1e-4,
                "{c}: {rc} vs {rd}"
            );
        }
        // Gold-like values reflect strongly, and everything reflects fully at grazing angles.
        let au = fresnel_conductor(
            1.0,
            Vec3::new(0.143, 0.374, 1.442),
            Vec3::new(3.98, 2.38, 1.6),
        );
        assert!(au.x > 0.9 && au.z < au.x);
        let g = fresnel_conductor(0.0, Vec3::splat(0.2), Vec3::splat(3.0));
        assert!((g - Vec3::ONE).abs().max_element() < 1e-4);
    }

    #[test]
    fn diffuse_reflectance_fits_match_the_integral() {
        // Mitsuba 3.9.1 prints fdr_int = 0.590479, fdr_ext = 0.090239 for plastic's
        // default η = 1.49 / 1.000277; the fits agree with a midpoint rule of the integral.
        let eta = 1.49f32 / 1.000277;
        let (int, ext) = (
            fresnel_diffuse_reflectance(1.0 / eta),
            fresnel_diffuse_reflectance(eta),
        );
        assert!(int.is_finite() && (int - 0.590479).abs() < 1e-5, "{int}");
        assert!(ext.is_finite() && (ext - 0.090239).abs() < 1e-5, "{ext}");
        for e in [0.7f32, 1.0 / 1.33, 1.33, 1.5, 2.0] {
            let n = 20000;
            let integral: f64 = (0..n)
                .map(|i| {
                    let mu = (i as f32 + 0.5) / n as f32;
                    2.0 * f64::from(fresnel_dielectric(mu, e).0 * mu) / f64::from(n)
                })
                .sum();
            let fit = f64::from(fresnel_diffuse_reflectance(e));
            assert!(
                (fit - integral).abs() <= 0.006 * integral,
                "{e}: {fit} vs {integral}"
            );
        }
    }
}

//! Our BSDFs against Mitsuba 3's own values: `tests/data/mitsuba-bsdf-values.txt`, written
//! by `scripts/mitsuba_bsdf_values.py` from Mitsuba 3.9.1 (`scalar_rgb`), holds for each
//! case a `<bsdf>` element, which both renderers load from the same text, Mitsuba's `eval`
//! (radiance and importance transport) and `pdf` at about 5000 pairs of directions (eleven
//! of the cases are `principled`), and the
//! Dirac components' sampled direction, probability, weight and relative index.
//!
//! Tolerances (errors relative to the largest value at that `wo` plus the value itself;
//! the worst found when written, printed with `--nocapture`, in brackets):
//! - `eval` (radiance and importance) 10⁻³ [4·10⁻⁷ for everything except rough plastic
//!   and principled, 2.3·10⁻⁶ for principled's clearcoat],
//!   and 2·10⁻³ for rough plastic [5.4·10⁻⁴], whose diffuse part holds transmittance and
//!   internal-reflectance tables that both renderers integrate numerically by their own
//!   rules;
//! - `pdf` 10⁻³ [1.5·10⁻⁶ GGX], except 3·10⁻³ for Beckmann [1.25·10⁻³]: our visible-normal
//!   density uses the exact Smith Λ (so it integrates to 1), Mitsuba's the rational fit of
//!   Walter et al. 2007;
//! - Dirac samples: direction to 10⁻⁵, probability and weight to 10⁻⁴ relative.

use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::Bsdf;
use mcrt_render::bsdf::{AnyBsdf, Sided};
use mcrt_render::description::BsdfDesc;
use mcrt_render::loader::parse_scene;
use std::path::PathBuf;

struct Case {
    name: String,
    bsdf: Sided<AnyBsdf>,
    evals: Vec<[f32; 10]>,
    importance: Vec<bool>,
    samples: Vec<[f32; 12]>,
}

fn nums<const N: usize>(words: &[&str]) -> [f32; N] {
    assert_eq!(words.len(), N, "malformed line {words:?}");
    let mut out = [0.0; N];
    for (o, w) in out.iter_mut().zip(words) {
        *o = w.parse().expect("a number");
    }
    out
}

/// The scene with a `principled` case's `anisotropic` value taken out, and that value. The
/// loader refuses anisotropy (its lobe would turn on shapes: our shading tangent is not
/// Mitsuba's `dp/du`), but the BSDF in its local frame is Mitsuba's, anisotropy included, so
/// the value goes into the description directly.
fn without_anisotropy(scene: &str) -> (String, Option<f32>) {
    const KEY: &str = r#"<float name="anisotropic" value=""#;
    let Some(at) = scene.find(KEY) else {
        return (scene.to_string(), None);
    };
    let rest = &scene[at + KEY.len()..];
    let end = rest.find('"').expect("a closing quote");
    let value: f32 = rest[..end].parse().expect("a number");
    let close = rest.find("/>").expect("a closed element") + 2;
    let scene = format!("{}{}", &scene[..at], &rest[close..]);
    (scene, Some(value))
}

fn load_cases() -> Vec<Case> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/mitsuba-bsdf-values.txt");
    let text = std::fs::read_to_string(&path).expect("reference values");
    let mut cases: Vec<Case> = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        if let Some(rest) = line.strip_prefix("case ") {
            let (name, xml) = rest.split_once(" | ").expect("case NAME | XML");
            let scene =
                format!(r#"<scene version="3.0.0"><shape type="sphere">{xml}</shape></scene>"#);
            let (scene, anisotropic) = without_anisotropy(&scene);
            let mut desc = parse_scene(&scene, None, &[]).expect("our loader reads the case");
            if let Some(a) = anisotropic {
                let anisotropic = |s: &mut mcrt_render::description::ShapeDesc| {
                    if let BsdfDesc::Principled(p) = &mut s.bsdf {
                        p.anisotropic = a;
                    }
                };
                desc.shapes[0] = desc.shapes[0].clone().changed(anisotropic).unwrap();
            }
            let bsdf = AnyBsdf::from_desc(&desc.shapes[0].bsdf).expect("valid BSDF");
            cases.push(Case {
                name: name.to_string(),
                bsdf,
                evals: Vec::new(),
                importance: Vec::new(),
                samples: Vec::new(),
            });
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        let case = cases.last_mut().expect("a case first");
        match words[0] {
            "e" => {
                case.importance.push(words[1] == "i");
                case.evals.push(nums(&words[2..]));
            }
            "s" => case.samples.push(nums(&words[1..])),
            other => panic!("unknown line kind {other}"),
        }
    }
    assert!(cases.len() >= 10, "only {} cases", cases.len());
    cases
}

/// (eval, pdf) relative tolerances of a case.
fn tolerances(name: &str) -> (f32, f32) {
    let beckmann = !name.contains("ggx") && name.starts_with("rough");
    let eval = if name.starts_with("roughplastic") {
        2e-3
    } else {
        1e-3
    };
    (eval, if beckmann { 3e-3 } else { 1e-3 })
}

#[test]
fn eval_and_pdf_match_mitsuba() {
    for case in load_cases() {
        let (tol_f, tol_p) = tolerances(&case.name);
        // The scale of each wo's values, for the absolute part of the tolerance.
        let scale = |wo: Vec3, pdf: bool| {
            case.evals
                .iter()
                .filter(|r| Vec3::new(r[0], r[1], r[2]) == wo)
                .map(|r| if pdf { r[9] } else { r[6].max(r[7]).max(r[8]) })
                .fold(0.0f32, f32::max)
        };
        let (mut worst_f, mut worst_p) = (0.0f32, 0.0f32);
        for (r, &importance) in case.evals.iter().zip(&case.importance) {
            let wo = Vec3::new(r[0], r[1], r[2]);
            let wi = Vec3::new(r[3], r[4], r[5]);
            let want_f = Vec3::new(r[6], r[7], r[8]);
            let (f, pdf) = if importance {
                (case.bsdf.eval_adjoint(wo, wi), case.bsdf.pdf(wo, wi))
            } else {
                case.bsdf.eval_pdf(wo, wi)
            };
            assert!(f.is_finite() && pdf.is_finite(), "{}: {wo} {wi}", case.name);
            let err_f = ((f - want_f).abs().max_element())
                / (scale(wo, false) + want_f.max_element()).max(1e-12);
            let err_p = (pdf - r[9]).abs() / (scale(wo, true) + r[9]).max(1e-12);
            worst_f = worst_f.max(err_f);
            worst_p = worst_p.max(err_p);
            assert!(
                err_f <= tol_f && err_p <= tol_p,
                "{} ({}) wo {wo} wi {wi}: f {f} vs {want_f}, pdf {pdf} vs {}",
                case.name,
                if importance { "importance" } else { "radiance" },
                r[9]
            );
        }
        println!(
            "{}: {} pairs, worst eval {:.2e}, worst pdf {:.2e}",
            case.name,
            case.evals.len(),
            worst_f,
            worst_p
        );
    }
}

#[test]
fn dirac_samples_match_mitsuba() {
    let mut n = 0;
    for case in load_cases() {
        for r in &case.samples {
            let wo = Vec3::new(r[0], r[1], r[2]);
            let s = case
                .bsdf
                .sample(wo, r[3], Vec2::splat(0.5))
                .unwrap_or_else(|| panic!("{}: no sample at {wo}", case.name));
            let want_wi = Vec3::new(r[4], r[5], r[6]);
            let want_w = Vec3::new(r[8], r[9], r[10]);
            let ok = s.delta
                && (s.wi - want_wi).abs().max_element() < 1e-5
                && (s.pdf - r[7]).abs() <= 1e-4 * r[7]
                && (s.weight - want_w).abs().max_element() <= 1e-4 * want_w.max_element()
                && (s.eta - r[11]).abs() <= 1e-5;
            assert!(
                ok,
                "{} wo {wo} u1 {}: ours {s:?}, Mitsuba wi {want_wi} pdf {} weight {want_w} eta {}",
                case.name, r[3], r[7], r[11]
            );
            n += 1;
        }
    }
    assert!(n >= 40, "only {n} Dirac samples compared");
}

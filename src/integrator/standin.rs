//! Temporary stand-ins for dependencies that have not landed yet (deleted when they do).

/// Balance heuristic (stand-in for `crate::sampling::mis`).
pub(crate) fn balance_heuristic(nf: f32, pf: f32, ng: f32, pg: f32) -> f32 {
    let (f, g) = (nf * pf, ng * pg);
    if f.is_infinite() {
        return 1.0;
    }
    if !(f > 0.0) {
        return 0.0;
    }
    (f / (f + g)).clamp(0.0, 1.0)
}

/// Power heuristic, β = 2 (stand-in for `crate::sampling::mis`).
pub(crate) fn power_heuristic(nf: f32, pf: f32, ng: f32, pg: f32) -> f32 {
    let (f, g) = (nf * pf, ng * pg);
    if f.is_infinite() {
        return 1.0;
    }
    if !(f > 0.0) {
        return 0.0;
    }
    let r = g / f;
    (1.0 / (1.0 + r * r)).clamp(0.0, 1.0)
}

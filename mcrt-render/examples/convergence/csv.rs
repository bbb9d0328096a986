//! The rendering study's results as CSV, so that a later run can rebuild the report without
//! rendering again.

use crate::render_study::RenderPoint;

/// Header line.
const HEADER: &str = "scene,strategy,sampler,spp,seconds,rel_mse";
/// Header line of the integrator study, whose second column names the integrator.
pub const INTEGRATOR_HEADER: &str = "scene,integrator,sampler,spp,seconds,rel_mse";

/// Formats the points, one line each after the header.
pub fn write(points: &[RenderPoint]) -> String {
    write_with(HEADER, points)
}

/// Parses what [`write`] wrote.
pub fn read(text: &str) -> Result<Vec<RenderPoint>, String> {
    read_with(HEADER, text)
}

/// Formats the points under `header`.
pub fn write_with(header: &str, points: &[RenderPoint]) -> String {
    let mut s = format!("{header}\n");
    for p in points {
        s += &format!(
            "{},{},{},{},{:e},{:e}\n",
            p.scene, p.strategy, p.sampler, p.spp, p.seconds, p.rel_mse
        );
    }
    s
}

/// Parses what [`write_with`] wrote under `header`.
pub fn read_with(header: &str, text: &str) -> Result<Vec<RenderPoint>, String> {
    let mut lines = text.lines();
    if lines.next() != Some(header) {
        return Err("not a convergence render CSV".into());
    }
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let bad = || format!("bad line: {l}");
            if f.len() != 6 {
                return Err(bad());
            }
            Ok(RenderPoint {
                scene: f[0].into(),
                strategy: f[1].into(),
                sampler: f[2].into(),
                spp: f[3].parse().map_err(|_| bad())?,
                seconds: f[4].parse().map_err(|_| bad())?,
                rel_mse: f[5].parse().map_err(|_| bad())?,
            })
        })
        .collect()
}

/// `earlier` with every point that `new` measures again replaced, then the new points.
pub fn merge(earlier: Vec<RenderPoint>, new: &[RenderPoint]) -> Vec<RenderPoint> {
    let key = |p: &RenderPoint| {
        (
            p.scene.clone(),
            p.strategy.clone(),
            p.sampler.clone(),
            p.spp,
        )
    };
    let mut out: Vec<RenderPoint> = earlier
        .into_iter()
        .filter(|o| !new.iter().any(|n| key(n) == key(o)))
        .collect();
    out.extend_from_slice(new);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip() {
        let p = RenderPoint {
            scene: "veach-mis".into(),
            strategy: "power".into(),
            sampler: "sobol".into(),
            spp: 64,
            seconds: 1.25,
            rel_mse: 3.5e-3,
        };
        let text = write(&[p.clone(), p.clone()]);
        assert_eq!(read(&text), Ok(vec![p.clone(), p.clone()]));
        assert!(read("nope\n").is_err());
        let mut newer = p.clone();
        newer.rel_mse = 1.0;
        let mut other = p.clone();
        other.spp = 256;
        let merged = merge(vec![p.clone(), other.clone()], std::slice::from_ref(&newer));
        assert_eq!(merged, vec![other, newer]);
        assert!(read(&format!("{HEADER}\na,b,c,x,1,2\n")).is_err());
        let text = write_with(INTEGRATOR_HEADER, std::slice::from_ref(&p));
        assert!(read(&text).is_err());
        assert_eq!(read_with(INTEGRATOR_HEADER, &text), Ok(vec![p]));
    }
}

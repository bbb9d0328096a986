//! Prints a few samples of some warps with their pdfs and the inverse of each sample.
//!
//! `cargo run --example samples`

use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::{
    CosineHemisphere, InvertibleWarp, PowerCosineHemisphere, ThetaOverSinHemisphere, UniformCone,
    UniformDiskConcentric, UniformTriangle,
};

/// A few fixed points of the unit square, edges included.
const US: [(f32, f32); 4] = [(0.0, 0.0), (0.25, 0.5), (0.5, 0.75), (0.9, 0.1)];

/// Prints a point's coordinates in scientific notation, so tiny cones stay readable.
trait Coords {
    fn coords(&self) -> String;
}

impl Coords for Vec2 {
    fn coords(&self) -> String {
        format!("({:>11.4e}, {:>11.4e})", self.x, self.y)
    }
}

impl Coords for Vec3 {
    fn coords(&self) -> String {
        format!("({:>11.4e}, {:>11.4e}, {:>11.4e})", self.x, self.y, self.z)
    }
}

fn show<W: InvertibleWarp>(name: &str, warp: &W)
where
    W::Point: Coords,
{
    println!("{name}");
    for (a, b) in US {
        let u = Vec2::new(a, b);
        let (p, pdf) = warp.sample_with_pdf(u);
        let back = warp.invert(p);
        println!(
            "  u = ({a:.2}, {b:.2}) -> {}  pdf = {pdf:<11.5e} invert = ({:.6}, {:.6})",
            p.coords(),
            back.x,
            back.y
        );
    }
}

fn main() -> Result<(), mcrt::sampling::SamplingError> {
    println!("mcrt warps: u in [0,1)^2 -> point, its pdf, and the inverse of the point\n");
    show(
        "UniformDiskConcentric (pdf per unit area)",
        &UniformDiskConcentric,
    );
    show(
        "UniformTriangle (barycentrics, pdf per unit barycentric area)",
        &UniformTriangle,
    );
    show("CosineHemisphere (pdf per steradian)", &CosineHemisphere);
    show(
        "UniformCone, half-angle 1e-4 rad (pdf per steradian)",
        &UniformCone::from_angle(1e-4)?,
    );
    show(
        "PowerCosineHemisphere, exponent 1e6 (pdf per steradian)",
        &PowerCosineHemisphere::new(1e6)?,
    );
    show(
        "ThetaOverSinHemisphere (pdf per steradian)",
        &ThetaOverSinHemisphere,
    );
    Ok(())
}

//! The polygon-offset resolvable difference `r` per format (`resolvable`, D32F per band).

use super::*;

/// The `units` of every offset draw: one value, because a rasterizer may compile a variant per
/// value (llvmpipe does). Up to 4 quanta per unit it keeps D16 below window depth 1 (2^12 × 4 /
/// 65535 ≈ 0.25 above 0.45), and it moves D32 by 2^-20 or more, 30× its f32 pipeline's noise.
pub(super) const OFFSET_UNITS: f32 = 4096.0;

/// `r` in quanta (module docs): a quad covering the viewport, window depth `lo` to `hi` across x.
pub(super) unsafe fn resolvable(gl: &Gl, o: &Objects, format: Format) -> Result<Vec<f64>> {
    let bands: &[(f64, f64)] = match format {
        Format::Unorm(_) => &[(0.40, 0.45)],
        Format::Float => &[(0.40, 0.45), (0.050, 0.055)],
    };
    let mut r = Vec::new();
    for &(lo, hi) in bands {
        let z = |w: f64| (2.0 * w - 1.0) as f32;
        let (a, b) = (z(lo), z(hi));
        let quad = Scene::clip(vec![
            [
                [-1.0, -1.0, a, 1.0],
                [1.0, -1.0, b, 1.0],
                [1.0, 1.0, b, 1.0],
            ],
            [
                [-1.0, -1.0, a, 1.0],
                [1.0, 1.0, b, 1.0],
                [-1.0, 1.0, a, 1.0],
            ],
        ]);
        // The unit is the quantum at the primitive's largest depth (for D32F, `2^(e − 23)`).
        let unit = format.quantum(0.5 * b as f64 + 0.5);
        let plain = draw(gl, o, format, &quad)?;
        (gl.Enable)(POLYGON_OFFSET_FILL);
        (gl.PolygonOffset)(0.0, OFFSET_UNITS);
        let offset = draw(gl, o, format, &quad);
        (gl.Disable)(POLYGON_OFFSET_FILL);
        let offset = offset?;
        let sum: f64 = offset.iter().zip(&plain).map(|(o, p)| o - p).sum();
        let mean = sum / plain.len() as f64;
        r.push(mean / OFFSET_UNITS as f64 / unit);
    }
    Ok(r)
}

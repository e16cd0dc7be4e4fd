//! The term `V`: f32 rounding of the vertices before the projection.
//!
//! Base and decal are different meshes: their vertices are rounded independently, and each
//! rounding moves a vertex off the exact common plane. How far depth moves at a pixel follows
//! from the plane's form `L` ([`crate::model::plane_form`]): the pixel's NDC depth error is
//! `Σ μᵢ·L(eᵢ)/d`, `eᵢ` the clip-space error of vertex `i`.
//!
//! # Eye-space vertices ([`eye_rounding`])
//! Each eye coordinate is rounded once, `|δpₖ| ≤ u·|pₖ|` (`u = 2⁻²⁴`), so
//! `|L(P·δp)| ≤ u·Σₖ |gₖ|·|pₖ|` with `g = L∘P` on eye coordinates. A vertex inside the frustum
//! has `|x| ≤ eₓ·w`, `|y| ≤ e_y·w`, `|z| = w` (`eₓ = max(|l|, |r|)/n`, `e_y = max(|b|, |t|)/n`),
//! so `|L(eᵢ)| ≤ K·wᵢ` with `K = u·(|gₓ|·eₓ + |g_y|·e_y + |g_z|)`, and at every pixel
//! `Σ μᵢ·|L(eᵢ)|/d ≤ K·Σ μᵢ·wᵢ/d = K`: the bound holds for any mesh inside the frustum, however
//! far its vertices, and for planes that contain the view direction (where `g` is finite and
//! the eye-space slope is not).
//!
//! # World-space vertices through an f32 model-view matrix ([`world_rounding`])
//! With vertices in world space (magnitude at most `W`, the camera's position too) and a rigid
//! model-view `[R | t]`, an eye coordinate is `Σⱼ Rₖⱼ·pⱼ + tₖ`, whose terms sum to at most
//! `A = 2√3·W` in magnitude (a rotation row has `‖Rₖ‖₁ ≤ √3`, and `|tₖ| = |Rₖ·camera| ≤ √3·W`).
//! Every rounding of the transform is relative to that magnitude, not to the vertex's distance
//! from the camera, so the clip coordinate `k` of a vertex errs by at most `γ_W·Bₖ`,
//! `Bₖ = Σᵢ₍₃₎ |Pₖᵢ|·A + |Pₖ₃|`, with `γ_W = 14u` counted on the costlier of the two ways
//! engines compute it:
//!
//! * `P·(MV·p)` in the shader: `p` stored as f32 (1), `MV`'s elements stored as f32 (1), the
//!   product `MV·p` (three products and three sums, 4 at most per coordinate with the
//!   first product exact-or-rounded: 4), the product `P·eye` (4): `10u`;
//! * `(P·MV)·p` (one MVP uniform, or GLSL's left-to-right `proj * view * model * v`): `p` (1),
//!   `MV` (4 for the product of model and view, when they are separate), `P·MV` (4), its
//!   storage as f32 (1), the product with `p` (4): `14u`.
//!
//! For a pixel at eye depth `d ≥ d₁` of the decal the error is at most `L(γ_W·B)/d₁`: it does
//! not shrink with the vertices' distance, and it grows with `W` — which is what camera-relative
//! rendering (vertices sent relative to the camera, `W` small) removes.

use super::PlaneForm;

/// `u = 2⁻²⁴`, the unit roundoff of f32.
const U: f64 = 1.0 / 16_777_216.0;

/// `γ_W`: the roundings of a world-space vertex through the f32 model-view-projection, in
/// units of the magnitude `Bₖ` (module docs).
pub(crate) const WORLD_ROUNDINGS: f64 = 14.0;

/// The NDC depth error at any pixel of a mesh inside the frustum from rounding its eye
/// coordinates to f32: `K = u·(|gₓ|·eₓ + |g_y|·e_y + |g_z|)`, `g = form.on_eye(m)`, `tangents`
/// `= (eₓ, e_y)` the frustum's largest half-extent tangents (module docs).
pub fn eye_rounding(form: &PlaneForm, m: &[f64; 16], tangents: [f64; 2]) -> f64 {
    let g = form.on_eye(m);
    U * (g[0].abs() * tangents[0] + g[1].abs() * tangents[1] + g[2].abs())
}

/// The magnitude bound `Bₖ` of each clip coordinate of a world-space vertex (module docs):
/// `Σᵢ₍₃₎ |Pₖᵢ|·2√3·W + |Pₖ₃|` for `k = x, y, z, w`.
pub fn world_magnitudes(m: &[f64; 16], world_reach: f64) -> [f64; 4] {
    let a = 2.0 * 3f64.sqrt() * world_reach;
    [0, 1, 2, 3].map(|row| {
        (0..3).map(|col| m[4 * col + row].abs()).sum::<f64>() * a + m[12 + row].abs()
    })
}

/// The NDC depth error at a pixel of eye depth `d ≥ nearest` from the f32 transform of
/// world-space vertices of magnitude `world_reach`: `|L|(γ_W·B)/nearest` (module docs). `form`
/// may hold bounds on the magnitudes of the plane's coefficients (only their sizes are used).
pub fn world_rounding(form: &PlaneForm, m: &[f64; 16], world_reach: f64, nearest: f64) -> f64 {
    let b = world_magnitudes(m, world_reach);
    WORLD_ROUNDINGS * U * form.bound(b) / nearest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::projection::{projection_f64, ClipDepth, Frustum};

    /// The eye-rounding bound holds for perturbed vertices of a plane anywhere in the frustum:
    /// each coordinate moved by its full `u·|p|` in the worst direction moves NDC depth at the
    /// vertex, times `w/d` ≤ 1, by at most `K` (checked in f64 against the exact depths).
    #[test]
    fn eye_rounding_bounds_each_vertex() {
        let frustum = Frustum::new(-0.12, 0.08, -0.05, 0.07, 0.1, 500.0).unwrap();
        let m = projection_f64(&frustum, ClipDepth::NegOneToOne).unwrap();
        // The plane z = −3 + 0.4x − 2y seen in 300×200.
        let on = |x: f64, y: f64| [x, y, -3.0 + 0.4 * x - 2.0 * y];
        let corners = [on(-0.5, -0.2), on(0.5, -0.2), on(0.5, 0.3), on(-0.5, 0.3)]
            .map(|p| glam::Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32));
        let shape =
            crate::footprint::decal_shape(&frustum, ClipDepth::NegOneToOne, [300, 200], &corners)
                .unwrap();
        let form = PlaneForm::of_footprint(&shape.footprint, [300, 200], ClipDepth::NegOneToOne);
        let k = eye_rounding(&form, &m, [0.12 / 0.1, 0.07 / 0.1]);
        let clip = |p: [f64; 3]| -> [f64; 4] {
            [0, 1, 2, 3].map(|r| m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r])
        };
        let mut worst: f64 = 0.0;
        for p in [on(0.1, 0.05), on(-2.0, -1.0), on(30.0, 20.0), on(-0.3, 0.9)] {
            let c = clip(p);
            if c[3] < 0.1 || c[0].abs() > c[3] || c[1].abs() > c[3] {
                continue; // outside the frustum: not what the bound covers
            }
            for signs in 0..8 {
                let s = |i: u32| if signs >> i & 1 == 1 { 1.0 } else { -1.0 };
                let q = [0, 1, 2].map(|i| p[i] * (1.0 + s(i as u32) * U));
                let e: Vec<f64> = clip(q).iter().zip(c).map(|(a, b)| a - b).collect();
                let l = e[2] - form.ax * e[0] - form.ay * e[1] - form.a0 * e[3];
                worst = worst.max(l.abs() / c[3]);
            }
        }
        assert!(worst > 0.0 && worst <= k * (1.0 + 1e-6), "{worst} > {k}");
        assert!(worst > 0.2 * k, "the bound is not loose by more than 5x here: {worst} vs {k}");
    }
}

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
//! Engines keep vertices in world (or model) space and transform them on the GPU. With the
//! camera's position and every model's origin within `W` of the world origin (each
//! coordinate), a rigid view `[R | t]` (`t = −R·camera`) and rigid model matrices, the terms an
//! eye coordinate `k` sums have magnitude at most
//!
//! `A = √3·(4W + |p − camera|)`:
//!
//! a rotation row has `‖Rₖ‖₁ ≤ √3`; a world vertex has coordinates up to `W + |p − camera|`,
//! the translation `|tₖ| ≤ √3·W`; through a model matrix `V·M` the object-space coordinates
//! are up to `2W + |p − camera|` and `V·M`'s translation up to `2√3·W`. A vertex inside the
//! frustum has `|p − camera| ≤ ρ·w`, `ρ = √(1 + eₓ² + e_y²)`. Every rounding of the transform
//! is relative to those magnitudes, not to the vertex's distance from the camera, so each clip
//! coordinate `k` errs by at most `γ_W·Bₖ`, `Bₖ = Σᵢ₍₃₎ |Pₖᵢ|·A + |Pₖ₃|`, independently (no
//! cancellation between `z_c` and `w_c` is assumed), with `γ_W = 14u` counted on the costlier
//! of the two ways engines compute it:
//!
//! * `P·(MV·p)` in the shader: `p` stored as f32 (1), `MV`'s elements stored as f32 (1), the
//!   product `MV·p` (three products and three sums: 4 on the longest path), the product
//!   `P·eye` (4): `10u`;
//! * `(P·MV)·p` (one MVP uniform, or GLSL's left-to-right `proj * view * model * v`): `p` (1),
//!   `V·M` (4), `P·MV` (4), its storage as f32 (1), the product with `p` (4): `14u`;
//! * `VP·(M·q)` (one view-projection applied to the world position the shader computes, bevy's
//!   `clip_from_world`, Unity's `UNITY_MATRIX_VP`): `q` and `M` stored (1 each), `M·q` (4),
//!   `P·V` in f32 (2: each row of a perspective `P` has at most two nonzero elements), the
//!   product with the world position (4): `12u`, within `γ_W`. Its magnitudes are those of the
//!   world position, at most `Aₖ` of a box reaching each model's `|origin| + extent`
//!   (`tests/gl_engine_scene.rs` draws it beside the eye-first shader).
//!
//! With the eye position computed first ([`crate::model::Pipeline::eye_first`]) the error is an
//! eye-space vector `δp` with `|δpₖ| ≤ γ_E·A`, `γ_E = 6u`: the first way above less the
//! projection's own four roundings, which are relative to the eye position's own magnitudes
//! and which the transform term `T` counts, as it does for eye-space vertices (`p` stored (1),
//! `MV`'s elements stored (1, kept: base and decal may be drawn with model-view matrices of
//! their own), `MV·p` (4)). It
//! reaches depth through the form on eye coordinates `g = L∘P`, as eye rounding does:
//! `|L(P·δp)| ≤ γ_E·A·(|gₓ| + |g_y| + |g_z|)`. A move along the plane costs nothing (level
//! ground only feels an error of eye `y`), so this is far smaller than the independent clip
//! errors of one combined matrix.
//!
//! **With the engine's matrices.** Knowing the view (or model-view) matrix `V` the shader
//! applies and the box `[lo, hi]` of the positions it maps
//! ([`crate::model::Pipeline::view`], [`crate::model::Pipeline::world_box`]), the magnitudes
//! are exact per eye coordinate: `Aₖ = Σⱼ |Vₖⱼ|·max(|loⱼ|, |hiⱼ|) + |Vₖ₃|`. Level ground
//! (world `y = 0`) under a level camera has `A_y = |V₁₃|`, the camera's height, however large
//! the ground and far the camera from the origin: the error off the ground stays small where
//! the scalar bound must assume the worst rotation.
//!
//! **A model through its own model matrix** (a decal entity, a terrain chunk). Engines draw a
//! decal as a unit quad and a terrain chunk in local coordinates `q`, through an f32 model
//! matrix `M` (origin `t`), the shader's matrix the model-view `V·M` multiplied on the CPU.
//! Multiplied in double and rounded once, each element of `V·M` errs by `u` of itself (the `1`
//! of "elements stored"), and the shader's product `(V·M)·q` sums magnitudes
//! `|(V·M)ₖ₃| + Σᵢ |(V·M)ₖᵢ|·|qᵢ| ≤ Σⱼ |Vₖⱼ|·(|tⱼ| + eⱼ) + |Vₖ₃|`, `eⱼ = Σᵢ |Mⱼᵢ|·|qᵢ|` the
//! model's extent along world axis `j`: at most `Aₖ` of a box that reaches `|tⱼ| + eⱼ` on each
//! axis (for a model centred on its origin, a box that holds its world corners). `M`'s own
//! rounding moves the model as rounding `p` does (the `1` of "`p` stored"). So `γ_E = 6u` with
//! the camera's `V` and such a box holds. Multiplied in f32 (`glm::mat4`), the product adds its
//! own four roundings of magnitudes `|V|·|M|`, which only the scalar bound's larger magnitudes
//! (`4W`, through a model matrix) cover: pass `world_reach` there (`tests/gl_engine_scene.rs`
//! draws both ways, for decal entities and terrain chunks).
//!
//! `A` splits into a part that does not shrink with distance, `4√3·W`, and one proportional to
//! `w`, `√3·ρ·w`. Through the form, the first gives at most `L(γ_W·B(4√3·W))/d₁` at a pixel of
//! depth `d ≥ d₁` (the weights `μᵢ` sum to 1), the second at most `L(γ_W·B'(√3·ρ))` (the
//! weights `μᵢ·wᵢ/d` sum to 1; `B'` without the translation column). Camera-relative rendering
//! (vertices sent relative to the camera, `W` about the scene's own size) removes the first.

use super::F32_UNIT_ROUNDOFF as U;
use super::{Pipeline, PlaneForm};

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

/// The window-depth error from rounding eye coordinates to f32 without the plane's form: a
/// plane of eye-space slope `slope` crossing the view axis at `d₁` or beyond, rounding z moves
/// depth by `u·d`, rounding x or y moves a point of the plane by `s·u·|x|`, `|x| ≤ e·d` inside
/// the frustum; through `dw/dd = b/d²`: `V = u·(b/d₁)·(1 + s·e)` (`b` the mapping's scale, `e`
/// the frustum's largest half-extent tangent, [`crate::model::gradient`]).
pub(crate) fn eye_rounding_bound(b: f64, d1: f64, slope: f64, e: f64) -> f64 {
    U * (b / d1) * (1.0 + slope * e)
}

/// `γ_E`: the roundings of a world-space vertex through an f32 model-view matrix when the eye
/// position is computed first (module docs), in units of the magnitude `A`.
pub(crate) const EYE_FIRST_ROUNDINGS: f64 = 6.0;

/// The magnitudes `Aₖ` of the terms each eye coordinate `k` sums, for a vertex within `extent`
/// of the camera: with the engine's view matrix `V` and the box of the vertices it maps,
/// `Σⱼ |Vₖⱼ|·max(|loⱼ|, |hiⱼ|) + |Vₖ₃|` exactly (whatever the extent); else, from the scalar
/// `world_reach` `W`, `√3·(4W + extent)` (module docs).
pub fn eye_magnitudes(pipeline: &Pipeline, extent: f64) -> [f64; 3] {
    match (pipeline.view, pipeline.world_box) {
        (Some(v), Some([lo, hi])) => [0, 1, 2].map(|k| {
            (0..3)
                .map(|j| f64::from(v[4 * j + k]).abs() * lo[j].abs().max(hi[j].abs()))
                .sum::<f64>()
                + f64::from(v[12 + k]).abs()
        }),
        _ => [3f64.sqrt() * (4.0 * pipeline.world_reach + extent); 3],
    }
}

/// For a vertex within `extent` of the camera, transformed from world space as `pipeline`
/// says: the bound on `|L(e)|` of its clip-space error `e` through the plane's `form`, and on
/// `|e_w|`. Eye-first with the exact form: `γ_E·Σₖ |gₖ|·Aₖ` (`g` the form on eye coordinates)
/// and `γ_E·A_z`; otherwise one combined matrix, `L(γ_W·B)` and `γ_W·B_w` with
/// `Bᵢ = Σₖ |Pᵢₖ|·Aₖ + |Pᵢ₃|` (module docs). `(0, 0)` for eye-space vertices.
pub fn world_error(
    form: &PlaneForm,
    exact_form: bool,
    m: &[f64; 16],
    pipeline: &Pipeline,
    extent: f64,
) -> (f64, f64) {
    if !pipeline.world_space() {
        return (0.0, 0.0);
    }
    let a = eye_magnitudes(pipeline, extent);
    if pipeline.eye_first && exact_form {
        let g = form.on_eye(m);
        let l: f64 = (0..3).map(|k| g[k].abs() * a[k]).sum();
        let gamma = EYE_FIRST_ROUNDINGS * U;
        return (gamma * l, gamma * a[2]);
    }
    let e = combined_errors(m, a);
    (form.bound(e), e[3])
}

/// The clip-space error bound `γ_W·Bₖ`, `Bₖ = Σᵢ |Pₖᵢ|·Aᵢ + |Pₖ₃|`, of a vertex whose eye
/// coordinates sum terms of magnitude `a` through one combined f32 matrix (module docs).
fn combined_errors(m: &[f64; 16], a: [f64; 3]) -> [f64; 4] {
    [0, 1, 2, 3].map(|row| {
        let b = (0..3).map(|k| m[4 * k + row].abs() * a[k]).sum::<f64>() + m[12 + row].abs();
        WORLD_ROUNDINGS * U * b
    })
}

/// The NDC depth error at a pixel of eye depth `d ≥ nearest` of a mesh inside the frustum,
/// from the f32 transform of world-space vertices ([`world_error`]): the part that does not
/// grow with the vertex's distance over `nearest`, plus the growing part at `ρ` per unit of
/// depth (`ρ = √(1 + eₓ² + e_y²)` from `tangents`; the weights `μᵢ·wᵢ/d` sum to 1).
pub fn world_rounding(
    form: &PlaneForm,
    exact_form: bool,
    m: &[f64; 16],
    pipeline: &Pipeline,
    nearest: f64,
    tangents: [f64; 2],
) -> f64 {
    let (fixed, growing) = world_parts(form, exact_form, m, pipeline, tangents);
    fixed / nearest + growing
}

/// [`world_rounding`]'s two parts: `F`, the NDC error times depth that does not grow with the
/// vertex's distance (at a pixel of depth `d` it gives `F/d`), and `G`, the NDC error of the
/// growing part, the same at every depth.
pub fn world_parts(
    form: &PlaneForm,
    exact_form: bool,
    m: &[f64; 16],
    pipeline: &Pipeline,
    tangents: [f64; 2],
) -> (f64, f64) {
    let rho = (1.0 + tangents[0].powi(2) + tangents[1].powi(2)).sqrt();
    let (fixed, _) = world_error(form, exact_form, m, pipeline, 0.0);
    let (at_rho, _) = world_error(form, exact_form, m, pipeline, rho);
    (fixed, at_rho - fixed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::projection::{projection_f64, ClipDepth, Frustum};

    /// `γ_E` covers what a shader's `view * p` does in f32 to a world position: from an f64 view
    /// (a rotation and the camera far from the origin) and an f64 point, each rounded to f32 as
    /// an engine stores them, then the product in f32 in GLSL's order (and fused, as a GPU may),
    /// against the f64 product of the f64 originals: every eye coordinate within `γ_E·A_k`
    /// (`A_k` from the f32 matrix and the box, as the model computes it), and the bound not
    /// loose by more than 8× on the worst of 4000 points.
    #[test]
    fn eye_first_roundings_cover_an_f32_view_transform() {
        // A Weyl sequence (the fractional parts of k·α for irrational α): deterministic and
        // spread evenly, with no generator to carry.
        let mut k = 0.0f64;
        let mut next = move || {
            k += 1.0;
            (k * 0.618_033_988_749_894_9 + 0.5 * (k * 0.414_213_562_373_095).fract()).fract()
        };
        let mut worst = 0.0f64;
        for _ in 0..40 {
            let (yaw, pitch) = (6.3 * next(), 1.5 * next() - 0.75);
            let camera = [2e4 * next() - 1e4, 1.7 + 10.0 * next(), 2e4 * next() - 1e4];
            let (sy, cy) = f64::sin_cos(yaw);
            let (sp, cp) = f64::sin_cos(pitch);
            // Rows of R = pitch · yaw (world → eye), t = −R·camera; column-major 4×4.
            let r = [
                [cy, 0.0, -sy],
                [sy * sp, cp, cy * sp],
                [sy * cp, -sp, cy * cp],
            ];
            let t: Vec<f64> = (0..3)
                .map(|k| -(0..3).map(|j| r[k][j] * camera[j]).sum::<f64>())
                .collect();
            let mut view = [0.0f64; 16];
            for k in 0..3 {
                for j in 0..3 {
                    view[4 * j + k] = r[k][j];
                }
                view[12 + k] = t[k];
            }
            view[15] = 1.0;
            let view32 = view.map(|v| v as f32);
            let lo = [camera[0] - 500.0, 0.0, camera[2] - 500.0];
            let hi = [camera[0] + 500.0, 0.0, camera[2] + 500.0];
            let pipeline = Pipeline {
                view: Some(view32),
                world_box: Some([lo, hi]),
                eye_first: true,
                ..Pipeline::default()
            };
            let a = eye_magnitudes(&pipeline, 0.0);
            for _ in 0..100 {
                let p = [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * next());
                let p32 = p.map(|c| c as f32);
                let v = [p32[0], p32[1], p32[2], 1.0];
                let plain = crate::test_mat_vec_f32(&view32, v, false);
                let fused = crate::test_mat_vec_f32(&view32, v, true);
                for k in 0..3 {
                    let exact: f64 =
                        (0..3).map(|j| view[4 * j + k] * p[j]).sum::<f64>() + view[12 + k];
                    for got in [plain[k], fused[k]] {
                        let ulps = (f64::from(got) - exact).abs() / (U * a[k]);
                        assert!(
                            ulps <= EYE_FIRST_ROUNDINGS,
                            "{ulps} u·A at {p:?}, coordinate {k}"
                        );
                        worst = worst.max(ulps);
                    }
                }
            }
        }
        assert!(worst > EYE_FIRST_ROUNDINGS / 8.0, "worst {worst}");
    }

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
                let q = clip(q);
                let l = form.at([0, 1, 2, 3].map(|k| q[k] - c[k]));
                worst = worst.max(l.abs() / c[3]);
            }
        }
        assert!(worst > 0.0 && worst <= k * (1.0 + 1e-6), "{worst} > {k}");
        assert!(
            worst > 0.2 * k,
            "the bound is not loose by more than 5x here: {worst} vs {k}"
        );
    }
}

//! The same model under the other clip conventions: `[0, 1]` clip depth and reversed Z.

use super::*;

/// The recommended offset for a [`Scene`] drawn under a clip-depth convention, in the form that
/// convention needs, with the decal's matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipRecommendation {
    /// The convention the offset is for.
    pub clip: ClipDepth,
    /// The constant NDC depth offset `c` for [`crate::clip_offset::ndc_offset_matrix`] (element
    /// 10 becomes `m10 − c`; negative: toward the camera) under `NegOneToOne` and `ZeroToOne`;
    /// 0 under `ReversedZeroToOne`.
    pub ndc_offset: f64,
    /// The relative offset `ε` for [`crate::clip_offset::relative_offset_matrix`] (element 14
    /// scaled by `1 + ε`, every point moved from `d` to `d/(1 + ε)`) under
    /// `ReversedZeroToOne`; 0 otherwise.
    pub relative_epsilon: f64,
    /// The convention's ε in one number: Lengyel's element-10 ε (`m10·(1 + ε)` is `m10 − c`,
    /// so `ε = −c/m10`, negative) under `NegOneToOne` and `ZeroToOne`; [`Self::relative_epsilon`]
    /// (positive) under `ReversedZeroToOne`.
    pub epsilon: f64,
    /// The equivalent `glPolygonOffset(−factor, −units)` magnitudes, as
    /// [`Recommendation::polygon_offset`], under `NegOneToOne` and `ZeroToOne`; `[0, 0]` under
    /// reversed Z, where the offset is relative and no constant `units` matches it.
    pub polygon_offset: [f64; 2],
    /// The smallest window-depth offset over the decal (at `d₂`; constant under `NegOneToOne`
    /// and `ZeroToOne`, `ε·b/d₂` under reversed Z).
    pub window_offset: f64,
    /// The eye-space shift toward the camera at `d₂` that the offset amounts to there.
    pub delta_at_far: f64,
    /// Occluders whose eye depth (`−z`) at the same pixel is smaller than the base's by at least
    /// this are never overdrawn by the decal (R2).
    pub bleed_gap: f64,
    /// The decal's projection matrix (f32, column-major), offset rounded outward; draw the base
    /// with [`crate::projection::projection`] of the same frustum and convention.
    pub matrix: [f32; 16],
    /// The terms the offset was built from (window-depth units; `quantum` at the decal's
    /// farthest point).
    pub terms: ErrorTerms,
}

/// The smallest offset that model (R1) guarantees ends z-fighting for `scene` drawn under
/// `clip` (see "Other clip conventions" in the module docs), with its matrix and bleed gap.
///
/// Conventions: OpenGL right-handed eye space; `NegOneToOne` is `glFrustum` with `GL_LESS` or
/// `GL_LEQUAL` and gives exactly [`recommend`]'s offset; `ZeroToOne` is
/// `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)` with `GL_LESS` or `GL_LEQUAL`
/// (Direct3D/Vulkan clip space), offset through element 10; `ReversedZeroToOne` adds
/// `glDepthFunc(GL_GREATER or GL_GEQUAL)` and `glClearDepth(0)`, offset through element 14
/// (relative, works where `m10 = 0`). `f` may be `+∞` in every convention; `scene.depth_test`
/// must match the convention.
///
/// # Errors
/// As [`recommend`]; [`crate::ErrorKind::Overflow`] if an element of the matrix leaves f32.
pub fn recommend_clip(scene: &Scene, clip: ClipDepth) -> Result<ClipRecommendation> {
    recommend_clip_building(scene, clip, true)
}

/// [`recommend_clip`], with the offset matrix built from zshift's own projection only when
/// `build` (the matrix-in calls apply the offset to the engine's matrix instead: `matrix` is then
/// all zeros).
pub(crate) fn recommend_clip_building(
    scene: &Scene,
    clip: ClipDepth,
    build: bool,
) -> Result<ClipRecommendation> {
    let frustum = &scene.frustum;
    if clip == ClipDepth::NegOneToOne {
        // `recommend` checks the scene itself.
        let r = recommend(scene)?;
        return Ok(ClipRecommendation {
            clip,
            epsilon: r.epsilon,
            polygon_offset: r.polygon_offset,
            ndc_offset: -r.ndc_offset,
            relative_epsilon: 0.0,
            window_offset: r.window_offset,
            delta_at_far: r.delta_at_far,
            bleed_gap: r.bleed_gap,
            matrix: if build {
                crate::offset::epsilon_matrix(frustum, r.epsilon)?
            } else {
                [0.0; 16]
            },
            terms: r.terms,
        });
    }
    check(scene, clip)?;
    let m = crate::projection::projection_f64(frustum, clip)?;
    let mapping = mapping_of(scene, clip)?;
    let terms = clip_error_terms(scene, clip)?;
    let [d1, d2] = scene.depth_range;
    let fits = |x: f64| representable(x, "a recommended value overflows f64");
    let b = scale(&scene.frustum);
    let (ndc_offset, relative_epsilon, window_offset, matrix) = if clip == ClipDepth::ZeroToOne {
        // Window depth = NDC depth: the constant offset is (R1) itself.
        let dw = fits(terms.window_offset())?;
        let c = -dw / mapping.window_per_ndc();
        (
            c,
            0.0,
            dw,
            if build {
                crate::clip_offset::ndc_offset_projection(frustum, clip, c)?
            } else {
                [0.0; 16]
            },
        )
    } else {
        let eps = match measured_facing_reversed(scene) {
            Some(eps) => eps,
            None => reversed_epsilon(scene, &mapping, &terms)?,
        };
        let matrix = if build {
            crate::clip_offset::relative_offset_projection(frustum, clip, eps)?
        } else {
            [0.0; 16]
        };
        (0.0, eps, fits(eps * (b / d2))?, matrix)
    };
    let offset_at = |d: f64| offset_at_depth(clip, relative_epsilon, window_offset, b, d);
    let remedies = super::Remedies::of(&scene.pipeline, &scene.profile);
    check_in_range(&mapping, d1, offset_at(d1), &terms, remedies)?;
    let toward = |dw: f64| if mapping.is_reversed() { dw } else { -dw };
    let delta_at_far = mapping.shift_of_window_change(toward(window_offset), d2)?;
    let bleed_gap = bleed_gap_at(scene, &mapping, &terms, offset_at)?;
    let (epsilon, polygon_offset) = if clip == ClipDepth::ReversedZeroToOne {
        (relative_epsilon, [0.0, 0.0])
    } else {
        let units = polygon_units(scene, &terms, window_offset);
        (-ndc_offset / m[10], [slope_factor(scene), fits(units)?])
    };
    Ok(ClipRecommendation {
        clip,
        epsilon: fits(epsilon)?,
        polygon_offset,
        ndc_offset: fits(ndc_offset)?,
        relative_epsilon,
        window_offset,
        delta_at_far: fits(delta_at_far)?,
        bleed_gap: fits(bleed_gap)?,
        matrix,
        terms,
    })
}

/// The window offset at eye depth `d` of a recommendation under `clip`: `window_offset` at every
/// depth, or under reversed Z `relative_epsilon·b/d` (`b` the frustum's [`scale`]).
fn offset_at_depth(
    clip: ClipDepth,
    relative_epsilon: f64,
    window_offset: f64,
    b: f64,
    d: f64,
) -> f64 {
    if clip == ClipDepth::ReversedZeroToOne {
        relative_epsilon * (b / d)
    } else {
        window_offset
    }
}

/// The bleed gap (R2) of `scene`, whose errors are `terms`, drawn with the window offset
/// `offset_at(d)` at eye depth `d`: the eye-depth separation an occluder needs at `d₁` and at
/// `d₂` (each with the quantum there), the larger; `d` itself where the separation would pass
/// the eye.
fn bleed_gap_at(
    scene: &Scene,
    mapping: &DepthMapping,
    terms: &ErrorTerms,
    offset_at: impl Fn(f64) -> f64,
) -> Result<f64> {
    let toward = |dw: f64| if mapping.is_reversed() { dw } else { -dw };
    let mut bleed_gap = 0.0f64;
    for d in scene.depth_range {
        let at_d = ErrorTerms {
            quantum: unit_quantum(scene.format, &scene.pipeline, mapping.window_depth(d)?)?,
            ..*terms
        };
        let g = match mapping.shift_of_window_change(toward(at_d.gap_window(offset_at(d))), d) {
            Ok(g) => g.min(d),
            // Past the eye: no occluder in front of the base is safe from the decal.
            Err(_) => d,
        };
        bleed_gap = bleed_gap.max(g);
    }
    Ok(bleed_gap)
}

/// The bleed gap of `scene` under `clip`, whose own errors are `terms`, when the decal is drawn
/// with `chosen`'s offset: another plane's of the same decal, through the same matrix
/// ([`crate::planes`]). The offset is `chosen.window_offset` at every depth, or under reversed Z
/// `chosen.relative_epsilon·b/d`.
///
/// # Errors
/// As [`recommend_clip`]'s checks of the scene, and [`crate::ErrorKind::Unresolvable`] where
/// `chosen`'s offset moves this plane's nearest point past the near plane: a plane nearer the
/// camera than the one whose offset was chosen may not take it (its own offset was checked,
/// not this larger one).
pub(crate) fn bleed_gap_with(
    scene: &Scene,
    clip: ClipDepth,
    terms: &ErrorTerms,
    chosen: &ClipRecommendation,
) -> Result<f64> {
    let mapping = mapping_of(scene, clip)?;
    let b = scale(&scene.frustum);
    let offset_at =
        |d: f64| offset_at_depth(clip, chosen.relative_epsilon, chosen.window_offset, b, d);
    let remedies = super::Remedies::of(&scene.pipeline, &scene.profile);
    check_in_range(
        &mapping,
        scene.depth_range[0],
        offset_at(scene.depth_range[0]),
        terms,
        remedies,
    )?;
    bleed_gap_at(scene, &mapping, terms, offset_at)
}

/// Under reversed Z with the decal's footprint and a measured `error_ulps_reversed` `k`: a bound
/// on `budget·d/b` over every pixel of the decal, from each term's own largest product with the
/// depth: `2k·u·(|m10|·d₂ + max M·d)` ([`Footprint::magnitude_depth`]), `2·max V(d)·d`
/// ([`super::terms::vertex_depth_product`]), `(2S + C + C_d)·d₂`; over `b`. The budget
/// evaluated at its worst pixel and carried to the farthest one (`budget·d₂/b`) overstates it by
/// up to `d₂/d₁`. `None` without a footprint, a measured figure, or when the errors are
/// correlated.
fn footprint_relative_budget(scene: &Scene, terms: &ErrorTerms, b: f64) -> Option<f64> {
    let footprint = scene.footprint?;
    let k = measured_figure(&scene.profile, scene.profile.error_ulps_reversed)?;
    if terms.correlated {
        return None;
    }
    let d2 = scene.depth_range[1];
    let (m10, _) =
        crate::projection::depth_row(&scene.frustum.planes(), ClipDepth::ReversedZeroToOne);
    let u = F32_UNIT_ROUNDOFF;
    let pipeline = scene.pipeline;
    let lift = pipeline.depth_range[0] / pipeline.span();
    let shifted = footprint.in_framebuffer(pipeline.viewport_origin, d2);
    let magnitude_depth = shifted.magnitude_depth + lift * d2;
    // V·d at its largest over the decal: the eye rounding from the corners is the same at
    // every pixel, and so is the world rounding's part that grows with depth (a seeded draw lost
    // a pixel over the ground cut to the frustum with V·d₁: a decal from 0.3 to 1.3 units, 367
    // from the origin).
    let vertex = super::terms::vertex_depth_product(scene, ClipDepth::ReversedZeroToOne).ok()?;
    let plane = k * u * (m10.abs() * d2 + magnitude_depth) + vertex;
    Some((2.0 * plane + (2.0 * terms.snap + terms.clip + terms.decal_clip) * d2) / b)
}

/// The relative ε under reversed Z: the window offset it gives at `d` is `ε·b/d`, which must
/// reach `q(w(d)) + budget` (strict test) or `budget` at every `d` of the decal. The budget
/// part is largest at `d₂`; the quantum part `q(w)·d/b` peaks, within each binade of float
/// depth, where `w` is smallest, so at `d₂` or where `w(d)` is a power of two. Element 14
/// rounded to f32 (`p ≥ b·(1 − u)`) carries `ε·p`, hence the final `1/(1 − u)`.
fn reversed_epsilon(scene: &Scene, mapping: &DepthMapping, terms: &ErrorTerms) -> Result<f64> {
    reversed_epsilon_with(scene, mapping, terms, 0.0)
}

/// [`reversed_epsilon`] with `extra`, a constant window-depth error beside the budget (the line
/// term of [`crate::lines`]), added to the budget at every depth.
pub(crate) fn reversed_epsilon_with(
    scene: &Scene,
    mapping: &DepthMapping,
    terms: &ErrorTerms,
    extra: f64,
) -> Result<f64> {
    let b = scale(&scene.frustum);
    let [d1, d2] = scene.depth_range;
    let budget = terms.budget() + extra;
    let strict = if terms.strict { 1.0 } else { 0.0 };
    let relative_budget = footprint_relative_budget(scene, terms, b).unwrap_or(f64::INFINITY);
    let need = |d: f64| -> Result<f64> {
        let q = unit_quantum(scene.format, &scene.pipeline, mapping.window_depth(d)?)?;
        Ok(strict * q * (d / b) + (budget * (d / b)).min(relative_budget))
    };
    let mut eps = need(d1)?.max(need(d2)?);
    // The binades are those of the stored depth, near + (far − near)·w under glDepthRange.
    let pipeline = scene.pipeline;
    let (w_lo, w_hi) = (
        pipeline.actual(mapping.window_depth(d2)?),
        pipeline.actual(mapping.window_depth(d1)?),
    );
    if !scene.format.is_unorm() && w_lo > 0.0 {
        // exp2, not powi: powi(k) for k < −1022 is 1/2^−k, which overflows to ∞ and gives 0,
        // and a walk from 0 never ends (a subnormal window depth reaches here).
        let mut p = (w_lo.log2().floor() + 1.0).exp2();
        while p > 0.0 && p <= w_hi {
            let unit = ((p - pipeline.depth_range[0]) / pipeline.span()).clamp(0.0, 1.0);
            let d = mapping.distance_at_window(unit)?;
            let q = pipeline.per_unit(p * 2f64.powi(-23));
            eps = eps.max(strict * q * (d / b) + (budget * (d / b)).min(relative_budget));
            p *= 2.0;
        }
    }
    representable(
        eps / (1.0 - F32_UNIT_ROUNDOFF),
        "the relative epsilon overflows f64",
    )
}

//! The model's terms for a scene under any clip convention ([`crate::model`] computes each
//! one; this gathers them for the decal): `E`, `V`, `S`, `C`, the depth test and the quantum.

use super::*;
use crate::model::clip::Clipped;

/// The model's terms for `scene` under `clip` (see the module docs); `NegOneToOne` gives
/// exactly [`error_terms`].
///
/// # Errors
/// As [`recommend`].
pub fn clip_error_terms(scene: &Scene, clip: ClipDepth) -> Result<ErrorTerms> {
    check(scene, clip)?;
    let mapping = mapping_of(scene, clip)?;
    let pipeline = scene.pipeline;
    let (m10, _) = crate::projection::depth_row(&scene.frustum.planes(), clip);
    let [d1, d2] = scene.depth_range;
    // In plain f64 (d₁, d₂ are checked): within 2⁻⁵⁰ of the correctly rounded window depths,
    // as close as the f64 evaluation of the terms below is to their formulas.
    let (w1, w2) = (
        mapping.window_depth_estimate(d1),
        mapping.window_depth_estimate(d2),
    );
    let (w_min, w_max) = (w1.min(w2), w1.max(w2));
    // Under glDepthRange(near, far) the stored depth is near + (far − near)·w: the roundings of
    // the viewport map and of the interpolation are relative to it, i.e. to w + lift in unit
    // window depth (0 for the default range).
    let lift = pipeline.depth_range[0] / pipeline.span();
    // T (crate::model::transform).
    let transform = transform::transform(clip, m10, [w1, w2], lift);
    // The footprint measured from the framebuffer's origin, where the rasterizer's plane
    // starts (the viewport may lie inside a larger framebuffer).
    let footprint = scene
        .footprint
        .map(|f| f.in_framebuffer(pipeline.viewport_origin, d2));
    // G: how far the plane's window depth runs across the framebuffer (with the axis-crossing
    // bound 1 + s·e; crate::model::interpolation); with the decal's footprint, the exact run
    // from the origin to its farthest pixel.
    let extrapolated = match footprint {
        Some(footprint) => footprint.extrapolation(),
        None => {
            let gradient = window_gradient(scene, d1)?;
            let extent = interpolation::framebuffer_extent(&pipeline, scene.viewport);
            let tilt = 1.0 + scene.slope * half_extent_tangent(&scene.frustum)?;
            interpolation::extrapolation_bound(gradient, extent, tilt)
        }
    };
    // V and I (crate::model::vertex, crate::model::interpolation).
    let (vertex, interpolation) = if scene.exact_depth {
        (0.0, 0.0)
    } else {
        (
            vertex_term(scene, clip, mapping.window_per_ndc())?,
            interpolation::interpolation(w_min, w_max, extrapolated, lift),
        )
    };
    // The spacing at the decal's farthest point: its largest window depth, or under reversed Z
    // its smallest.
    let far_w = if mapping.is_reversed() { w_min } else { w_max };
    // That point is d₂ either way; the estimate decides the spacing unless near a binade edge.
    let q = if pipeline.depth_range == [0.0, 1.0] {
        mapping.spacing_at_estimate(scene.format, d2, far_w)?
    } else {
        unit_quantum(scene.format, &pipeline, mapping.window_depth(d2)?)?
    };
    let bound = transform + vertex + interpolation;
    // M, the largest magnitude of the plane's terms from the window origin over the decal's
    // pixels (crate::model::interpolation).
    let magnitude = lift
        + match footprint {
            Some(footprint) => footprint.magnitude(),
            None => interpolation::magnitude_bound(w_max, extrapolated),
        };
    let plane = match measured_plane_error(&scene.profile, clip, m10, magnitude) {
        Some(measured) => (measured + vertex).min(bound),
        None => bound,
    };
    let snap = snap(scene)?;
    let clip_term = match scene.profile.near_clip {
        NearClip::ClippedF32 => clip_term(scene, clip, &mapping)?,
        // The probe found clipped planes within twice the unclipped error plus 2 D24 quanta.
        NearClip::PlanePreserving if matches!(scene.base, Base::Clipped { .. }) => {
            plane + snap + pipeline.per_unit(2.0 / 16_777_215.0)
        }
        NearClip::PlanePreserving => 0.0,
    };
    // A decal partly off screen is clipped too, its own corners the reach.
    let decal_reach = scene.footprint.map_or(0.0, |f| f.clipped_reach);
    let decal_clip = match scene.profile.near_clip {
        _ if decal_reach == 0.0 => 0.0,
        NearClip::ClippedF32 => {
            clip_term_of_reach(scene, clip, &mapping, decal_reach, Clipped::Decal)?
        }
        NearClip::PlanePreserving => plane + snap + pipeline.per_unit(2.0 / 16_777_215.0),
    };
    // A facing plane whose every corner has the same f32 z (base and decal) is drawn at one
    // depth, and each step of the depth chain is monotone in element 10: the decal's computed
    // depth is never behind the base's, so under an …EQUAL test (a tie passes) no offset is
    // needed. The budget of base and decal is then 0; the occluder's error stays in the gap.
    let correlated = scene.exact_depth && !scene.depth_test.is_strict();
    // The probe measured the facing figures with glDepthRange(0, 1) and eye-space vertices.
    let facing = if scene.exact_depth && scene.depth_test.is_strict() && pipeline.is_default_depth()
    {
        measured_facing(scene, clip)
    } else {
        0.0
    };
    Ok(ErrorTerms {
        quantum: q,
        transform,
        vertex,
        interpolation,
        snap,
        plane,
        clip: clip_term,
        strict: scene.depth_test.is_strict(),
        correlated,
        facing,
        decal_clip,
    })
}

/// The plane's form on clip coordinates ([`crate::model::plane_form`]): exact from the decal's
/// footprint, else bounds on its coefficients' magnitudes over every plane of the scene's slope
/// whose axis crossing lies at `d₁` or beyond ([`PlaneForm::of_slope`]).
fn plane_form(scene: &Scene, clip: ClipDepth, m: &[f64; 16]) -> Result<PlaneForm> {
    if let Some(footprint) = scene.footprint {
        return Ok(PlaneForm::of_footprint(&footprint, scene.viewport, clip));
    }
    let e = half_extent_tangent(&scene.frustum)?;
    Ok(PlaneForm::of_slope(m, scene.slope, scene.depth_range[0], e))
}

/// The term `V` ([`crate::model::vertex`]), in unit window depth: with the decal's footprint
/// the eye-rounding bound from the plane's form (finite for planes containing the view
/// direction), else `u·(b/d₁)·(1 + s·e)` (a plane of slope `s` crossing the axis at `d₁` or
/// beyond); with world-space vertices ([`Pipeline::world_reach`]) the larger of that and the
/// f32 model-view term.
#[inline]
fn vertex_term(scene: &Scene, clip: ClipDepth, per_ndc: f64) -> Result<f64> {
    let parts = vertex_parts(scene, clip, per_ndc)?;
    let world = parts.world.map_or(0.0, |(fixed, growing)| {
        fixed / scene.depth_range[0] + growing
    });
    representable(parts.eye.max(world), "the vertex term overflows f64")
}

/// The largest product of the vertex term with the depth over the decal, `max V(d)·d` for `d`
/// in `[d₁, d₂]` (window depth × eye depth; 0 for an exact depth), for a budget carried as
/// `ε·b/d` under reversed Z. The eye rounding from the decal's corners, `K`, is the same at every
/// pixel ([`crate::model::vertex`]), so `K·d₂`; the world rounding `F/d + G` (its fixed part
/// falls with depth, the rest does not) gives `F + G·d₂`; without corners the eye bound
/// `u·(b/d)(1 + s·e)` falls with depth, `V(d₁)·d₁`.
pub(super) fn vertex_depth_product(scene: &Scene, clip: ClipDepth) -> Result<f64> {
    let [d1, d2] = scene.depth_range;
    if scene.exact_depth {
        return Ok(0.0);
    }
    let parts = vertex_parts(scene, clip, mapping_of(scene, clip)?.window_per_ndc())?;
    let eye = parts.eye * if parts.eye_falls { d1 } else { d2 };
    let world = parts
        .world
        .map_or(0.0, |(fixed, growing)| fixed + growing * d2);
    representable(eye.max(world), "the vertex term overflows f64")
}

/// The vertex term's parts in window depth ([`vertex_term`] takes the larger of the eye and
/// the world rounding at `d₁`, [`vertex_depth_product`] their products with the depth).
struct VertexParts {
    /// The eye rounding: `K` from the decal's corners (the same at every pixel), else the
    /// bound `u·(b/d₁)·(1 + s·e)`, which falls as `1/d` (`eye_falls`).
    eye: f64,
    eye_falls: bool,
    /// With world-space vertices, the world rounding's fixed part `F` (giving `F/d` at depth
    /// `d`) and its growing part `G` ([`vertex::world_parts`]).
    world: Option<(f64, f64)>,
}

fn vertex_parts(scene: &Scene, clip: ClipDepth, per_ndc: f64) -> Result<VertexParts> {
    let bound = || -> Result<f64> {
        let e = half_extent_tangent(&scene.frustum)?;
        Ok(vertex::eye_rounding_bound(
            scale(&scene.frustum),
            scene.depth_range[0],
            scene.slope,
            e,
        ))
    };
    // The common case (no corners, eye-space vertices) needs neither the f64 matrix nor the form.
    if scene.footprint.is_none() && !scene.pipeline.world_space() {
        return Ok(VertexParts {
            eye: bound()?,
            eye_falls: true,
            world: None,
        });
    }
    let m = crate::projection::projection_f64(&scene.frustum, clip)?;
    let form = plane_form(scene, clip, &m)?;
    let tangents = tangents_of(&scene.frustum);
    let (eye, eye_falls) = match scene.footprint {
        Some(_) => (per_ndc * vertex::eye_rounding(&form, &m, tangents), false),
        None => (bound()?, true),
    };
    // One combined matrix errs in each clip coordinate independently; the eye position computed
    // first errs in eye space, and only its part off the plane counts (needs the exact form).
    let world = scene.pipeline.world_space().then(|| {
        let exact = scene.footprint.is_some();
        let (fixed, growing) = vertex::world_parts(&form, exact, &m, &scene.pipeline, tangents);
        (per_ndc * fixed, per_ndc * growing)
    });
    Ok(VertexParts {
        eye,
        eye_falls,
        world,
    })
}

pub(crate) fn mapping_of(scene: &Scene, clip: ClipDepth) -> Result<DepthMapping> {
    // A Frustum's planes are checked.
    Ok(DepthMapping::of_planes(scene.frustum.planes(), clip))
}

/// The term `C` of a base the rasterizer clips ([`crate::model::clip`]), 0 for
/// [`Base::InsideFrustum`]: with the convention's projection, the plane's form (exact from the
/// footprint, else bounds over every plane of the slope, see [`plane_form`]) and the clipper's
/// measured roundings where the probe found them.
fn clip_term(scene: &Scene, clip: ClipDepth, mapping: &DepthMapping) -> Result<f64> {
    let Base::Clipped { reach } = scene.base else {
        return Ok(0.0);
    };
    clip_term_of_reach(scene, clip, mapping, reach, Clipped::Base)
}

/// [`clip_term`] for a primitive of eye-space `reach` on the decal's plane (the base, or the
/// decal itself where it reaches outside the frustum).
fn clip_term_of_reach(
    scene: &Scene,
    clip: ClipDepth,
    mapping: &DepthMapping,
    reach: f64,
    clipped: Clipped,
) -> Result<f64> {
    let m = crate::projection::projection_f64(&scene.frustum, clip)?;
    // The bound on six clip stages of f32 rounding, or the probe's clip_ulps with its margin.
    let gamma = clip_model::clip_gamma(&scene.profile);
    let form = plane_form(scene, clip, &m)?;
    clip_model::clip_term(
        &m,
        reach,
        scene.depth_range[0],
        gamma,
        &form,
        scene.footprint.is_some(),
        &scene.pipeline,
        mapping.window_per_ndc(),
        clipped,
    )
}

//! The terms of (B1) for the light's pipeline: the caster's own rasterization error (the decal
//! model of [`crate::recommend`] under a spot light, of [`crate::orthographic`] under a
//! directional one, with the map as viewport), the storage and read-back roundings, the
//! lookup's own rounding of the receiver's light-space depth (the f32 view and projection of
//! the light's vertex pipeline) and the texel footprint at the limit angle or of one listed
//! receiver's plane.

use super::receivers::COPLANARITY_WIDENING;
use super::*;

/// The storage term of `K`: the stored UNORM value is within the quantum `q` of the computed
/// depth under any rounding GL allows; where the probe identified the rasterizer's conversion
/// (a measured profile's [`RasterizerProfile::facing_chain`], every one of its candidates rounds
/// to the nearest integer), within `q/2` plus the f32 rounding of the product `w·(2^m − 1)`
/// the conversion may take first (`u·w_max`, relative). The smaller of the two. D32F stores
/// the computed depth: `quantum` is its own term there and is left as it is.
fn storage(map: &ShadowMap, quantum: f64, w_max: f64) -> f64 {
    match map.profile.facing_chain {
        Some(_) if map.profile.measured && map.format.is_unorm() => {
            quantum.min(0.5 * quantum + U * w_max)
        }
        _ => quantum,
    }
}

/// The vertex pipeline of the light's caster and lookup shaders ([`crate::model::vertex`]): the
/// map's pipeline with the larger of the two `world_reach`es (both bound the same
/// coordinates).
fn vertex_pipeline(map: &ShadowMap) -> crate::model::Pipeline {
    crate::model::Pipeline {
        world_reach: map.world_reach.max(map.pipeline.world_reach),
        ..map.pipeline
    }
}

/// The terms of (B1) for receivers at light depths `[d1, d2]` of eye-space slope `slope`: every
/// plane within the limit angle (`receiver = None`), or one receiver plane with its exact
/// window-depth plane in the map (`Some`: the decal model runs on that footprint, and `F` is
/// `a·(|gₓ| + |g_y|)` of its gradient).
pub(super) fn terms_of(
    map: &ShadowMap,
    [d1, d2]: [f64; 2],
    slope: f64,
    receiver: Option<&crate::footprint::Footprint>,
) -> Result<ShadowTerms> {
    let reach = map.lookup.reach()?;
    let theta = map.limit_angle_deg.to_radians();
    // The receiver's own footprint term: exact in f64 from its window plane, widened.
    let own = receiver
        .map(|fp| reach * (fp.gradient[0].abs() + fp.gradient[1].abs()) * COPLANARITY_WIDENING);
    let [w_px, h_px] = map.resolution.map(f64::from);
    let (caster, snap, lookup, quantum, footprint, w_max) = match map.light {
        LightProjection::Perspective(frustum) => {
            let scene = Scene {
                frustum,
                viewport: map.resolution,
                format: map.format,
                depth_range: [d1, d2],
                slope,
                exact_depth: false,
                depth_test: if map.clip == ClipDepth::ReversedZeroToOne {
                    DepthTest::Greater
                } else {
                    DepthTest::Less
                },
                base: Base::InsideFrustum,
                profile: map.profile,
                footprint: receiver.copied(),
                pipeline: vertex_pipeline(map),
            };
            let t = crate::recommend::clip_error_terms(&scene, map.clip)?;
            let (l, r, b, top, n, f) = frustum.parameters();
            let (sx, sy) = ((r - l).abs() / w_px, (top - b).abs() / h_px);
            let (ex, ey) = (l.abs().max(r.abs()) / n, b.abs().max(top.abs()) / n);
            let psi_xy = sx * ex / (1.0 + ex * ex).sqrt() + sy * ey / (1.0 + ey * ey).sqrt();
            let psi = (ex.hypot(ey)).atan();
            let bb = f * n / (f - n);
            let ray = theta + psi;
            let footprint = if let Some(own) = own {
                own
            } else if ray >= std::f64::consts::FRAC_PI_2 {
                f64::INFINITY
            } else {
                reach * bb / (n * d1) * (psi_xy + ray.tan() * sx.hypot(sy))
            };
            let mapping = crate::precision::DepthMapping::projection(n, f, map.clip)?;
            let w_max = mapping.window_depth(d1)?.max(mapping.window_depth(d2)?);
            (
                t.plane,
                t.snap,
                t.transform + t.vertex,
                t.quantum,
                footprint,
                w_max,
            )
        }
        LightProjection::Orthographic(ortho) => {
            let decal = crate::decal::Decal {
                viewport: map.resolution,
                format: map.format,
                depth_range: [d1, d2],
                slope,
                exact_depth: false,
                snapping: map.profile.snapping,
                base: Base::InsideFrustum,
                profile: Some(map.profile),
                // A listed receiver's window plane: the world term on its exact form.
                footprint: receiver.copied(),
                depth_test: None,
                // The light's vertex pipeline and the framebuffer state (an atlas tile's
                // origin, glDepthRange).
                pipeline: vertex_pipeline(map),
            };
            let t = crate::orthographic::error_terms(
                &crate::orthographic::Scene { ortho, decal },
                map.clip,
            )?;
            let (l, r, b, top, n, f) = ortho.parameters();
            let span = f - n;
            let (sx, sy) = ((r - l).abs() / w_px, (top - b).abs() / h_px);
            let footprint = own.unwrap_or(reach * theta.tan() * sx.hypot(sy) / span);
            let w_max = ortho
                .window_depth(map.clip, d1)?
                .max(ortho.window_depth(map.clip, d2)?);
            (
                t.plane,
                t.snap,
                t.transform + t.vertex,
                t.quantum,
                footprint,
                w_max,
            )
        }
    };
    // Under glDepthRange(near, far) the stored depth is near + (far − near)·w: roundings of it
    // are relative to w + lift in unit window depth.
    let lift = map.pipeline.depth_range[0] / map.pipeline.span();
    let read = if map.format.is_unorm() {
        U * (w_max + lift)
    } else {
        0.0
    };
    let quantum = storage(map, quantum, w_max + lift);
    let snap_factor = match map.profile.snapping {
        crate::profile::Snapping::SubpixelBits(b) => 2f64.powi(-(b as i32)),
        crate::profile::Snapping::Unsnapped => 0.0,
    };
    Ok(ShadowTerms {
        reach,
        quantum,
        caster,
        snap,
        slope_factor: 2.0 * reach + snap_factor,
        lookup,
        read,
        constant: quantum + caster + lookup + read,
        footprint,
    })
}

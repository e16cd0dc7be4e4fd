//! The outputs of the terms ("Outputs" in the module docs): the constant in each API's units
//! against its resolvable difference at the receivers' smallest window depth, the slope factor
//! and the clamp rounded up to f32 (none where it would span the map's depth range), the
//! refusal where the constant would, the receiver-side offsets along the light and along the normal, and the cost
//! (leak thickness, peter-panning).

use super::*;

/// The outputs for `terms` with the clamp `needed` (`+∞`: none) and, when known, the
/// receiver-side offsets `(along_light, along_normal)`; else they follow from the limit angle.
pub(super) fn finish(
    map: &ShadowMap,
    terms: ShadowTerms,
    needed: f64,
    offsets: Option<(f64, f64)>,
) -> Result<ShadowBias> {
    // Only rounding terms that span the map's depth range leave no bias: the constant would
    // lift every caster past the far plane.
    if terms.constant.is_nan() || terms.constant >= 1.0 {
        return Err(Error::new(
            ErrorKind::Unresolvable,
            "no shadow bias is acne-free: the rounding terms span the map's depth range (tighten the light's near/far or use a deeper format)",
        )
        .with_value("limit_angle_deg", map.limit_angle_deg));
    }
    // A clamp that would span the whole depth range bounds nothing: set none, as where a spot
    // light's rays can graze (infinite footprint). The slope factor still covers every plane's
    // footprint within the limit angle; casters that steep get a bias past the far plane and
    // cast no shadow, and no receiver-side offset along the light reaches that far.
    let (needed, offsets) = if needed.is_finite() && needed >= 1.0 {
        (f64::INFINITY, Some((f64::INFINITY, f64::INFINITY)))
    } else {
        (needed, offsets)
    };
    let sign = if map.clip == ClipDepth::ReversedZeroToOne {
        -1.0
    } else {
        1.0
    };
    let factor = round_up_f32(terms.slope_factor * (1.0 + 6.0 * U));
    // The clamp bounds the offset in stored depth: the unit window depth it needs, times
    // far − near of glDepthRange (the slope factor needs no change: the slope it multiplies is
    // of stored depth too).
    let clamp = if needed.is_finite() {
        needed * map.pipeline.span()
    } else {
        0.0
    };
    let clamp32 = round_up_f32(clamp);
    // The smallest resolvable difference over the receivers: UNORM's is constant; float's
    // grows with depth, so take it at the smallest window depth.
    let w_small = smallest_window_depth(map)?;
    let units_of = |r: f64| -> f64 { terms.constant / r };
    // Each API's r is a difference of stored depth, taken at the stored depth of w_small under
    // glDepthRange; counted here in unit window depth, as the terms are.
    let pipeline = &map.pipeline;
    let unit_r = |api: BiasApi| -> Result<f64> {
        Ok(pipeline.per_unit(resolvable_difference(
            api,
            map.format,
            pipeline.actual(w_small),
        )?))
    };
    let gl_r = unit_r(BiasApi::OpenGl)?
        * map.profile.resolvable[crate::model::measured::profile_index(map.format)];
    let d3d_r = unit_r(BiasApi::Direct3d)?;
    let vk_r = unit_r(BiasApi::Vulkan)?;
    let gl_units = units_of(gl_r);
    let vk_count = units_of(vk_r);
    if vk_count.is_nan() || vk_count > f64::from(i32::MAX) {
        return Err(Error::new(
            ErrorKind::Unresolvable,
            "on D32F the polygon-offset unit vanishes at the receivers' smallest window depth: keep receivers off window depth 0 (the far plane under reversed Z, the near plane otherwise) or bias on the receiver side",
        )
        .with_value("receiver_near", map.receiver_depths[0]));
    }
    let int_units = |x: f64, what: &'static str| -> Result<i32> {
        let c = x.ceil();
        if c.is_nan() || c > f64::from(i32::MAX) {
            return Err(Error::new(ErrorKind::Overflow, what));
        }
        Ok(c as i32)
    };
    let d3d_units = int_units(
        units_of(d3d_r),
        "the Direct3D DepthBias does not fit in INT",
    )?;
    let webgpu_units = int_units(units_of(vk_r), "the WebGPU depthBias does not fit in i32")?;
    let vk_units = round_up_f32(units_of(vk_r));
    let isign = sign as i32;
    let (along_light, along_normal, leak) = match offsets {
        Some((light, normal)) => (light, normal, light),
        None => receiver_offsets(map, &terms)?,
    };
    // A receiver moved toward a spot light by its light depth or more reaches or passes the
    // light, where the projection flips: no such offset works. (Short of it, past the near
    // plane, the lookup's depth leaves the map's range on the lit side; along the ray its map
    // position stays. A directional light has no such point.)
    let room = match map.light {
        LightProjection::Perspective(_) => map.receiver_depths[0],
        LightProjection::Orthographic(_) => f64::INFINITY,
    };
    let usable = |offset: f64| if offset < room { offset } else { f64::INFINITY };
    let (along_light, along_normal) = (usable(along_light), usable(along_normal));
    let e = map.elevation_deg.to_radians();
    Ok(ShadowBias {
        terms,
        gl_polygon_offset: [
            sign * f64::from(factor),
            sign * gl_units.ceil(),
            sign * f64::from(clamp32),
        ],
        d3d: D3dBias {
            depth_bias: isign * d3d_units,
            slope_scaled: sign as f32 * factor,
            clamp: sign as f32 * clamp32,
        },
        vulkan: [
            sign as f32 * vk_units,
            sign as f32 * factor,
            sign as f32 * clamp32,
        ],
        webgpu_depth_bias: isign * webgpu_units,
        webgpu_slope_clamp: [sign as f32 * factor, sign as f32 * clamp32],
        along_light,
        along_normal,
        leak_thickness: leak,
        peter_panning: leak * e.cos(),
    })
}

/// The receivers' smallest window depth in the map (where float depth's `r` is smallest).
fn smallest_window_depth(map: &ShadowMap) -> Result<f64> {
    let [d1, d2] = map.receiver_depths;
    Ok(match map.light {
        LightProjection::Perspective(frustum) => {
            let (_, _, _, _, n, f) = frustum.parameters();
            let mapping = crate::precision::DepthMapping::projection(n, f, map.clip)?;
            mapping.window_depth(d1)?.min(mapping.window_depth(d2)?)
        }
        LightProjection::Orthographic(ortho) => ortho
            .window_depth(map.clip, d1)?
            .min(ortho.window_depth(map.clip, d2)?),
    })
}

/// `(along_light, along_normal, leak_thickness)` (module docs), at the farthest receiver.
fn receiver_offsets(map: &ShadowMap, terms: &ShadowTerms) -> Result<(f64, f64, f64)> {
    let theta = map.limit_angle_deg.to_radians();
    let d2 = map.receiver_depths[1];
    // Constant and footprint-per-tan as distances along the light.
    let (k_l, d_l, ray_limit) = match map.light {
        LightProjection::Orthographic(ortho) => {
            let span = ortho.far() - ortho.near();
            let per_tan = if theta == 0.0 {
                0.0
            } else {
                terms.footprint / theta.tan()
            };
            ((terms.constant + terms.snap) * span, per_tan * span, theta)
        }
        LightProjection::Perspective(frustum) => {
            let (l, r, b, t, n, f) = frustum.parameters();
            let bb = f * n / (f - n);
            let (ex, ey) = (l.abs().max(r.abs()) / n, b.abs().max(t.abs()) / n);
            let along = (1.0 + ex * ex + ey * ey).sqrt();
            let (w_px, h_px) = (f64::from(map.resolution[0]), f64::from(map.resolution[1]));
            let (sx, sy) = ((r - l).abs() / w_px, (t - b).abs() / h_px);
            let psi_xy = sx * ex / (1.0 + ex * ex).sqrt() + sy * ey / (1.0 + ey * ey).sqrt();
            // Eye shift for a window change β at d₂: β·d²/(b − β·d).
            // (+∞ where β reaches the end of the depth range: no receiver-side offset along the
            // light gives that window change there.)
            let shift = |beta: f64| -> Result<f64> {
                let den = bb - beta * d2;
                Ok(if den <= 0.0 {
                    f64::INFINITY
                } else {
                    beta * d2 * d2 / den
                })
            };
            let base = terms.constant + terms.snap + terms.reach * bb / (n * d2) * psi_xy;
            let per_tan = terms.reach * bb / (n * d2) * sx.hypot(sy);
            let k = shift(base)? * along;
            // The footprint's share, linear in the window change near 0: its eye size is the
            // shift of base + per_tan less that of base, at tan θ = 1 (an upper bound by the
            // convexity of the shift in β is not needed: d_l is used only with tan θ ≤ its
            // value at the limit, below).
            let psi = ex.hypot(ey).atan();
            let ray = (theta + psi).min(std::f64::consts::FRAC_PI_2);
            let d = if k.is_infinite() {
                f64::INFINITY
            } else if ray < std::f64::consts::FRAC_PI_2 && ray > 0.0 {
                (shift(base + per_tan * ray.tan())? * along - k) / ray.tan()
            } else {
                shift(per_tan)? * along
            };
            (k, d, ray)
        }
    };
    if !(k_l.is_finite() && d_l.is_finite()) {
        return Ok((f64::INFINITY, f64::INFINITY, f64::INFINITY));
    }
    let along_light = if ray_limit >= std::f64::consts::FRAC_PI_2 {
        f64::INFINITY
    } else {
        k_l + d_l * ray_limit.tan()
    };
    // max over θ ≤ limit of K·cos θ + D·sin θ: √(K² + D²) at atan(D/K) if inside, else at the
    // limit.
    let peak = d_l.atan2(k_l);
    let along_normal = if peak <= ray_limit {
        k_l.hypot(d_l)
    } else {
        k_l * ray_limit.cos() + d_l * ray_limit.sin()
    };
    Ok((along_light, along_normal, along_light))
}

/// The smallest f32 not below `x`.
fn round_up_f32(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) >= x {
        y
    } else {
        f32::from_bits(y.to_bits() + 1)
    }
}

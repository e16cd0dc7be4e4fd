//! A facing decal's offset from the probe's measurements: the identified depth chain's exact
//! steps ([`crate::depth_chain`]), else the measured facing quanta.

use super::*;

/// The profile's measured offset for a shared-z facing plane under a strict test, in window
/// depth: [`RasterizerProfile::facing_quanta`] (under `[0, 1]`
/// [`RasterizerProfile::facing_quanta_zero_to_one`]) times the format's quantum (D32F: 2⁻²⁴),
/// from a measured profile; 0 otherwise (and under reversed Z, where the probe does not measure
/// it).
pub(super) fn measured_facing(scene: &Scene, clip: ClipDepth) -> f64 {
    if let Some(offset) = chain_facing(scene, clip) {
        return offset;
    }
    let p = scene.profile;
    let figure = match clip {
        ClipDepth::NegOneToOne => p.facing_quanta[profile_index(scene.format)],
        ClipDepth::ZeroToOne => p.facing_quanta_zero_to_one[profile_index(scene.format)],
        ClipDepth::ReversedZeroToOne => f64::NAN,
    };
    let Some(k) = measured_figure(&p, figure) else {
        return 0.0;
    };
    let unit = match scene.format {
        DepthFormat::Float32 => F32_UNIT_ROUNDOFF,
        format => format.spacing_at(0.5).unwrap_or(0.0),
    };
    k * unit
}

/// The profile's measured relative ε for a shared-z facing plane under reversed Z and a strict
/// test on D32F ([`RasterizerProfile::facing_reversed`] times 2⁻²⁴), divided by `1 − u` for
/// element 14's own rounding as [`reversed_epsilon`] is; `None` where not measured or not such a
/// scene.
pub(super) fn measured_facing_reversed(scene: &Scene) -> Option<f64> {
    if !scene.pipeline.is_default_depth() {
        return None;
    }
    if let Some(eps) = chain_facing(scene, ClipDepth::ReversedZeroToOne) {
        return Some(eps);
    }
    let k = measured_figure(&scene.profile, scene.profile.facing_reversed)?;
    (scene.exact_depth && scene.depth_test.is_strict() && scene.format == DepthFormat::Float32)
        .then(|| k * F32_UNIT_ROUNDOFF / (1.0 - F32_UNIT_ROUNDOFF))
}

/// How far, in f32 steps of the engine's elements, the chain's answer is checked around zshift's
/// own matrix: an engine that computes `glFrustum`'s elements in its own f32 code may be an ulp or
/// two off the correctly rounded ones, and the answer must hold for it too.
const CHAIN_ELEMENT_SPREAD: u32 = 2;

/// Whether the chain's answer, checked within [`CHAIN_ELEMENT_SPREAD`] f32 steps of zshift's
/// matrix `plain`, covers a base drawn with `engine`: its elements 10 and 14 (in magnitude, so a
/// left-handed matrix compares with its right-handed twin) lie within that spread.
pub(crate) fn chain_covers(plain: &[f32; 16], engine: &[f32; 16]) -> bool {
    [10, 14].iter().all(|&i| {
        let (a, b) = (plain[i].abs().to_bits(), engine[i].abs().to_bits());
        a.abs_diff(b) <= CHAIN_ELEMENT_SPREAD
    })
}

/// A shared-z facing decal under a strict test with a profile whose probe identified the depth
/// chain ([`RasterizerProfile::facing_chain`]): the exact number of f32 steps `k` of the offset
/// element it needs ([`crate::depth_chain::steps_to_pass`]; the largest over element 10 and 14
/// within [`CHAIN_ELEMENT_SPREAD`] steps of zshift's matrix, and over `m10·z + m14` fused or not,
/// the one step that runs in the engine's own shader), as the offset to request: the move
/// of `k − 0.45` steps, which the outward rounding of the offset matrix (from the exact element,
/// within half a step of the f32 one) turns into `k` steps, or `k + 1` in a sliver. Under `[−1, 1]`
/// and `[0, 1]` a window-depth offset (half the element's move, or all of it); under reversed Z a
/// relative ε of element 14. `None` where the chain is not known, the scene is not such a decal,
/// its depth is not an f32, the format is D32 (UNORM, whose conversion the probe cannot see), or
/// `f < 2n`. The base must be drawn with zshift's matrix for the frustum, or one whose elements 10
/// and 14 are within [`CHAIN_ELEMENT_SPREAD`] f32 steps of it (any `glFrustum` computed in f32 or
/// better with `f ≥ 2n`); the matrix-in calls check the engine's own and fall back otherwise.
fn chain_facing(scene: &Scene, clip: ClipDepth) -> Option<f64> {
    let p = scene.profile;
    let chain = p.facing_chain?;
    let [d1, d2] = scene.depth_range;
    let z = -(d1 as f32);
    let planes = scene.frustum.planes();
    // Below f = 2n an engine's f32 (f + n)/(f − n) cancels and may stray far from zshift's
    // element (Mesa's own glFrustum by 2 to 582912 f32 steps): the worst phase stands in.
    let near_far_apart = planes.far() >= 2.0 * planes.near();
    if !(p.measured && scene.exact_depth && scene.depth_test.is_strict() && near_far_apart)
        || d1 != d2
        || f64::from(z) != -d1
    {
        return None;
    }
    let bits = match scene.format {
        DepthFormat::Unorm16 => 16,
        DepthFormat::Unorm24 => 24,
        DepthFormat::Unorm32 => return None,
        DepthFormat::Float32 => 0,
    };
    let m = crate::projection::projection(&scene.frustum, clip).ok()?;
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let spread = CHAIN_ELEMENT_SPREAD;
    let around = |x: f32| {
        (0..=2 * spread).filter_map(move |i| {
            let bits = x.to_bits().checked_add(i)?.checked_sub(spread)?;
            let y = f32::from_bits(bits);
            (y.is_finite() && y.signum() == x.signum()).then_some(y)
        })
    };
    // The product and sum m10·z + m14 run in the engine's own vertex shader, which a compiler
    // may fuse or not whatever the probe's shader got: both are covered. (The division by w,
    // the viewport map and the conversion are the fixed-function part the probe identified.)
    let shader_variants = [
        chain,
        crate::depth_chain::DepthChain {
            fused_clip: !chain.fused_clip,
            ..chain
        },
    ];
    let mut k = 0;
    for variant in shader_variants {
        for m10 in around(m[10]) {
            for m14 in around(m[14]) {
                let steps = |limit| {
                    crate::depth_chain::steps_to_pass(variant, clip, bits, (m10, m14), z, limit)
                };
                // Nearby elements need nearby steps: bisect a short range first.
                let near = if k > 0 { steps(2 * k + 16) } else { None };
                k = k.max(near.or_else(|| steps(1 << 20))?);
            }
        }
    }
    let element = |k: u32| {
        let (m10, m14) = crate::depth_chain::stepped((m[10], m[14]), reversed, k)?;
        Some(f64::from(if reversed { m14 } else { m10 }))
    };
    let (before, at, start) = (element(k - 1)?, element(k)?, element(0)?);
    let moved = ((before - start) + 0.55 * (at - before)).abs();
    Some(match clip {
        ClipDepth::NegOneToOne => 0.5 * moved,
        ClipDepth::ZeroToOne => moved,
        ClipDepth::ReversedZeroToOne => moved / start.abs(),
    })
}

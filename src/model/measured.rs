//! What a measured profile replaces: the probe's figures as terms of the model.
//!
//! [`crate::recommend::Scene::profile`] is a [`RasterizerProfile`] (each field defined once, in
//! [`crate::profile`]); the default, [`RasterizerProfile::worst_case`], assumes 8 sub-pixel bits
//! of snapping, `r` = 1 quantum and clipping in f32, and uses the bounds of the other terms. A
//! profile the probe measured ([`crate::probe::probe`], in the engine's own context) enters the
//! model field by field:
//!
//! * `snapping`: `S` ([`crate::model::snap`]), 0 where the rasterizer is unsnapped.
//! * `error_ulps` `k` (and `error_ulps_reversed` under reversed Z) **replaces `T + I`**: the probe
//!   found every pixel it drew within `k·u·(c + M)` of the plane through its f32 vertices,
//!   `M = |w₀| + |gₓ|·x + |g_y|·y` the magnitude of the plane's terms from the window origin
//!   ([`crate::model::interpolation`]) and `c` the transform's constant part (1 under `[−1, 1]`,
//!   2 under `[0, 1]` where the viewport map halves nothing, `|m10| = n/(f − n)` under reversed
//!   Z). So `E = min(k·u·(c + M) + V, T + V + I)` (plus `u·(|m10| − 11/9)⁺/2`, the transform's
//!   excess where `f` is closer to `n` than the probe's views). `M` is the decal's own with a
//!   footprint, else bounded by `w(d₂) + 2G`. **This is a measured figure, not a proof**: a
//!   maximum of roundings over the planes the probe drew (about 300, among them 256 in random
//!   directions and frusta, 128 of them off-centre). On llvmpipe the probe finds 1.54 (`[−1, 1]`
//!   and `[0, 1]`, each measured) and 4.29 (reversed);
//!   `tests/gl_scenes.rs` (`the_probed_error_bound_holds`) draws 804 other planes per convention
//!   and finds single pixels at up to 1.09× that `E` (the largest of more roundings is larger),
//!   never more than the `2E` the offset reserves for base and decal together; the sweep's pairs
//!   of base and decal, the quantity that decides a lost pixel, stay inside (0 lost in every
//!   scene). `plane_error` (one worst figure per format) is a summary for reports and changes
//!   nothing.
//! * The footprint ([`crate::recommend::Scene::footprint`], from the decal's corners): replaces
//!   the extrapolation bound `G` in `I` and `S` by the run to the decal's farthest pixel with
//!   its exact gradients, and `M` by its value there; under reversed Z each term of the budget
//!   is carried to the relative offset at its own worst depth
//!   ([`crate::footprint::Footprint::magnitude_depth`]).
//! * `near_clip`: [`crate::profile::NearClip::ClippedF32`] keeps `C` ([`crate::model::clip`]);
//!   [`crate::profile::NearClip::PlanePreserving`] replaces it by what the probe allows a
//!   clipped plane beyond an unclipped one, the base's own `E + S` plus 2 D24 quanta (`2⁻²⁴`),
//!   whatever the reach. `clip_ulps` `k` replaces the bound `6 + 5k` on the clipper's roundings
//!   by `4k` where smaller ([`crate::model::clip`]: a sampled maximum with a margin, not a proof).
//! * `resolvable` `r`: [`crate::recommend::Recommendation::polygon_offset`]'s units are
//!   `(Δw − 2S)/(r·q)`.
//! * `facing_quanta`, `facing_quanta_zero_to_one`, `facing_reversed`, `facing_chain` (only from
//!   a measured profile): the offset of a facing plane with shared f32 z under a strict test, a
//!   term of the decal problem alone (see "Correlated errors" in [`crate::recommend`]).

use crate::precision::DepthFormat;
use crate::profile::RasterizerProfile;
use crate::projection::ClipDepth;

use super::F32_UNIT_ROUNDOFF;

/// The largest `|m10|` of the planes the probe measures `error_ulps` on (its views have
/// f/n ≥ 10 under `[−1, 1]`: `|m10| = (f + n)/(f − n) ≤ 11/9`).
const PROBED_M10: f64 = 11.0 / 9.0;

/// A figure of `profile` the model may use: one the probe measured (a measured profile, finite
/// and positive; NaN means not measured).
pub(crate) fn measured_figure(profile: &RasterizerProfile, figure: f64) -> Option<f64> {
    (profile.measured && figure.is_finite() && figure > 0.0).then_some(figure)
}

/// The per-quad error `T + I` from a measured profile (module docs): the probe found every
/// pixel's computed depth within `error_ulps·u·(1 + M)` under `[−1, 1]`, the 1 standing for the
/// transform's own roundings at `|m10| ≤ 11/9`. A larger `|m10|` (f close to n) adds its excess
/// `u·(|m10| − 11/9)/2` (the product `m10·z`, halved by the viewport map); under `[0, 1]`
/// nothing halves the transform's roundings, so the 1 becomes 2 and the excess is whole. Under
/// reversed Z the probe measures `error_ulps_reversed` against `|m10| + M` (its errors are
/// relative to the small depths: no constant 1). `None` for the worst-case profile or an
/// unmeasured figure.
pub(crate) fn measured_plane_error(
    profile: &RasterizerProfile,
    clip: ClipDepth,
    m10: f64,
    magnitude: f64,
) -> Option<f64> {
    let p = profile;
    let k = measured_figure(
        p,
        if clip == ClipDepth::ReversedZeroToOne {
            p.error_ulps_reversed
        } else {
            p.error_ulps
        },
    )?;
    let u = F32_UNIT_ROUNDOFF;
    let excess = (m10.abs() - PROBED_M10).max(0.0);
    Some(match clip {
        ClipDepth::NegOneToOne => k * u * (1.0 + magnitude) + u * excess / 2.0,
        ClipDepth::ZeroToOne => k * u * (2.0 + magnitude) + u * excess,
        ClipDepth::ReversedZeroToOne => k * u * (m10.abs() + magnitude),
    })
}

/// The index of `format` in a [`RasterizerProfile`]'s per-format arrays (D16, D24, D32, D32F).
pub(crate) fn profile_index(format: DepthFormat) -> usize {
    match format {
        DepthFormat::Unorm16 => 0,
        DepthFormat::Unorm24 => 1,
        DepthFormat::Unorm32 => 2,
        DepthFormat::Float32 => 3,
    }
}

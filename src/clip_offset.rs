//! Depth offsets for every projection convention: where the offset belongs, and its f32 rounding.
//!
//! Every `glFrustum`-family projection gives NDC depth `z_ndc = −m10 + m14/d` at eye distance
//! `d` (x, y and `w = d` do not involve elements 10 and 14). That leaves two places for an
//! offset that moves depth without moving pixels:
//!
//! * **Element 10, additively** — `m10 → m10 − c` adds the constant `c` to every NDC depth.
//!   Lengyel's `m10·(1 + ε)` (seed 000, eq. 4.1.3) is the case `c = −ε·m10`; it needs
//!   `m10 ≠ 0`. A constant offset suits UNORM buffers, whose steps are constant in depth.
//! * **Element 14, multiplicatively** — `m14 → m14·(1 + ε)` gives `z_ndc = −m10 + m14/(d/(1+ε))`:
//!   exactly the depth of the point moved to `d/(1 + ε)`, a shift toward the camera of the
//!   fixed fraction `ε/(1 + ε)` of its distance, in every convention. This is the offset for
//!   reversed Z with float depth, where element 10 is 0 for the infinite projection (scaling it
//!   does nothing) and the buffer's spacing `2^(e−23)` is itself relative to the stored
//!   `w ≈ n/d`: one relative ε of a few `2⁻²³` works at every distance.
//!
//! Both are rounded outward in f32 (double-double decides the direction), so the offset the GPU
//! sees is never smaller than the one asked for, and at most one f32 ulp of the element larger.

use crate::domain::{finite, representable};
use crate::double_double::DoubleDouble;
use crate::error::Result;
use crate::offset::{outward_of_ratio, rounded_outward, Ratio};
use crate::precision::DepthMapping;
#[cfg(doc)]
use crate::projection::tweaked_infinite_f64;
use crate::projection::{
    projection, projection_exact, to_f32, tweaked_infinite, ClipDepth, Frustum,
};

/// The f32 projection with `c` added to every NDC depth through element 10 (`m10 − c`).
///
/// `m` is any column-major perspective matrix with `w = −z_eye` (the `glFrustum` family, any
/// [`ClipDepth`], the tweaked infinite projection). Every element but 10 is the nearest f32 of
/// the given f64 (builders from a [`Frustum`], such as [`offset_projection`], round the exact
/// elements instead);
/// element 10 is `p − x` with `p = f32(m10)` and `x` the f32 satisfying `|c| ≤ |x| ≤ |c| + ulp`,
/// same sign as `c`. `c < 0` moves depth toward the camera under `NegOneToOne`/`ZeroToOne`;
/// `c > 0` under reversed Z.
///
/// # Errors
/// [`ErrorKind::NotFinite`](crate::ErrorKind::NotFinite) if `c` is NaN or infinite; [`ErrorKind::Overflow`](crate::ErrorKind::Overflow) if an element
/// leaves f32.
pub fn ndc_offset_matrix(m: &[f64; 16], c: f64) -> Result<[f32; 16]> {
    with_ndc_offset(to_f32(m)?, c)
}

/// [`ndc_offset_matrix`] for the projection of `frustum` under `clip`: every element but 10 the
/// nearest f32 of the exact element (as [`projection`]), element 10 lowered by `c` and rounded
/// outward.
///
/// # Errors
/// As [`projection`] and [`ndc_offset_matrix`].
pub fn ndc_offset_projection(frustum: &Frustum, clip: ClipDepth, c: f64) -> Result<[f32; 16]> {
    with_ndc_offset(projection(frustum, clip)?, c)
}

/// [`relative_offset_matrix`] for the projection of `frustum` under `clip`: every element but 14
/// the nearest f32 of the exact element (as [`projection`]), element 14 scaled by `1 + ε` and
/// rounded outward.
///
/// # Errors
/// As [`projection`] and [`relative_offset_matrix`].
pub fn relative_offset_projection(
    frustum: &Frustum,
    clip: ClipDepth,
    epsilon: f64,
) -> Result<[f32; 16]> {
    with_relative_offset(projection(frustum, clip)?, epsilon)
}

/// `plain` with `c` added to every NDC depth through element 10, rounded outward as
/// [`ndc_offset_matrix`] describes. The offset `−c` is exact, so the estimate of
/// `plain[10] − c` has one rounding.
fn with_ndc_offset(mut plain: [f32; 16], c: f64) -> Result<[f32; 16]> {
    if let Some(x) = outward_of_ratio(plain[10], Ratio(-c, 1.0), 0.0) {
        plain[10] = x;
        return Ok(plain);
    }
    finite(c, "the NDC depth offset c is NaN or infinite")?;
    plain[10] = rounded_outward(plain[10], DoubleDouble::from_f64(-c))?;
    Ok(plain)
}

/// The f32 projection with element 14 scaled by `1 + ε`: every point's depth becomes that of
/// the point at `d/(1 + ε)` (toward the camera for `ε > 0`), in every convention.
///
/// Element 14 is rounded away from `p = f32(m14)` so that `x/p ≥ 1 + ε` for `ε > 0` (and
/// `≤` for `ε < 0`), within one f32 ulp.
///
/// # Errors
/// [`ErrorKind::NotFinite`](crate::ErrorKind::NotFinite) if `ε` is NaN or infinite; [`ErrorKind::Domain`](crate::ErrorKind::Domain) unless `ε > −1`;
/// [`ErrorKind::Overflow`](crate::ErrorKind::Overflow) if an element leaves f32.
pub fn relative_offset_matrix(m: &[f64; 16], epsilon: f64) -> Result<[f32; 16]> {
    with_relative_offset(to_f32(m)?, epsilon)
}

/// `plain` with element 14 scaled by `1 + ε`, rounded outward as [`relative_offset_matrix`]
/// describes. The offset `p·ε` is estimated with one rounding.
fn with_relative_offset(mut plain: [f32; 16], epsilon: f64) -> Result<[f32; 16]> {
    let p = plain[14];
    if epsilon > -1.0 {
        if let Some(x) = outward_of_ratio(p, Ratio(f64::from(p) * epsilon, 1.0), 1.0) {
            plain[14] = x;
            return Ok(plain);
        }
    }
    finite(epsilon, "the relative offset epsilon is NaN or infinite")?;
    if epsilon <= -1.0 {
        return Err(crate::domain::domain(
            "the relative offset epsilon must be greater than -1",
        ));
    }
    plain[14] = rounded_outward(p, DoubleDouble::product(f64::from(p), epsilon))?;
    Ok(plain)
}

/// The relative offset `ε = δ/(d − δ)` (with `d = −Pz`) that moves a point at eye-space depth
/// `Pz` toward the camera by `δ` through element 14 ([`relative_offset_matrix`]); every other
/// point moves by the same fraction `δ/d` of its distance.
///
/// # Errors
/// [`ErrorKind::NotFinite`](crate::ErrorKind::NotFinite) for NaN or ±∞; [`ErrorKind::Domain`](crate::ErrorKind::Domain) unless `Pz < 0` and
/// `Pz + δ < 0`.
pub fn relative_epsilon(delta: f64, pz: f64) -> Result<f64> {
    finite(delta, "the eye-space shift delta is NaN or infinite")?;
    finite(pz, "the eye-space depth Pz is NaN or infinite")?;
    if pz >= 0.0 || pz + delta >= 0.0 {
        return Err(crate::domain::domain(
            "Pz and Pz + delta must be in front of the eye (< 0)",
        ));
    }
    representable(delta / (-pz - delta), "the relative epsilon overflows f64")
}

/// The constant NDC offset `c = z_ndc(d − δ) − z_ndc(d)` that moves a point at `Pz` (`d = −Pz`)
/// toward the camera by `δ` under `mapping`: the generalisation of seed 000 eq. 4.1.6–4.1.7
/// (for `NegOneToOne`, `c = −ε·m10` with Lengyel's ε).
///
/// # Errors
/// As [`DepthMapping::window_change_of_shift`].
pub fn ndc_offset_of_shift(mapping: &DepthMapping, delta: f64, pz: f64) -> Result<f64> {
    finite(pz, "the eye-space depth Pz is NaN or infinite")?;
    Ok(mapping.window_change_of_shift(delta, -pz)? / mapping.window_per_ndc())
}

/// The offset variant of [`crate::projection::projection`]: the projection of `frustum` under
/// `clip`, moving geometry at `Pz` toward the camera by `δ` (`δ < 0` moves it away).
///
/// `NegOneToOne` and `ZeroToOne` use the constant NDC offset through element 10 (identical to
/// [`crate::offset::offset_matrix`] for `NegOneToOne` up to the f32 rounding of the same
/// value); `ReversedZeroToOne` uses the relative offset through element 14, which exists even
/// where `m10 = 0` and matches float depth's relative spacing.
///
/// # Errors
/// As [`Frustum::to_cols_array_f64`], [`ndc_offset_of_shift`] and [`relative_epsilon`].
pub fn offset_projection(
    frustum: &Frustum,
    clip: ClipDepth,
    delta: f64,
    pz: f64,
) -> Result<[f32; 16]> {
    let plain = projection(frustum, clip)?;
    let planes = frustum.planes();
    if clip == ClipDepth::ReversedZeroToOne {
        planes.check_eye_z(pz)?;
        return with_relative_offset(plain, relative_epsilon(delta, pz)?);
    }
    let mapping = DepthMapping::projection(planes.near(), planes.far(), clip)?;
    with_ndc_offset(plain, ndc_offset_of_shift(&mapping, delta, pz)?)
}

/// The fast path of [`offset_projection`] alone: `None` where it defers to the exact path
/// (checks, details and every rounding too close to call). When it returns a matrix, that
/// matrix is [`offset_projection`]'s (and [`offset_projection_exact`]'s).
pub fn offset_projection_fast(
    frustum: &Frustum,
    clip: ClipDepth,
    delta: f64,
    pz: f64,
) -> Option<[f32; 16]> {
    let mut m = crate::projection::projection_fast(frustum, clip)?;
    if clip == ClipDepth::ReversedZeroToOne {
        frustum.planes().check_eye_z(pz).ok()?;
        let epsilon = relative_epsilon(delta, pz).ok()?;
        m[14] = outward_of_ratio(m[14], Ratio(f64::from(m[14]) * epsilon, 1.0), 1.0)?;
        return Some(m);
    }
    let planes = frustum.planes();
    let mapping = DepthMapping::projection(planes.near(), planes.far(), clip).ok()?;
    let c = ndc_offset_of_shift(&mapping, delta, pz).ok()?;
    m[10] = outward_of_ratio(m[10], Ratio(-c, 1.0), 0.0)?;
    Some(m)
}

/// [`offset_projection`] decided by the exact path alone (the plain elements by
/// [`crate::projection::projection_exact`], the offset element by double-double): the same
/// matrix, slower; tests compare the fast path with it.
///
/// # Errors
/// As [`offset_projection`].
pub fn offset_projection_exact(
    frustum: &Frustum,
    clip: ClipDepth,
    delta: f64,
    pz: f64,
) -> Result<[f32; 16]> {
    let mut m = projection_exact(frustum, clip)?;
    let planes = frustum.planes();
    if clip == ClipDepth::ReversedZeroToOne {
        planes.check_eye_z(pz)?;
        let epsilon = relative_epsilon(delta, pz)?;
        m[14] = rounded_outward(m[14], DoubleDouble::product(f64::from(m[14]), epsilon))?;
        return Ok(m);
    }
    let mapping = DepthMapping::projection(planes.near(), planes.far(), clip)?;
    let c = ndc_offset_of_shift(&mapping, delta, pz)?;
    m[10] = rounded_outward(m[10], DoubleDouble::from_f64(-c))?;
    Ok(m)
}

/// The fast path of [`offset_tweaked_infinite`] alone, as [`offset_projection_fast`].
pub fn offset_tweaked_infinite_fast(
    frustum: &Frustum,
    tweak: f64,
    delta: f64,
    pz: f64,
) -> Option<[f32; 16]> {
    let mut m = crate::projection::tweaked_infinite_fast(frustum, tweak)?;
    let mapping = DepthMapping::tweaked_infinite(frustum.planes().near(), tweak).ok()?;
    let c = ndc_offset_of_shift(&mapping, delta, pz).ok()?;
    m[10] = outward_of_ratio(m[10], Ratio(-c, 1.0), 0.0)?;
    Some(m)
}

/// The offset variant of [`crate::projection::tweaked_infinite`]: moves geometry at `Pz`
/// toward the camera by `δ` with a constant NDC offset through element 10.
///
/// # Errors
/// As [`tweaked_infinite_f64`] and [`ndc_offset_of_shift`].
pub fn offset_tweaked_infinite(
    frustum: &Frustum,
    tweak: f64,
    delta: f64,
    pz: f64,
) -> Result<[f32; 16]> {
    let plain = tweaked_infinite(frustum, tweak)?;
    let mapping = DepthMapping::tweaked_infinite(frustum.planes().near(), tweak)?;
    with_ndc_offset(plain, ndc_offset_of_shift(&mapping, delta, pz)?)
}

//! The engine's own projection matrix in, the decal's matrix out.
//!
//! An engine already has its projection as 16 floats (from GLM, glam, its own code). Rebuilding
//! it from `l, r, b, t, n, f` gives a matrix whose elements differ from the engine's in the last
//! bit, so base and decal would be drawn with different depth rows. The functions here read the
//! engine's matrix, recognise what it is, and change only the one element that carries the
//! offset, rounded outward, so that every other element is bit-identical to the input and the
//! offset the GPU sees is never less than the one asked for (and at most one f32 ulp of the
//! changed element more).
//!
//! # What is recognised
//! Only the depth row (elements 2, 6, 10, 14) and the w row (3, 7, 11, 15) matter; the x and y
//! rows may hold anything (off-centre frusta, TAA jitter, a Vulkan y flip).
//!
//! * **Perspective**: `m3 = m7 = m15 = 0`, `m11 = ±1` (`−1`: OpenGL's right-handed eye space,
//!   `w = −z`; `+1`: a left-handed matrix, `w = +z`), `m2 = m6 = 0`. NDC depth at eye distance
//!   `d = w` is `z_ndc = s·m10 + m14/d` with `s = m11`: finite, infinite (`s·m10 = ±1` or `0`),
//!   tweaked infinite (the far plane beyond infinity), reversed.
//! * **Orthographic**: `m3 = m7 = m11 = 0`, `m15 = 1`, `m2 = m6 = 0`, `m10 ≠ 0`. NDC depth is
//!   `z_ndc = m10·z + m14`, read in OpenGL's right-handed eye space (`z = −d`). For a
//!   left-handed orthographic matrix negate elements 8–11 first, and back after: the offset
//!   element (14) is not among them.
//!
//! Anything else (an oblique near plane, `m2 ≠ 0`; a scaled w row; NaN) is refused with a
//! detail that says which element is wrong. So is a matrix whose depth runs the other way from
//! the convention the caller states (a reversed-Z matrix passed as `NegOneToOne`): a convention
//! mismatch is an error, never a wrong matrix. A `[−1, 1]` matrix and a `[0, 1]` one cannot be
//! told apart from their elements (each is a valid projection of the other kind, with another
//! near plane); the caller's `clip` decides.
//!
//! # Where the offset goes
//! | shape, convention | offset | element |
//! |---|---|---|
//! | perspective, `[−1, 1]` or `[0, 1]`, eye shift or NDC offset | constant NDC `c` | 10: `m10 + s·c` |
//! | perspective, reversed, eye shift | relative `ε = δ/(d − δ)`: every point moved from `d` to `d/(1 + ε)` | 14: `m14·(1 + ε)` |
//! | perspective, reversed, NDC offset | constant NDC `c` | 10 |
//! | orthographic, any | constant NDC `c = m10·δ` (an eye shift is the same everywhere) | 14: `m14 + c` |
//!
//! The offset is computed in double-double from the engine's own f32 elements (exact in f64),
//! and the element is rounded away from its plain value ([`crate::offset`]'s outward rounding).

use crate::domain::{domain, finite};
use crate::double_double::DoubleDouble;
#[cfg(doc)]
use crate::error::ErrorKind;
use crate::error::Result;
use crate::offset::rounded_outward;
use crate::projection::{ClipDepth, Frustum};
use crate::recommend::{ClipRecommendation, Scene};

/// The shape of a projection matrix, as far as depth is concerned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// `w = ±z_eye`: depth `z_ndc = s·m10 + m14/d`.
    Perspective {
        /// `m11`: −1 for OpenGL's right-handed eye space, +1 for a left-handed matrix.
        handedness: f64,
        /// Whether the far plane lies beyond infinity: depth never reaches the far end of the
        /// convention's range (the tweaked infinite projection, Lengyel 2007).
        tweaked: bool,
    },
    /// `w = 1`: depth `z_ndc = m10·z + m14`, linear in eye distance.
    Orthographic,
}

/// What the depth and w rows of an engine's matrix say under a clip convention.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Recognized {
    /// The convention the caller stated.
    pub clip: ClipDepth,
    /// Perspective (and how) or orthographic.
    pub shape: Shape,
    /// The near plane distance the matrix maps to the convention's near end (perspective:
    /// positive; orthographic: any, the near plane may lie behind the eye).
    pub near: f64,
    /// The far plane distance (perspective: `+∞` for an infinite or tweaked projection).
    pub far: f64,
}

/// The NDC depths of the near and far ends of a convention.
fn ends(clip: ClipDepth) -> (f64, f64) {
    match clip {
        ClipDepth::NegOneToOne => (-1.0, 1.0),
        ClipDepth::ZeroToOne => (0.0, 1.0),
        ClipDepth::ReversedZeroToOne => (1.0, 0.0),
    }
}

/// Refuses a nonzero element with a detail naming it.
fn zero(m: &[f64; 16], i: usize, detail: &'static str) -> Result<()> {
    if m[i] != 0.0 {
        return Err(domain(detail).with_value(ELEMENT_NAMES[i], m[i]));
    }
    Ok(())
}

const ELEMENT_NAMES: [&str; 16] = [
    "m[0]", "m[1]", "m[2]", "m[3]", "m[4]", "m[5]", "m[6]", "m[7]", "m[8]", "m[9]", "m[10]",
    "m[11]", "m[12]", "m[13]", "m[14]", "m[15]",
];

/// Reads `m` (column-major) and says what projection it is under `clip`.
///
/// # Errors
/// [`ErrorKind::NotFinite`] for a NaN or infinite element; [`ErrorKind::Domain`] for a matrix
/// that is neither a perspective nor an orthographic projection with a plain depth row (the
/// detail names the element), or whose depth runs against `clip` (a convention mismatch), or
/// whose near plane is not in front of the eye (perspective).
pub fn recognize(m: &[f32; 16], clip: ClipDepth) -> Result<Recognized> {
    let mut e = [0.0f64; 16];
    for (i, (x, &v)) in e.iter_mut().zip(m).enumerate() {
        *x = finite(
            f64::from(v),
            "a projection matrix element is NaN or infinite",
        )
        .map_err(|err| err.with_value(ELEMENT_NAMES[i], f64::from(v)))?;
    }
    zero(&e, 2, "m[2] (row 2, column 0) is not 0: depth depends on x (an oblique near plane or a rotated projection); only a depth row (0, 0, m[10], m[14]) can be offset")?;
    zero(&e, 6, "m[6] (row 2, column 1) is not 0: depth depends on y (an oblique near plane or a rotated projection); only a depth row (0, 0, m[10], m[14]) can be offset")?;
    zero(&e, 3, "m[3] (row 3, column 0) is not 0: not a projection matrix, or a row-major (transposed) one: pass the column-major array glUniformMatrix4fv(.., GL_FALSE, ..) takes")?;
    zero(
        &e,
        7,
        "m[7] (row 3, column 1) is not 0: not a projection matrix, or a row-major (transposed) one",
    )?;
    if e[15] == 0.0 {
        perspective(&e, clip)
    } else {
        orthographic(&e, clip)
    }
}

#[inline(always)]
fn perspective(e: &[f64; 16], clip: ClipDepth) -> Result<Recognized> {
    let s = e[11];
    if s != 1.0 && s != -1.0 {
        return Err(domain(
            "m[11] must be -1 (OpenGL's right-handed w = -z) or +1 (left-handed) in a perspective matrix (m[15] = 0); a row-major (transposed) matrix has it in m[14]",
        )
        .with_value("m[11]", s));
    }
    let (m10, m14) = (e[10], e[14]);
    let (z_near, z_far) = ends(clip);
    // dz_ndc/dd = −m14/d²: depth grows with distance iff m14 < 0.
    if m14 == 0.0 {
        return Err(domain(
            "m[14] is 0: depth does not vary with distance, not a perspective projection",
        ));
    }
    direction(
        clip,
        m14 > 0.0,
        ("m[14]", m14),
        "depth grows with distance (m[14] < 0): a standard matrix, but clip is ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE",
        "depth falls with distance (m[14] > 0): a reversed-Z matrix; pass clip ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE",
    )?;
    // z_ndc(d) = s·m10 + m14/d, so the distance at NDC depth z is m14/(z − s·m10).
    let a = s * m10;
    let near = m14 / (z_near - a);
    if !(near > 0.0 && near.is_finite()) {
        return Err(domain(
            "the matrix puts the convention's near end behind the eye: its depth row does not fit the stated clip convention",
        )
        .with_value("m[10]", m10));
    }
    let far_denominator = z_far - a;
    // Depth reaches the far end at a finite distance when m14/(z_far − a) > near; at infinity
    // when z_far = a; never (a tweaked infinite projection) when the quotient's sign is wrong.
    let (far, tweaked) = if far_denominator == 0.0 {
        (f64::INFINITY, false)
    } else {
        let far = m14 / far_denominator;
        if far > near {
            (far, false)
        } else {
            (f64::INFINITY, true)
        }
    };
    Ok(Recognized {
        clip,
        shape: Shape::Perspective {
            handedness: s,
            tweaked,
        },
        near,
        far,
    })
}

/// Refuses a depth row that runs against `clip` (a convention mismatch): depth must grow with
/// distance unless `clip` is reversed. `falls` says whether it falls; the detail names the
/// element that says so.
fn direction(
    clip: ClipDepth,
    falls: bool,
    (name, value): (&'static str, f64),
    grows_but_reversed: &'static str,
    falls_but_standard: &'static str,
) -> Result<()> {
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    if falls == reversed {
        return Ok(());
    }
    let detail = if reversed {
        grows_but_reversed
    } else {
        falls_but_standard
    };
    Err(domain(detail).with_value(name, value))
}

fn orthographic(e: &[f64; 16], clip: ClipDepth) -> Result<Recognized> {
    zero(
        e,
        11,
        "m[11] is not 0 while m[15] is not 0: neither a perspective nor an orthographic projection",
    )?;
    if e[15] != 1.0 {
        return Err(
            domain("m[15] must be 1 in an orthographic matrix (0 in a perspective one)")
                .with_value("m[15]", e[15]),
        );
    }
    let (m10, m14) = (e[10], e[14]);
    if m10 == 0.0 {
        return Err(domain(
            "m[10] is 0: an orthographic matrix whose depth does not vary, nothing to offset",
        ));
    }
    // z_ndc = m10·z + m14 with z = −d: the distance at NDC depth z is (m14 − z)/m10.
    direction(
        clip,
        m10 > 0.0,
        ("m[10]", m10),
        "depth grows with distance (m[10] < 0): a standard orthographic matrix, but clip is ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE",
        "depth falls with distance in OpenGL eye space (m[10] > 0): a reversed-Z orthographic matrix (pass clip ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE), or a left-handed one (negate elements 8-11 first)",
    )?;
    let (z_near, z_far) = ends(clip);
    Ok(Recognized {
        clip,
        shape: Shape::Orthographic,
        near: (m14 - z_near) / m10,
        far: (m14 - z_far) / m10,
    })
}

/// `m` with element `i` moved away from its value by `offset` (double-double), rounded outward.
#[inline(always)]
pub(crate) fn moved(m: &[f32; 16], i: usize, offset: DoubleDouble) -> Result<[f32; 16]> {
    let mut out = *m;
    // Decided from the offset's leading f64 (within 2⁻⁵³ of it) where it can be, as
    // `crate::offset::outward_of_ratio` shows; else from the double-double value.
    let (x, decided) = crate::offset::outward_decided(m[i], offset.hi, 1.0);
    out[i] = if decided {
        x
    } else {
        rounded_outward(m[i], offset)?
    };
    Ok(out)
}

/// The engine's matrix `m` with the NDC depth of every point moved toward the camera by `c`
/// (NDC units; negative moves away): through element 10 for a perspective matrix (`m10 + s·c`
/// with the sign of the convention), element 14 for an orthographic one.
///
/// Under `[−1, 1]` an NDC offset `c` is a window-depth offset `c/2`; under `[0, 1]` and reversed,
/// `c`. Every element but the offset one is bit-identical to `m`; the offset one is rounded
/// away from its value, so the NDC offset the GPU sees is at least `|c|` and at most one f32 ulp
/// of the element more.
///
/// # Errors
/// As [`recognize`]; [`ErrorKind::NotFinite`] if `c` is NaN or infinite;
/// [`ErrorKind::Overflow`] if the element leaves f32.
pub fn offset_ndc(m: &[f32; 16], clip: ClipDepth, c: f64) -> Result<[f32; 16]> {
    let r = recognize(m, clip)?;
    finite(c, "the NDC offset c is NaN or infinite").map_err(|e| e.with_value("c", c))?;
    let toward = toward_sign(clip) * c;
    match r.shape {
        Shape::Perspective { handedness, .. } => {
            moved(m, 10, DoubleDouble::from_f64(handedness * toward))
        }
        Shape::Orthographic => moved(m, 14, DoubleDouble::from_f64(toward)),
    }
}

/// The sign of an NDC change toward the camera: −1 where depth grows with distance, +1 reversed.
fn toward_sign(clip: ClipDepth) -> f64 {
    if clip == ClipDepth::ReversedZeroToOne {
        1.0
    } else {
        -1.0
    }
}

/// The engine's matrix `m` with geometry at eye distance `d` moved toward the camera by `delta`
/// (eye-space units; negative moves it away): seed 000's eq. 4.1.3–4.1.7 on the engine's own
/// elements.
///
/// Perspective `[−1, 1]` and `[0, 1]`: the constant NDC offset `c = m14·δ/(d·(d − δ))` through
/// element 10 (points nearer than `d` move less than `δ` in eye space, farther ones more).
/// Perspective reversed: element 14 scaled by `1 + δ/(d − δ)`, which moves every point from `d'`
/// to `d'·(d − δ)/d` (the offset that exists where `m10 = 0` and suits float depth).
/// Orthographic: the constant NDC offset `m10·δ` through element 14, the same eye shift `δ` at
/// every distance (so `d` is only checked). The offset element is rounded outward; every other
/// element is bit-identical to `m`.
///
/// # Errors
/// As [`recognize`]; [`ErrorKind::NotFinite`] for NaN or infinite `delta` or `d`;
/// [`ErrorKind::Domain`] unless `d > 0` and `d − δ > 0` (perspective; the shifted point must
/// stay in front of the eye); [`ErrorKind::Overflow`] if the element leaves f32.
pub fn offset_shift(m: &[f32; 16], clip: ClipDepth, delta: f64, d: f64) -> Result<[f32; 16]> {
    let r = recognize(m, clip)?;
    finite(delta, "the eye-space shift delta is NaN or infinite")
        .map_err(|e| e.with_value("delta", delta))?;
    finite(d, "the eye distance d is NaN or infinite").map_err(|e| e.with_value("d", d))?;
    match r.shape {
        Shape::Orthographic => {
            let c = DoubleDouble::product(f64::from(m[10]), delta);
            moved(m, 14, c)
        }
        Shape::Perspective { handedness, .. } => {
            if d <= 0.0 {
                return Err(domain(
                    "the eye distance d must be greater than 0 (in front of the eye)",
                )
                .with_value("d", d));
            }
            let shifted = DoubleDouble::sum(d, -delta);
            if shifted.hi <= 0.0 {
                return Err(domain(
                    "the shifted distance d - delta must stay in front of the eye (> 0)",
                )
                .with_value("d - delta", shifted.hi));
            }
            let m14 = f64::from(m[14]);
            if clip == ClipDepth::ReversedZeroToOne {
                let epsilon = DoubleDouble::from_f64(delta).div(shifted);
                return moved(m, 14, epsilon.mul_f64(m14));
            }
            // c = m14·δ/(d·(d − δ)), applied as m10 + s·c.
            let c = DoubleDouble::product(m14, delta).div(shifted.mul_f64(d));
            moved(m, 10, c.mul_f64(handedness))
        }
    }
}

/// [`recognize`]'s checks without their details, branch-free: `(valid, s)` with `s = m11`
/// (`±1`) for a perspective matrix, 0 for an orthographic one.
#[inline(always)]
fn recognised_fast(m: &[f32; 16], clip: ClipDepth) -> (bool, f64) {
    let finite = m.iter().fold(true, |all, x| all & x.is_finite());
    let rows = (m[2] == 0.0) & (m[6] == 0.0) & (m[3] == 0.0) & (m[7] == 0.0);
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let (s, m10, m14) = (f64::from(m[11]), f64::from(m[10]), f64::from(m[14]));
    if m[15] == 0.0 {
        let near = m14 / (ends(clip).0 - s * m10);
        let shape = ((s == 1.0) | (s == -1.0)) & (m14 != 0.0) & ((m14 > 0.0) == reversed);
        let near_ok = (near > 0.0) & (near < f64::INFINITY);
        (finite & rows & shape & near_ok, s)
    } else {
        let shape = (s == 0.0) & (m[15] == 1.0) & (m10 != 0.0) & ((m10 > 0.0) == reversed);
        (finite & rows & shape, 0.0)
    }
}

/// The fast path of [`offset_shift`]: its matrix, or `None` where it defers (an error to
/// explain, or an offset too close to an f32 step to decide from its f64 estimate,
/// `crate::offset::outward_of_ratio`). Arithmetic and comparisons only, nothing that panics.
///
/// The estimates, from the engine's f32 elements (exact in f64): `c = m14·δ/(d·(d − δ))`
/// (four roundings), `m14·δ/(d − δ)` (three) and `m10·δ` (one); each intermediate product must
/// be a normal f64 for their relative bounds (else the exact path decides).
#[inline]
pub fn offset_shift_fast(m: &[f32; 16], clip: ClipDepth, delta: f64, d: f64) -> Option<[f32; 16]> {
    let (recognised, s) = recognised_fast(m, clip);
    let (m10, m14) = (f64::from(m[10]), f64::from(m[14]));
    let normal = |x: f64| x.abs() >= f64::MIN_POSITIVE;
    let inputs = (delta.abs() < f64::INFINITY) & (d.abs() < f64::INFINITY);
    let (i, estimate, rounds, valid) = if s == 0.0 {
        (14, m10 * delta, 1.0, true)
    } else {
        let shifted = d - delta;
        let product = m14 * delta;
        let valid = (d > 0.0) & (shifted > 0.0) & normal(product);
        if clip == ClipDepth::ReversedZeroToOne {
            (14, product / shifted, 3.0, valid)
        } else {
            let depths = d * shifted;
            (10, s * (product / depths), 4.0, valid & normal(depths))
        }
    };
    let (x, decided) = crate::offset::outward_decided(m[i], estimate, rounds);
    let mut out = *m;
    out[i] = x;
    (recognised & inputs & valid & decided).then_some(out)
}

/// The fast path of [`offset_ndc`], as [`offset_shift_fast`] (the offset `c` is exact).
#[inline]
pub fn offset_ndc_fast(m: &[f32; 16], clip: ClipDepth, c: f64) -> Option<[f32; 16]> {
    let (recognised, s) = recognised_fast(m, clip);
    let toward = toward_sign(clip) * c;
    let (i, estimate) = if s == 0.0 {
        (14, toward)
    } else {
        (10, s * toward)
    };
    let (x, decided) = crate::offset::outward_decided(m[i], estimate, 0.0);
    let mut out = *m;
    out[i] = x;
    (recognised & (c.abs() < f64::INFINITY) & decided).then_some(out)
}

pub use crate::decal::Decal;

/// The frustum of a recognised perspective matrix: `l, r, b, t` on the near plane from the x
/// and y rows (`x_ndc = m0·x/d + s·m8`), sorted so `l < r` and `b < t` (a y flip changes no
/// footprint), and the recognised planes (`f = +∞` for a tweaked projection).
#[inline(always)]
pub(crate) fn frustum_of(m: &[f32; 16], r: &Recognized, handedness: f64) -> Result<Frustum> {
    let n = r.near;
    let side = |scale: f32, shear: f32| {
        let (scale, shear) = (f64::from(scale), f64::from(shear));
        let a = n * (-1.0 - handedness * shear) / scale;
        let b = n * (1.0 - handedness * shear) / scale;
        (a.min(b), a.max(b))
    };
    if m[0] == 0.0 || m[5] == 0.0 {
        return Err(domain(
            "m[0] or m[5] is 0: the x or y row has no scale, not a perspective projection",
        ));
    }
    let (l, rt) = side(m[0], m[8]);
    let (b, t) = side(m[5], m[9]);
    Frustum::new(l, rt, b, t, n, r.far)
}

/// The depth range, slope and footprint of a planar decal from its eye-space `corners`, seen
/// through the engine's own matrix `m` under `clip` in a `viewport` at the framebuffer's origin:
/// [`crate::footprint::decal_shape_for_matrix`] on `m` widened to f64. Fill a [`Decal`]'s
/// `depth_range`, `slope` and `footprint` from it.
///
/// # Errors
/// As [`crate::footprint::decal_shape_for_matrix`].
pub fn decal_shape(
    m: &[f32; 16],
    clip: ClipDepth,
    viewport: [u32; 2],
    corners: &[glam::Vec3],
) -> Result<crate::footprint::DecalShape> {
    crate::footprint::decal_shape_for_matrix(&m.map(f64::from), clip, viewport, corners)
}

/// The recommended offset for a decal drawn with the engine's own matrix `m` under `clip`, and
/// the decal's matrix: `m` with the recommendation applied to its own offset element, rounded
/// outward, every other element bit-identical (the recommendation's `matrix` field).
///
/// Perspective: [`crate::recommend::recommend_clip`]'s model on the frustum read from `m`
/// (`l, r, b, t` from the x and y rows, `n, f` from [`recognize`]); element 10 (a constant NDC
/// offset) under `[−1, 1]` and `[0, 1]`, element 14 (relative) reversed. A tweaked infinite
/// projection is treated as infinite (its tweak, at most 2⁻¹⁰ here, moves depth by less than one
/// part in a thousand; the offset is applied to the engine's own elements).
/// Orthographic: [`crate::orthographic::recommend`] on the box read from `m`; element 14.
///
/// # Errors
/// As [`recognize`], [`crate::recommend::recommend_clip`] and
/// [`crate::orthographic::recommend`]; [`crate::ErrorKind::Domain`] for a tweak above 2⁻¹⁰.
pub fn recommend(m: &[f32; 16], clip: ClipDepth, decal: &Decal) -> Result<ClipRecommendation> {
    let r = recognize(m, clip)?;
    let Shape::Perspective {
        handedness,
        tweaked,
    } = r.shape
    else {
        let mut rec = crate::orthographic::recommend(&ortho_scene(m, &r, decal)?, clip)?;
        rec.matrix = moved(m, 14, DoubleDouble::from_f64(rec.ndc_offset))?;
        return Ok(rec);
    };
    let tweak = 1.0 - handedness * f64::from(m[10]);
    if tweaked && tweak.abs() > 1.0 / 1024.0 {
        return Err(domain(
            "the matrix is a tweaked infinite projection with a tweak above 2^-10: the model would not describe its depth",
        )
        .with_value("tweak", tweak));
    }
    let mut scene = scene(frustum_of(m, &r, handedness)?, decal, clip);
    // The identified depth chain emulates the base's own elements 10 and 14 only within a few f32
    // steps of zshift's matrix for this frustum; further off (a tweaked infinite projection, an
    // engine's loose f32 formula) the measured worst phase stands in.
    if scene.profile.facing_chain.is_some() {
        let plain = crate::projection::projection(&scene.frustum, clip)?;
        if !crate::recommend::chain_covers(&plain, m) {
            scene.profile.facing_chain = None;
        }
    }
    let mut rec = crate::recommend::recommend_clip_building(&scene, clip, false)?;
    rec.matrix = if clip == ClipDepth::ReversedZeroToOne {
        let eps = rec.relative_epsilon;
        moved(m, 14, DoubleDouble::product(f64::from(m[14]), eps))?
    } else {
        // recommend_clip's c is the signed change of NDC depth: s·Δm10 = c, so Δm10 = s·c.
        moved(m, 10, DoubleDouble::from_f64(handedness * rec.ndc_offset))?
    };
    Ok(rec)
}

/// The orthographic model's scene for a recognised orthographic matrix: the box from the x and
/// y rows (`x_ndc = m0·x + m12`), sorted (a y flip changes no footprint).
fn ortho_scene(m: &[f32; 16], r: &Recognized, decal: &Decal) -> Result<crate::orthographic::Scene> {
    let side = |scale: f32, shift: f32| {
        let (scale, shift) = (f64::from(scale), f64::from(shift));
        let (a, b) = ((-1.0 - shift) / scale, (1.0 - shift) / scale);
        (a.min(b), a.max(b))
    };
    let (l, rt) = side(m[0], m[12]);
    let (b, t) = side(m[5], m[13]);
    let (near, far) = (r.near.min(r.far), r.near.max(r.far));
    Ok(crate::orthographic::Scene {
        ortho: crate::orthographic::Ortho::new(l, rt, b, t, near, far)?,
        decal: *decal,
    })
}

/// The model's scene for a decal under a frustum (the one place that knows `Scene`'s fields):
/// the decal's depth test (the convention's strict one unless given), base, profile (the worst
/// case with the decal's snapping unless given) and pipeline.
#[inline(always)]
pub(crate) fn scene(frustum: Frustum, decal: &Decal, clip: ClipDepth) -> Scene {
    use crate::recommend::DepthTest;
    Scene {
        footprint: decal.footprint,
        frustum,
        viewport: decal.viewport,
        format: decal.format,
        depth_range: decal.depth_range,
        slope: decal.slope,
        exact_depth: decal.exact_depth,
        depth_test: decal
            .depth_test
            .unwrap_or(if clip == ClipDepth::ReversedZeroToOne {
                DepthTest::Greater
            } else {
                DepthTest::Less
            }),
        base: decal.base,
        profile: decal.rasterizer(),
        pipeline: decal.pipeline,
    }
}

//! The term `S`: sub-pixel snapping of a sloped plane.
//!
//! A rasterizer that snaps window x, y to `2^-b` pixel (`GL_SUBPIXEL_BITS` = b) *before*
//! setting up the depth plane moves each vertex by up to `2^-(b+1)` pixel per axis, so the
//! plane's depth moves by up to
//!
//! `S = 2^-(b+1)·(gₓ + g_y)·(1 + s·e)`,
//!
//! with `g` the window-depth gradient per pixel of a plane crossing the view axis at `d₁` and
//! `1 + s·e` the bound on where it really crosses it ([`crate::model::gradient`]). With the
//! decal's footprint its exact gradients replace the bound (`S = 2^-(b+1)·(|gₓ| + |g_y|)`).
//! Mesa's llvmpipe snaps only coverage and sets the depth plane up from the unsnapped float
//! positions ([`crate::profile::Snapping::Unsnapped`], `S = 0`).
//!
//! # Relation to glPolygonOffset
//! `glPolygonOffset(factor, units)` adds `factor·M + units·r` to window depth, `M` the polygon's
//! largest depth gradient per pixel. The snapping term of base and decal, `2S ≤ 2^-b·2M`, is
//! slope-scaled: `factor = 2^(1−b)` (`slope_factor`), 0 unsnapped.

use crate::domain::power_of_two;
use crate::profile::Snapping;

/// `S` for window `gradient` `(gₓ, g_y)` per pixel and the `tilt` on the plane's axis crossing
/// (`1 + s·e` for the bound over every plane of the slope; 1 with the footprint's exact
/// gradients): `2^-(b+1)·(|gₓ| + |g_y|)·tilt`, 0 unsnapped.
pub(crate) fn snap(snapping: Snapping, gradient: [f64; 2], tilt: f64) -> f64 {
    match snapping {
        Snapping::Unsnapped => 0.0,
        Snapping::SubpixelBits(b) => {
            let [gx, gy] = gradient;
            power_of_two(-(b as i32) - 1) * (gx.abs() + gy.abs()) * tilt
        }
    }
}

/// `glPolygonOffset`'s factor equivalent to the snapping term: `2^(1−b)`, 0 unsnapped.
pub(crate) fn slope_factor(snapping: Snapping) -> f64 {
    match snapping {
        Snapping::SubpixelBits(b) => power_of_two(1 - b as i32),
        Snapping::Unsnapped => 0.0,
    }
}

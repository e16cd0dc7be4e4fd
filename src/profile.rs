//! What a rasterizer does that the offset model needs to know: a profile is plain data.
//!
//! No vendor documents how it snaps vertices before depth setup, how it clips a primitive that
//! crosses the near plane, or how it scales `glPolygonOffset` units (the minimum resolvable
//! difference `r` is 1×, 2× or 4× a format's quantum depending on the GPU). A
//! [`RasterizerProfile`] holds those facts. [`RasterizerProfile::worst_case`] (the `Default`)
//! assumes the worst of each and is what the recommendation uses unless told otherwise; a
//! measured profile comes from the probe, which draws in the caller's own GL context.

/// Whether the rasterizer snaps vertex positions before setting up the depth plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Snapping {
    /// Snapped to `2^-bits` pixel, `bits` = `GL_SUBPIXEL_BITS` (the conservative assumption for a
    /// GPU; adds the slope-scaled term `S`).
    SubpixelBits(u32),
    /// Depth interpolated from the unsnapped float positions (measured on Mesa llvmpipe): `S = 0`.
    Unsnapped,
}

/// How the clipper treats a primitive that crosses the near plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NearClip {
    /// New vertices are computed in f32 where the edges cross the near plane, and the depth plane
    /// is set up from them: the worst case, and what Mesa's llvmpipe does.
    ClippedF32,
}

/// The per-device facts the offset model needs. See the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RasterizerProfile {
    /// Whether vertex positions are snapped before depth setup.
    pub snapping: Snapping,
    /// `glPolygonOffset`'s minimum resolvable difference `r` per format (D16, D24, D32, D32F), in
    /// units of the format's quantum (for D32F, of `2^(e−23)`).
    pub resolvable: [f64; 4],
    /// The worst `|computed − exact|` window depth per pixel of a sloped plane, per format (D16,
    /// D24, D32, D32F), in units of the format's quantum; NaN where not measured (the model's
    /// bound applies).
    pub plane_error: [f64; 4],
    /// How primitives crossing the near plane are clipped.
    pub near_clip: NearClip,
    /// `false` for [`RasterizerProfile::worst_case`]; `true` for a profile the probe measured.
    pub measured: bool,
}

impl RasterizerProfile {
    /// The profile that assumes the worst of every fact: 8 sub-pixel bits of snapping, `r` up to
    /// 4 quanta, per-pixel errors as the model bounds them, clipping in f32.
    pub fn worst_case() -> Self {
        Self {
            snapping: Snapping::SubpixelBits(8),
            resolvable: [4.0; 4],
            plane_error: [f64::NAN; 4],
            near_clip: NearClip::ClippedF32,
            measured: false,
        }
    }
}

impl Default for RasterizerProfile {
    fn default() -> Self {
        Self::worst_case()
    }
}

//! What an engine knows about a decal besides its projection matrix: the input of the
//! recommendation for an engine's own matrix ([`crate::matrix_in::recommend`]), perspective or
//! orthographic ([`crate::orthographic::recommend`]).

use crate::precision::DepthFormat;
use crate::recommend::Snapping;

/// A decal over a coplanar base, as the engine knows it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decal {
    /// Viewport width and height in pixels (`glViewport`).
    pub viewport: [u32; 2],
    /// The depth attachment's format.
    pub format: DepthFormat,
    /// The decal's nearest and farthest eye distance (`n ≤ d₁ ≤ d₂ ≤ f`).
    pub depth_range: [f64; 2],
    /// Eye-space tilt of its plane, `|∂z/∂x| + |∂z/∂y|` (0 facing the camera).
    pub slope: f64,
    /// Every corner of base and decal has the same f32 eye-space z (requires `slope == 0`).
    pub exact_depth: bool,
    /// How the rasterizer positions vertices before depth setup (used when `profile` is `None`).
    pub snapping: Snapping,
    /// What is known of the base's extent ([`crate::recommend::Base`]): a base the rasterizer
    /// clips (a floor running behind the camera) adds the clipping term. Perspective only: the
    /// orthographic model takes no base.
    pub base: crate::recommend::Base,
    /// The rasterizer's profile (from [`crate::probe::probe`]): when `Some`, it supplies every
    /// rasterizer fact, its own snapping included, and `snapping` is ignored; `None` is
    /// [`crate::recommend::RasterizerProfile::worst_case`] with `snapping`.
    pub profile: Option<crate::recommend::RasterizerProfile>,
    /// The decal's window-space geometry from its corners
    /// ([`crate::matrix_in::decal_shape`] computes it with `depth_range` and `slope` from the
    /// engine's matrix), or `None`: the model's bounds over every plane of that slope and every
    /// pixel of the viewport. Perspective only: the orthographic model does not use it.
    pub footprint: Option<crate::footprint::Footprint>,
    /// The decal pass's depth test (`glDepthFunc`), or `None` for the convention's strict test
    /// (`GL_LESS`, `GL_GREATER` under reversed Z). An `…EQUAL` test needs one quantum less
    /// offset and an occluder one quantum more separation: an engine that draws every pass
    /// with `GL_LEQUAL` must say so, or its bleed gap is a quantum too narrow.
    pub depth_test: Option<crate::recommend::DepthTest>,
    /// How the engine draws besides its matrix: world-space vertices, the viewport's origin,
    /// `glDepthRange` ([`crate::model::Pipeline`]; its `Default` is eye-space vertices, the
    /// viewport at the framebuffer's origin, `glDepthRange(0, 1)`), for the perspective and
    /// the orthographic model alike.
    pub pipeline: crate::model::Pipeline,
}

impl Decal {
    /// The profile the model uses: `profile`, or the worst case with `snapping`.
    pub fn rasterizer(&self) -> crate::recommend::RasterizerProfile {
        self.profile.unwrap_or(crate::recommend::RasterizerProfile {
            snapping: self.snapping,
            ..crate::recommend::RasterizerProfile::worst_case()
        })
    }
}

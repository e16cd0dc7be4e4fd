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
    /// How the rasterizer positions vertices before depth setup.
    pub snapping: Snapping,
}

//! The terms of the rasterizer model that every coplanar problem shares, one file per term.
//!
//! Every coplanar problem (a decal over its base, edges over their faces, a shadow receiver
//! over its own map) asks how far two depths of one plane, computed by different primitives,
//! can disagree on the rasterizer that draws them. The answer is a sum of terms, each a bound
//! on one step of the pipeline; the problems compose them ([`crate::recommend`] is the decal's,
//! [`crate::lines`] the edges', [`crate::shadow`] the shadow map's). Each term lives here, with
//! its derivation; `u = 2⁻²⁴` is the unit roundoff of f32 throughout.
//!
//! | file | term | what it bounds |
//! |---|---|---|
//! | [`pipeline`] | — | what the engine's pipeline is beside the projection: vertices in world space through an f32 model-view matrix, the viewport's origin in the framebuffer, `glDepthRange` |
//! | [`plane_form`] | — | a plane as the rasterizer sees it: its window-depth plane (affine in window `x`, `y` for every plane that covers a pixel, level ground under a level camera included) and the linear form on clip coordinates that measures how far a vertex's error moves depth off it |
//! | [`gradient`] | `b`, `e`, `g` | what the terms share: the depth mapping's scale `b = f·n/(f − n)`, the frustum's half-extent tangent `e`, the window gradient of a plane of slope `s` and the tilt `1 + s·e` on its axis crossing |
//! | [`quantum`] | `q` | the depth quantum: the smallest difference the stored format keeps, under `glDepthRange` |
//! | [`transform`] | `T` | f32 rounding of the vertex transform and the viewport map, per clip convention |
//! | [`vertex`] | `V` | f32 rounding of the vertices before the projection: eye coordinates rounded once, or world coordinates through the engine's f32 model-view matrix |
//! | [`interpolation`] | `I`, `G`, `M` | f32 rounding of the rasterizer's depth-plane set-up and evaluation, relative to the depth extrapolated from the framebuffer's origin (`G`); the magnitude `M` a measured figure scales |
//! | [`snap`] | `S` | sub-pixel snapping of a sloped plane before depth set-up; its `glPolygonOffset` factor |
//! | [`clip`] | `C` | the rasterizer's f32 clipping of a base that leaves the frustum, and the remedy: cutting it in f64 ([`clip::clip_to_frustum`]; stored in world space, [`clip::clip_to_frustum_stored`]) |
//! | [`measured`] | — | what a probed profile replaces: `T + I` by its per-pixel figure, `C` by its clipper's, the per-format index of its arrays |
//!
//! A plane's error `E = T + V + I` per primitive, with `S` beside it and `C` for a clipped base,
//! is what the problems budget; `q` is what the depth test needs on top under a strict test.

pub mod clip;
#[cfg(test)]
mod clipper_emulation;
pub mod gradient;
pub mod interpolation;
pub mod measured;
pub mod pipeline;
pub mod plane_form;
pub mod quantum;
pub mod snap;
pub mod transform;
pub mod vertex;

pub use pipeline::Pipeline;
pub use plane_form::PlaneForm;

/// `u = 2⁻²⁴`, the unit roundoff of f32: half an ulp of 1.
pub(crate) const F32_UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

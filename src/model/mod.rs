//! The terms of the rasterizer model that every coplanar problem shares, one file per term.
//!
//! Every coplanar problem (a decal over its base, edges over their faces, a shadow receiver
//! over its own map) asks how far two depths of one plane, computed by different primitives,
//! can disagree on the rasterizer that draws them. The answer is a sum of terms, each a bound
//! on one step of the pipeline; the problems compose them ([`crate::recommend`] is the decal's).
//! The terms that are new with the engine's own pipeline live here, each with its derivation:
//!
//! | file | term | what it bounds |
//! |---|---|---|
//! | [`pipeline`] | — | what the engine's pipeline is beside the projection: vertices in world space through an f32 model-view matrix, the viewport's origin in the framebuffer, `glDepthRange` |
//! | [`plane_form`] | — | a plane as the rasterizer sees it: its window-depth plane (affine in window `x`, `y` for every plane that covers a pixel, level ground under a level camera included) and the linear form on clip coordinates that measures how far a vertex's error moves depth off it |
//! | [`vertex`] | `V` | f32 rounding of the vertices before the projection: eye coordinates rounded once, or world coordinates through the engine's f32 model-view matrix |
//!
//! The other terms (`q`, `T`, `I`, `S`, `C`) are derived in [`crate::recommend`]'s module docs.

pub mod pipeline;
pub mod plane_form;
pub mod vertex;

pub use pipeline::Pipeline;
pub use plane_form::PlaneForm;

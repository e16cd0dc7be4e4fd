//! # zshift
//!
//! Ends z-fighting of coplanar geometry (decals, scorch marks, outlines) by offsetting depth
//! through the projection matrix, and tells exactly how much depth precision a projection has.
//!
//! ## Conventions
//! Unless a function says otherwise: OpenGL's right-handed eye space looking down −z; clip depth
//! in `[−w, w]`, NDC depth in `[−1, 1]`, window depth in `[0, 1]`; column-major matrices, as
//! `glLoadMatrixf` takes them. Distances `n`, `f`, `d` are positive; `Pz` is an eye-space z
//! (negative in front of the camera). `δ > 0` moves geometry toward the camera. All arithmetic
//! is f64; each matrix element is the f32 nearest its exact value ([`rounding`]), and where the
//! rounding direction matters (the offset element) it is chosen so the offset is never lost.
//!
//! ## Map of the modules
//! | module | computes | seeds |
//! |---|---|---|
//! | [`projection`] | the `glFrustum` matrix, finite or infinite far; `gluPerspective`, `[0, 1]` and reversed clip depth, tweaked infinite | 000 eq. 4.1.1, 003 |
//! | [`offset`] | ε from δ, the minimum ε and δ, offset matrices rounded outward | 000 eq. 4.1.3–4.1.11, 002 |
//! | [`precision`] | window depth and the exact depth step at a distance; per clip convention and depth format (`DepthMapping`, `DepthFormat`) | 001 |
//! | [`profile`] | what a rasterizer does that the offset model needs (snapping, polygon-offset `r`, clipping): plain data | |
//! | [`probe`] | measures a `RasterizerProfile` in the caller's GL context, through its function loader | |
//! | [`model`] | the rasterizer model's terms every coplanar problem composes, one file per term with its derivation: `q`, `T`, `V`, `I`, `S`, `C`, the plane's form, the engine's pipeline, what a probed profile replaces | 000, 001, 002, 004 |
//! | [`recommend`] | the decal problem: the offset a decal over its coplanar base needs on a real rasterizer, (R1) and the bleed gap (R2), from [`model`]'s terms | 000, 002, 004 |
//! | [`domain`] | validated planes, depths and depth bits (the input rules) | |
//! | [`clip_offset`] | offsets for every convention: constant NDC (element 10) or relative (element 14) | 000 eq. 4.1.3–4.1.7 |
//! | [`median`] | Kooima's median-distance projection, its GLSL and its depth offset | 003 |
//! | [`polygon_offset`] | eye-space δ ↔ `glPolygonOffset` units, D3D `DepthBias`, Vulkan `depthBiasConstantFactor` | 004 |
//! | [`plan`] | tight near/far planes, one offset for a depth range, stacked decal layers | 000, 001, 002 |
//! | [`lines`] | edges over their own faces (wireframe on shaded, outlines, hidden-line drawing): polygon offset for the faces or a matrix offset for the edges, and the hidden-line gap | 004 |
//! | [`steepest_face`] | a mesh's steepest face as drawn (its window-depth gradient from its triangles and matrix): the `face_gradient` an engine passes for its own mesh | 004 |
//! | [`decal`] | what an engine knows about a decal besides its matrix (the recommendation's input) | |
//! | [`matrix_in`] | the engine's own `float[16]` in, the decal's matrix out: recognised (perspective, infinite, tweaked, reversed, orthographic), one element offset, rounded outward | 000 eq. 4.1.3–4.1.7 |
//! | [`planes`] | one decal over several planes (a mesh decal over terrain): the largest of the planes' offsets, every plane's bleed gap at it | 000, 004 |
//! | [`orthographic`] | `glOrtho` for every clip convention, its constant offset through element 14, its (constant) depth step | |
//! | [`shadow`] | shadow-map bias: the smallest acne-free caster bias in every API's units, receiver-side offsets, peter-panning | 004 |
//! | [`rounding`] | how matrices reach f32: the nearest f32 of the exact element (proven fast test, exact fallback), offsets outward | |
//! | [`ffi`] | the C ABI (`include/zshift.h`): status codes, checks, panic boundary | |

#![warn(missing_docs)]

pub mod clip_offset;
pub mod decal;
pub mod depth_chain;
pub mod domain;
mod double_double;
pub mod error;
pub mod ffi;
pub mod footprint;
pub mod lines;
pub mod matrix_in;
pub mod median;
pub mod model;
pub mod offset;
pub mod orthographic;
pub mod plan;
pub mod planes;
pub mod polygon_offset;
pub mod precision;
pub mod probe;
pub mod profile;
pub mod projection;
pub mod recommend;
pub mod rounding;
pub mod shadow;
pub mod steepest_face;

pub use domain::{depth_steps, Planes};
pub use error::{Error, ErrorKind, Result};
/// The glam version this crate's API speaks (`Mat4`, `Vec3`), re-exported so callers need no
/// second, mismatched copy.
pub use glam;
pub use offset::{
    epsilon, epsilon_matrix, load_offset_matrix, max_delta_away, min_delta_toward, min_epsilon,
    offset_matrix,
};
pub use precision::{depth_resolution, window_depth};
pub use projection::{frustum, Frustum};

/// Deterministic uniform samples in `[0, 1)` for the unit tests (xorshift64 from `seed`).
#[cfg(test)]
pub(crate) fn test_uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// GLSL's `m * v` in f32 for the unit tests that emulate a shader: the columns summed left to
/// right, each product rounded, or fused into the sum (as a GPU may).
#[cfg(test)]
pub(crate) fn test_mat_vec_f32(m: &[f32; 16], v: [f32; 4], fused: bool) -> [f32; 4] {
    [0, 1, 2, 3].map(|r| {
        let mut acc = m[r] * v[0];
        for j in 1..4 {
            acc = if fused {
                m[4 * j + r].mul_add(v[j], acc)
            } else {
                acc + m[4 * j + r] * v[j]
            };
        }
        acc
    })
}

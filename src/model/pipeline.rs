//! What the engine's pipeline does besides the projection: where its vertices come from and
//! where its window lies.
//!
//! * **Vertices in world space.** Engines keep vertices in world (or model) space and transform
//!   them in the vertex shader with an f32 model-view (or model-view-projection) matrix; the
//!   roundings of that transform are absolute, relative to the world coordinates and the
//!   camera's position, not to the vertex's distance from the camera. [`Pipeline::world_reach`]
//!   states their size; [`crate::model::vertex`] derives the term.
//! * **The viewport's origin.** A rasterizer sets its depth plane up relative to the
//!   framebuffer's origin (Mesa llvmpipe's `a0 = z₀ − ∂z/∂x·x₀ − ∂z/∂y·y₀`), so a viewport at
//!   `(x, y)` in a larger framebuffer (split screen, editor panes) extrapolates the plane
//!   further, and the interpolation's roundings grow with it.
//! * **`glDepthRange(near, far)`** (Direct3D's viewport `MinDepth`/`MaxDepth`) maps NDC depth to
//!   `near + (far − near)·w`, `w` the unit window depth of `[0, 1]`: the format's quantum is
//!   `1/(far − near)` times larger against `w`, and the stored values lie near `near`, not 0.
//!
//! The model works in **unit window depth** `w` (what `glDepthRange(0, 1)` stores): every
//! offset and error term is a change of `w`, so an offset applied through the projection matrix
//! means the same whatever the depth range. [`Pipeline::actual`] maps `w` to the stored window
//! depth, [`Pipeline::per_unit`] converts a stored spacing back to `w`.

use crate::domain::{domain, finite};
use crate::error::Result;

/// How the engine draws, besides its projection matrix: the vertex pipeline before it and the
/// framebuffer state after it. The [`Default`] is the pipeline the model assumed before it knew
/// these: eye-space vertices, the viewport at the framebuffer's origin, `glDepthRange(0, 1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pipeline {
    /// 0 when base and decal vertices reach the vertex shader in eye space (relative to the
    /// camera, as camera-relative rendering sends them). Otherwise the largest magnitude of any
    /// coordinate of the camera's position, and of every model's origin, in the space the
    /// shader receives vertices in (world space for most engines): the f32 model-view's
    /// roundings are relative to it, however close the vertex is to the camera. The view and
    /// model matrices must be rigid (rotation and translation; with a uniform scale `k`, pass
    /// `k·world_reach`). See [`crate::model::vertex`].
    pub world_reach: f64,
    /// With `world_reach > 0`: the vertex shader computes the eye position first and applies
    /// the projection to it (`proj * (view * p)`, `proj * (modelView * p)`; three.js's
    /// `projectionMatrix * mvPosition`), so an error of the eye position moves the vertex along
    /// the plane as much as off it, and only the part off the plane counts. `false` (the
    /// conservative default) also covers one model-view-projection matrix (`mvp * p`, or GLSL's
    /// left-to-right `proj * view * model * p`), whose clip coordinates err independently, and
    /// one view-projection applied to world positions (bevy's
    /// `clip_from_world * (world_from_local * p)`, Unity's `UNITY_MATRIX_VP`): pass the camera's
    /// view and a box as for a model-view multiplied in double ([`Pipeline::view`];
    /// `tests/gl_engine_scene.rs` draws it). Its bleed gap is 6–12 times
    /// that of the same scene drawn eye first (median; `docs/engine-scene.md`).
    pub eye_first: bool,
    /// The f32 matrix the vertex shader applies to the positions it receives to make eye
    /// coordinates (the view, or model-view, matrix; column-major), with
    /// [`Pipeline::world_box`]: the model then knows each eye coordinate's rounding exactly
    /// instead of bounding it from `world_reach` over every rotation. Base and decal must both
    /// be drawn through it. A model with a matrix `M` of its own (a decal entity, a terrain
    /// chunk), drawn through the model-view `V·M`: pass the camera's view `V` and a
    /// [`Pipeline::world_box`] that reaches `|origin| + extent` on each axis (for a model
    /// centred on its origin: a box that holds its world corners), when `V·M` is multiplied in
    /// double and rounded once to f32 (`glm::dmat4`; [`crate::model::vertex`] shows why that is
    /// covered); multiplied in f32 (`glm::mat4`), pass `world_reach` instead, whose bound covers
    /// that product (`tests/gl_engine_scene.rs` draws both, for decals and terrain chunks).
    /// Base and decal drawn through one model-view (a decal on a vehicle, both in its model
    /// space): pass that model-view and the box of the model-space positions, however it was
    /// multiplied (both go through the same rounded matrix, which keeps them coplanar).
    /// `None`: not given.
    pub view: Option<[f32; 16]>,
    /// The box `[lo, hi]` of the base and decal positions the shader receives (in the space
    /// `view` maps from), with [`Pipeline::view`]. Only the base's triangles under the decal
    /// reach the decal's pixels: for a tessellated ground, the box of the cells the decal
    /// touches (with the decal's corners); for one large quad, its corners. `None`: not given.
    pub world_box: Option<[[f64; 3]; 2]>,
    /// `glViewport`'s `x` and `y`: the viewport's lower-left corner in the framebuffer, pixels.
    pub viewport_origin: [u32; 2],
    /// `glDepthRange(near, far)` (Direct3D: `MinDepth`, `MaxDepth`), `0 ≤ near < far ≤ 1`.
    pub depth_range: [f64; 2],
}

impl Default for Pipeline {
    fn default() -> Self {
        Self {
            world_reach: 0.0,
            eye_first: false,
            view: None,
            world_box: None,
            viewport_origin: [0, 0],
            depth_range: [0.0, 1.0],
        }
    }
}

impl Pipeline {
    /// `far − near` of the depth range: stored window depth per unit window depth.
    pub fn span(&self) -> f64 {
        self.depth_range[1] - self.depth_range[0]
    }

    /// The stored window depth of unit window depth `w`: `near + (far − near)·w`.
    pub fn actual(&self, w: f64) -> f64 {
        self.depth_range[0] + self.span() * w
    }

    /// A difference of stored window depth as a difference of unit window depth.
    pub fn per_unit(&self, stored: f64) -> f64 {
        stored / self.span()
    }

    /// Whether vertices reach the shader in world (or model) space: `world_reach > 0` or the
    /// view matrix given.
    pub fn world_space(&self) -> bool {
        self.world_reach > 0.0 || self.view.is_some()
    }

    /// Whether this is the default pipeline (the one the probe's facing figures were measured
    /// with: eye-space vertices, `glDepthRange(0, 1)`).
    pub fn is_default_depth(&self) -> bool {
        !self.world_space() && self.depth_range == [0.0, 1.0]
    }

    /// Checks every field, naming the bad one as the C field is spelled.
    ///
    /// # Errors
    /// [`crate::ErrorKind::NotFinite`] for a NaN or infinite `world_reach` or depth range end;
    /// [`crate::ErrorKind::Domain`] for a negative `world_reach`, or a depth range that is not
    /// `0 ≤ near < far ≤ 1` (an inverted one, `glDepthRange(1, 0)`, with the remedy:
    /// `glClipControl` and reversed Z).
    #[inline]
    pub fn check(&self) -> Result<()> {
        // The default pipeline, the usual case, passes at once (a box without its view is still
        // refused).
        if self.world_reach == 0.0
            && self.view.is_none()
            && self.world_box.is_none()
            && self.depth_range == [0.0, 1.0]
        {
            return Ok(());
        }
        self.check_fields()
    }

    /// [`Pipeline::check`] field by field.
    fn check_fields(&self) -> Result<()> {
        let w = self.world_reach;
        finite(w, "world_reach is NaN or infinite").map_err(|e| e.with_value("world_reach", w))?;
        if w < 0.0 {
            return Err(domain(
                "world_reach must be >= 0 (0: vertices reach the shader in eye space)",
            )
            .with_value("world_reach", w));
        }
        self.check_matrices()?;
        let [near, far] = self.depth_range;
        for (name, x) in [("depth_range_near", near), ("depth_range_far", far)] {
            finite(x, "a glDepthRange end is NaN or infinite")
                .map_err(|e| e.with_value(name, x))?;
        }
        if (0.0..=1.0).contains(&near) && (0.0..near).contains(&far) {
            // glDepthRange(1, 0): reversed depth without glClipControl. Not modelled (the
            // stored depth then falls as NDC depth rises); name the remedy that also keeps the
            // precision such a range loses (NDC depth near 1 is already rounded in f32).
            return Err(domain(
                "an inverted glDepthRange (far < near: reversed depth without glClipControl) is not modelled: for reversed Z use glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), a reversed projection, glDepthRange(0, 1) and ZSHIFT_CLIP_REVERSED_ZERO_TO_ONE (Python Clip.REVERSED_ZERO_TO_ONE), which also keeps the precision an inverted range loses",
            )
            .with_value("depth_range_far", far)
            .with_bound("depth_range_near", near));
        }
        if !(0.0..1.0).contains(&near) {
            return Err(domain(
                "glDepthRange's near end must lie in [0, 1) (pass 0 and 1 for the default)",
            )
            .with_value("depth_range_near", near));
        }
        if !(far > near && far <= 1.0) {
            return Err(domain(
                "glDepthRange's far end must lie in (depth_range_near, 1] (pass 0 and 1 for the default)",
            )
            .with_value("depth_range_far", far)
            .with_bound("depth_range_near", near));
        }
        Ok(())
    }

    /// The view matrix and the box: both or neither, finite, the box ordered.
    fn check_matrices(&self) -> Result<()> {
        match (self.view, self.world_box) {
            (None, None) => Ok(()),
            (Some(v), Some([lo, hi])) => {
                for x in v {
                    let x = f64::from(x);
                    finite(x, "an element of the view matrix is NaN or infinite")
                        .map_err(|e| e.with_value("view_matrix", x))?;
                }
                for k in 0..3 {
                    finite(lo[k], "a world_box coordinate is NaN or infinite")
                        .and_then(|_| finite(hi[k], "a world_box coordinate is NaN or infinite"))?;
                    if lo[k] > hi[k] {
                        return Err(domain(
                            "world_box must be [min x, min y, min z, max x, max y, max z] with each min <= its max",
                        )
                        .with_value("world_box min", lo[k]));
                    }
                }
                Ok(())
            }
            _ => Err(domain(
                "view_matrix and world_box go together: pass both (the model then knows each eye coordinate's rounding) or neither",
            )),
        }
    }
}

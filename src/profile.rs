//! What a rasterizer does that the offset model needs to know: a profile is plain data.
//!
//! No vendor documents how it snaps vertices before depth setup, how it clips a primitive that
//! crosses the near plane, or how it scales `glPolygonOffset` units (the minimum resolvable
//! difference `r` is 1×, 2× or 4× a format's quantum depending on the GPU). A
//! [`RasterizerProfile`] holds those facts. [`RasterizerProfile::worst_case`] (the `Default`)
//! assumes the worst of each and is what the recommendation uses unless told otherwise; a
//! measured profile comes from [`crate::probe::probe`], which draws in the caller's own GL
//! context (C: `zshift_probe`, `ZshiftProfile`).

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
    /// is set up from them: the worst case, and what Mesa's llvmpipe does. The probe reports it
    /// whenever ground planes crossing the near plane stray from their exact plane by more than
    /// twice (plus 2 D24 quanta) what the same planes do when clipped in f64 before drawing —
    /// whatever the cause (a float clipper, or, without clipping, the far-behind vertices' own
    /// transform error): the model must add the clipping terms. On llvmpipe the clipper is the
    /// cause: fed exact f32 clip coordinates (no transform), the clipped planes still erred by
    /// 103 D24 quanta.
    ClippedF32,
    /// A primitive crossing the near plane keeps the depth of its plane to within the same
    /// per-pixel error as one that does not (homogeneous rasterization, a clipper working in
    /// higher precision, or one that interpolates depth from the original vertices): ground
    /// planes with corners ±1000 behind and ahead of the camera, clipped by the rasterizer, err
    /// at most twice (plus 2 D24 quanta) what they do when clipped in f64 before drawing. The
    /// model's `C` is then that excess: the base's own `E + S` plus 2 D24 quanta.
    PlanePreserving,
}

/// The per-device facts the offset model needs. See the module docs.
///
/// Each field has one definition, here; [`crate::recommend`] says how each enters the model
/// ("A measured profile"): `snapping` sets the term `S`, `resolvable` the `glPolygonOffset`
/// equivalent, `near_clip` decides the term `C` of a base the rasterizer clips, `error_ulps`
/// (`error_ulps_reversed` under reversed Z) replaces the per-quad bound `T + I` by the measured
/// `k·u·(c + M)`, and the facing figures replace `q + 2T` for facing planes with shared f32 z.
/// `plane_error` and `plane_error_reversed` are summaries for reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RasterizerProfile {
    /// Whether vertex positions are snapped before depth setup.
    pub snapping: Snapping,
    /// `glPolygonOffset`'s minimum resolvable difference `r` per format (D16, D24, D32, D32F):
    /// what one unit of `glPolygonOffset(0, 1)` moves window depth by, in units of the format's
    /// quantum (UNORM: `1/(2^m − 1)`; D32F: `2^(e−23)`, `e` the exponent of the primitive's
    /// largest depth). Finite and > 0. The recommendation's `glPolygonOffset` units are its
    /// constant offset over `r·q`; the worst case is 1 (the smallest `r` of any implementation
    /// known: units computed against it are enough wherever `r` is larger). Measured on
    /// llvmpipe: 2 on D16/D24/D32, 1 on D32F.
    pub resolvable: [f64; 4],
    /// The worst `|stored − exact|` window depth per pixel of a plane (facing to grazing), per
    /// format (D16, D24, D32, D32F), under the standard `[−1, 1]` mapping, in units of the
    /// format's quantum `1/(2^m − 1)`; for D32F in units of 2⁻²⁴ (float depth's error is mostly
    /// absolute). NaN where not measured. The planes are drawn as an engine draws them — f32
    /// eye-space vertices times an f32 projection in the vertex shader — and "exact" is the
    /// plane through the vertices times the matrix in f64, so the figure covers the f32
    /// transform, the division by `w`, the viewport transform, depth setup, interpolation and
    /// the conversion to the format (rounding included), not the rounding of the coordinates
    /// themselves. A summary for reports: the model uses `error_ulps`, which scales with each
    /// scene's planes.
    pub plane_error: [f64; 4],
    /// D32F's `plane_error` under reversed Z (`glClipControl(GL_ZERO_TO_ONE)`, window depth
    /// `n(f − d)/((f − n)d)`), in units of the f32 spacing `2^(e − 23)` at the primitive's
    /// largest window depth (errors there are relative); NaN where not measured (no
    /// `glClipControl`). A summary for reports, like `plane_error`.
    pub plane_error_reversed: f64,
    /// The per-pixel error of the depth the rasterizer computes (before conversion to the
    /// stored format), in f32 unit roundoffs `u = 2⁻²⁴` of `1 + M`: every measured pixel under
    /// `[−1, 1]` kept `|computed − exact| ≤ error_ulps·u·(1 + M)`, with
    /// `M = |w₀| + |∂w/∂x|·x + |∂w/∂y|·y` the magnitude of the terms when the plane's window
    /// depth is evaluated from the window origin (`w₀` the plane's depth extrapolated to window
    /// `(0, 0)`, `∂w/∂x`, `∂w/∂y` its window-depth gradients per pixel, `x`, `y` the pixel's
    /// window coordinates; the 1 stands for the transform's and the viewport mapping's own
    /// roundings). On D32F the stored depth is the computed one; on the UNORM formats the probe
    /// takes the stored error less one quantum of conversion, and the figure is the largest over
    /// the formats. "Exact" is the plane through the f32 vertices, as for `plane_error`. NaN
    /// where not measured. A sampled maximum (over about 300 planes), not a proof: the model
    /// uses it for `T + I` (see [`crate::recommend`], "A measured profile", for how far other
    /// planes were checked).
    pub error_ulps: f64,
    /// `error_ulps` under reversed Z (`glClipControl(GL_ZERO_TO_ONE)`, D32F, window depth
    /// `n(f − d)/((f − n)d)`): every measured pixel kept `|computed − exact| ≤
    /// error_ulps_reversed·u·(|m10| + M)`, `M` as for `error_ulps` and `|m10| = n/(f − n)` the
    /// transform's constant part (the product `m10·z`; the sum and the division are relative to
    /// the depth, which `M` covers). NaN where not measured (no `glClipControl`). A sampled
    /// maximum, like `error_ulps`.
    pub error_ulps_reversed: f64,
    /// The window-depth offset, per format (D16, D24, D32, D32F), in units of the format's
    /// quantum `1/(2^m − 1)` (D32F: of 2⁻²⁴), that a decal facing the camera needs to pass
    /// `GL_LESS` over its base when every corner of both has the same f32 z and the decal's
    /// matrix differs from the base's only in element 10 (moved toward 0): measured at 256 depths
    /// (each its own phase between two stored values, window depth 0.02 to 0.9995, two frusta)
    /// under `[−1, 1]`, the largest. Replaces the model's `q + 2T` for such scenes
    /// ([`crate::recommend::Scene::exact_depth`], strict test, `[−1, 1]`). NaN where not
    /// measured (D16, whose quantum is hundreds of element-10 steps).
    pub facing_quanta: [f64; 4],
    /// `facing_quanta` under `[0, 1]` depth (`glClipControl(GL_ZERO_TO_ONE)`, standard, not
    /// reversed), where one step of element 10 moves window depth twice as far; used for such
    /// scenes under [`crate::projection::ClipDepth::ZeroToOne`]. NaN where not measured (no
    /// `glClipControl`, or D16).
    pub facing_quanta_zero_to_one: [f64; 4],
    /// Under reversed Z on D32F (`glClipControl(GL_ZERO_TO_ONE)`, `GL_GREATER`): the relative
    /// offset `ε` (element 14 scaled by `1 + ε`), in units of 2⁻²⁴, that a facing decal sharing
    /// its base's f32 z needs, the largest over 256 depths (window depth 10⁻⁵ to 0.9); used for
    /// such scenes under [`crate::projection::ClipDepth::ReversedZeroToOne`] with D32F. NaN
    /// where not measured.
    pub facing_reversed: f64,
    /// The f32 arithmetic from a facing vertex's eye depth to its stored value, when the probe
    /// identified it: the one candidate of [`crate::depth_chain`] that reproduced, bit for bit,
    /// every stored depth of its facing planes (256 depths per mode, each at several offsets, on
    /// D16, D24 and D32F, under `[−1, 1]`, `[0, 1]` and reversed Z). `None` for the worst case, or
    /// where no candidate reproduced them all. The model then computes a shared-z facing decal's
    /// offset exactly ([`crate::depth_chain::steps_to_pass`]) instead of taking
    /// `facing_quanta`'s worst phase.
    pub facing_chain: Option<crate::depth_chain::DepthChain>,
    /// How primitives crossing the near plane are clipped: decides the term `C` of a base the
    /// rasterizer clips ([`NearClip`]).
    pub near_clip: NearClip,
    /// Under [`NearClip::ClippedF32`]: the clipper's measured error in the model's own units.
    /// The term `C` of a clipped base is `(window/NDC)·γ·L(A)/d₁` ([`crate::recommend`], "The
    /// base"), with `γ = (6 + 5·6)·u` bounding every rounding of six clip stages. The probe draws,
    /// on D24, ground planes reaching 1000 and 10⁴ units behind and ahead of the camera (floors
    /// seen level and pitched, turned about the vertical, and sloped planes) and 48 planes in
    /// random directions (slopes 0.3 to 10, crossing the view axis 1 to 40 units ahead, reaching
    /// 100 times that), through a centred, an off-centre and an axis-off frustum; each once as
    /// given (the rasterizer clips it) and once cut to the frustum in f64. Every pixel of the
    /// first stayed within `clip_ulps·u·(window/NDC)·L(A)/d` of its plane beyond the second's
    /// error at that pixel (less one quantum of conversion), under `[−1, 1]` and, where
    /// `glClipControl` exists, `[0, 1]` and reversed Z: 0.86 on llvmpipe (0.84, 0.86 and 0.22).
    /// NaN where not measured. The model takes `γ = 4·clip_ulps·u` where below the bound: a
    /// sampled maximum, it is exceeded by a few steep clipped planes of `tests/gl_scenes.rs`'s
    /// full grid (up to 2), hence the margin ([`crate::model::clip`]).
    pub clip_ulps: f64,
    /// How far from the pixel a 1-pixel line fragment takes its depth: the largest
    /// `|stored − plane at the pixel centre| / max(|gₓ|, |g_y|)` over the fragments of lines drawn
    /// in sloped planes (`gₓ`, `g_y` the plane's window-depth gradients per pixel), in pixels,
    /// for `GL_LINES` of width 1 (`[0]`) and for triangles drawn under
    /// `glPolygonMode(GL_LINE)` (`[1]`), single-sampled. [`crate::lines`] takes it for its reach
    /// `Δ` (worst case `(w + 1)/2`, 1 pixel at width 1); wider lines add `(w − 1)/2`. NaN where
    /// not measured. Measured on llvmpipe: 0.5 and 0.72 (its unfilled stage draws the
    /// triangle's edges with their own set-up). A sampled maximum (96 lines, 48 triangles).
    pub line_reach: [f64; 2],
    /// How far a polygon-mode outline takes its depth off its side's line, onto the
    /// neighbouring face, in pixels of the triangle's `max(|gₓ|, |g_y|)`: the largest
    /// `|stored − side's depth|` over fragments of 1-pixel outlines beyond a side of constant
    /// depth (outside its triangle: where a neighbour's face is). Near 0 (f32 noise: 6·10⁻⁶ on
    /// llvmpipe) where the outline's depth follows its line, as Mesa's draw module draws it; up to
    /// the fragment's distance from the side where a rasterizer evaluates the triangle's plane
    /// there. [`crate::lines`] then adds the neighbour's slope term (worst case: the whole reach).
    /// NaN where not measured. A sampled maximum (16 sides).
    pub outline_neighbour: f64,
    /// How far from a sample a multisampled 1-pixel line's sample takes its depth: the largest
    /// `|stored − plane at the sample| / max(|gₓ|, |g_y|)` over every sample of the
    /// [`RasterizerProfile::line_reach`] lines and outlines drawn into a multisampled
    /// `GL_DEPTH_COMPONENT32F` texture (each sample copied out with `texelFetch`, compared with
    /// the plane at its `glGetMultisamplefv` position), at 4 samples and at the context's largest
    /// count up to 16, the larger; `GL_LINES` (`[0]`) and polygon-mode lines (`[1]`), pixels.
    /// [`crate::lines`] takes it for its reach under MSAA (worst case `√2·(w + 1)/2`, 1.41 pixels
    /// at width 1); wider lines add `√2·(w − 1)/2`. Measured on llvmpipe: 1.056 and 1.054 (a
    /// sample takes the line's depth about a pixel from itself along the gradient). NaN where not
    /// measured. A sampled maximum (2048 lines and 2048 triangles in 32 gradient directions, every
    /// sample).
    pub line_reach_msaa: [f64; 2],
    /// How far from the pixel a 3-pixel line fragment takes its depth: the largest
    /// `|stored − plane at the pixel centre| / max(|gₓ|, |g_y|)` over the fragments of the
    /// [`RasterizerProfile::line_reach_msaa`] geometry drawn single-sampled at `glLineWidth(3)`,
    /// `GL_LINES` (`[0]`) and polygon-mode lines (`[1]`), pixels. [`crate::lines`] takes the
    /// polygon-mode figure for wide outlines (worst case `(w + 1)/2 + 1/8`, 2.125 at width 3);
    /// wider ones add `(w − 3)/2`. Measured on llvmpipe: 1.5006 and 1.5007. NaN where not measured
    /// (a forward-compatible core context refuses the width). A sampled maximum.
    pub line_reach_wide: [f64; 2],
    /// How far a multisampled 1-pixel line's sample is, in any direction, from the point whose
    /// depth it takes: the largest `|stored − plane at the sample| / |∇z|` (the whole gradient,
    /// not its larger component) over the [`RasterizerProfile::line_reach_msaa`] samples,
    /// `GL_LINES` (`[0]`) and polygon-mode lines (`[1]`), pixels. [`crate::lines`] takes it
    /// against a bound on a face's gradient length (a face-slope angle, a mesh's own faces;
    /// worst case `(w + 1)/2`, 1 pixel at width 1) for 1-pixel lines; wider ones take
    /// [`RasterizerProfile::line_reach_msaa_wide_whole`]. Measured on llvmpipe: 0.865 and 0.866,
    /// on an NVIDIA H200 0.5005 and 0.5007 (the sample's projection on the line). NaN where not
    /// measured.
    pub line_reach_msaa_whole: [f64; 2],
    /// The same at `glLineWidth(3)`: how far, in any direction, a multisampled 3-pixel line's
    /// sample is from the point whose depth it takes, over the
    /// [`RasterizerProfile::line_reach_msaa`] geometry drawn multisampled at that width,
    /// `GL_LINES` (`[0]`) and polygon-mode lines (`[1]`), pixels. [`crate::lines`] takes it for
    /// multisampled lines wider than 1 against a bound on a face's gradient length (worst case
    /// `(w + 1)/2`, 2 pixels at width 3), adding `(w − 3)/2` beyond width 3. Measured on
    /// llvmpipe: 1.656 and 1.652; on an NVIDIA H200 1.5000 and 1.4999. NaN where not measured
    /// (a forward-compatible core context refuses the width).
    pub line_reach_msaa_wide_whole: [f64; 2],
    /// `glPolygonOffset`'s slope rule: the offset of `glPolygonOffset(1, 0)` on a plane with
    /// `|gₓ| = |g_y| = g`, over `g`: 1 where the slope term is `max(|gₓ|, |g_y|)` (GL's rule,
    /// llvmpipe), `√2` where it is their root sum of squares (allowed by Vulkan and Direct3D).
    /// [`crate::lines`] multiplies a face's push by it in the hidden-line gap (worst case `√2`).
    /// NaN where not measured.
    pub offset_slope: f64,
    /// `false` for [`RasterizerProfile::worst_case`]; `true` for a profile the probe measured.
    /// The model uses `error_ulps` only from a measured profile; every other field always.
    pub measured: bool,
    /// How long the probe took to measure this profile, in seconds (0 for
    /// [`RasterizerProfile::worst_case`]). Informational: the model ignores it.
    pub probe_seconds: f64,
}

/// The line width, pixels, [`RasterizerProfile::line_reach_wide`] is measured at (the wide lines
/// engines still draw: selection outlines, CAD silhouettes): the probe draws at it, the model
/// scales from it.
pub(crate) const WIDE_LINE_WIDTH: f32 = 3.0;

impl RasterizerProfile {
    /// The profile that assumes the worst of every fact: 8 sub-pixel bits of snapping, `r` of 1
    /// quantum (the most `glPolygonOffset` units), per-pixel errors as the model bounds them,
    /// clipping in f32.
    pub fn worst_case() -> Self {
        Self {
            snapping: Snapping::SubpixelBits(8),
            resolvable: [1.0; 4],
            plane_error: [f64::NAN; 4],
            plane_error_reversed: f64::NAN,
            error_ulps: f64::NAN,
            error_ulps_reversed: f64::NAN,
            facing_quanta: [f64::NAN; 4],
            facing_quanta_zero_to_one: [f64::NAN; 4],
            facing_reversed: f64::NAN,
            facing_chain: None,
            near_clip: NearClip::ClippedF32,
            clip_ulps: f64::NAN,
            line_reach: [f64::NAN; 2],
            outline_neighbour: f64::NAN,
            line_reach_msaa: [f64::NAN; 2],
            line_reach_wide: [f64::NAN; 2],
            line_reach_msaa_whole: [f64::NAN; 2],
            line_reach_msaa_wide_whole: [f64::NAN; 2],
            offset_slope: f64::NAN,
            measured: false,
            probe_seconds: 0.0,
        }
    }
}

impl Default for RasterizerProfile {
    fn default() -> Self {
        Self::worst_case()
    }
}

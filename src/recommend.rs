//! The decal problem: the offset a real rasterizer needs for a decal over its coplanar base,
//! from the error model of how a decal's stored depth can differ from its base's, and the
//! smallest projection-matrix offset that beats every term of it.
//!
//! # The model
//! A decal drawn over a coplanar base survives at a pixel when its stored depth passes the
//! depth test against the base's. The offset projection (seed 000, eq. 4.1.4) lowers the
//! decal's NDC depth by the constant `Δndc = −ε·m10 = |ε|·(f+n)/(f−n)`, i.e. window depth by
//! `Δw = Δndc/2`. Each quad's computed window depth at a pixel differs from the exact depth of
//! the plane by at most `E + S` (terms below), the base's by `C` more when the rasterizer clips
//! it; stored values keep their order once two computed values are a quantum `q` apart (the
//! conversion to the stored format is monotone), and computed values in order store in order.
//! So no decal pixel is lost when
//!
//! `Δw ≥ q + 2(E + S) + C`  under `GL_LESS` (`GL_GREATER` reversed),
//! `Δw ≥ 2(E + S) + C`      under `GL_LEQUAL` (`GL_GEQUAL`): a tie passes,        (R1)
//!
//! and zshift recommends exactly the right-hand side: `ε = −2·Δw / |m10|`, rounded outward into
//! element 10 by [`crate::offset::epsilon_matrix`]. The terms are shared with the other
//! coplanar problems and live in [`crate::model`], one file per term with its derivation (all
//! in window-depth units, `u = 2⁻²⁴`, `d₁ ≤ d₂` the decal's nearest and farthest eye depths,
//! `b = f·n/(f−n)`, `s` the plane's eye-space slope `|∂z/∂x| + |∂z/∂y|` and
//! `e = max(|l|, |r|, |b|, |t|)/n`):
//!
//! * `q`, the **depth quantum** at the decal's farthest point ([`crate::model::quantum`]).
//! * `E = T + V + I`, the **plane error** of one quad:
//!   * `T`, **f32 rounding of the vertex transform** ([`crate::model::transform`]). It applies
//!     even to bit-identical vertices, because the decal's element 10 differs from the base's.
//!   * `V`, **f32 rounding of the vertex coordinates** ([`crate::model::vertex`]): the decal's
//!     corners are not the base's; `V = u·(b/d₁)·(1 + s·e)` for eye-space vertices. Zero when
//!     every corner of base and decal has the same f32 z ([`Scene::exact_depth`]).
//!   * `I`, **f32 interpolation** ([`crate::model::interpolation`]), relative to the depth
//!     extrapolated from the framebuffer's origin. Zero with [`Scene::exact_depth`].
//! * `S`, **sub-pixel snapping** ([`crate::model::snap`]; 0 on a rasterizer that sets depth up
//!   from unsnapped positions, [`Snapping::Unsnapped`]).
//! * `C`, **the base's f32 clipping** ([`crate::model::clip`]; 0 for [`Base::InsideFrustum`]):
//!   see "The base".
//!
//! A measured profile replaces some of them by what the probe found
//! ([`crate::model::measured`]).
//!
//! No term is a fudge factor and there is no safety margin: each is a worst-case bound on one
//! rounding or snapping step, or a figure measured on the rasterizer that draws.
//!
//! [`recommend`] covers the standard `glFrustum` mapping (NDC depth `[−1, 1]`,
//! `glDepthRange(0, 1)`); [`recommend_clip`] applies the same model to the other conventions.
//!
//! # The depth test and the bleed gap
//! [`Scene::depth_test`] is the decal pass's `glDepthFunc`. Under the strict tests the decal's
//! stored depth must differ from the base's, hence `q` in (R1); under `GL_LEQUAL`/`GL_GEQUAL`
//! equal stored values pass, so computed values in order suffice and (R1) drops `q`.
//!
//! An occluder in front of the base must not lose to the decal. The occluder is a quad like the
//! decal (inside the frustum), with the same error `E + S`; under a strict test the decal
//! loses to it once its computed depth is at or behind the occluder's, under an `…EQUAL` test
//! only once it is a quantum behind (a tie passes: at the `GL_LESS` gap an occluder can store the
//! decal's very value). So an occluder whose exact window depth is in front of the base's by
//!
//! `G_w = Δw + 2(E + S)` (strict),  `G_w = Δw + 2(E + S) + q` (`…EQUAL`)             (R2)
//!
//! is never overdrawn. [`Recommendation::bleed_gap`] is that separation as an **eye depth**:
//! the difference of `−z` between base and occluder at the same pixel (not a Euclidean distance
//! along the ray, which is longer off-axis), taken at `d₂` where it is largest for a given
//! window separation (`G = d·x/(1 + x)`, `x = G_w·d/b`).
//!
//! # The base
//! The base is what the engine knows least about, and what breaks a model that treats it like
//! the decal: a floor running behind the camera is clipped by the rasterizer, which computes
//! the new vertices in f32. [`Base`] says whether that happens: [`Base::InsideFrustum`] (the
//! rasterizer clips nothing) or [`Base::Clipped`] with the base's `reach` `R`, the largest
//! `|x|`, `|y|` or `|z|` of its eye-space vertices. The term `C` of a clipped base
//! ([`crate::model::clip`]) is a sound bound but a large one; where it would move the decal past
//! the near plane [`recommend`] refuses ([`crate::ErrorKind::Unresolvable`], "cut the base to
//! the frustum"); elsewhere it answers, and the bleed gap says what the answer costs. **The
//! remedy is [`clip_to_frustum`]**: cut the base polygon in f64 to the frustum shrunk by 2⁻¹⁶,
//! draw the result as a fan, and pass [`Base::InsideFrustum`]: the base's error is then the
//! decal's `E`.
//!
//! # A measured profile
//! [`Scene::profile`] is a [`RasterizerProfile`]; the default,
//! [`RasterizerProfile::worst_case`], uses the bounds of [`crate::model`]. A profile the probe
//! measured ([`crate::probe::probe`], in the engine's own context) enters the model field by
//! field, as [`crate::model::measured`] describes: `error_ulps` replaces `T + I` (a measured
//! figure, not a proof), the footprint ([`Scene::footprint`]) replaces the extrapolation bounds,
//! `near_clip` and `clip_ulps` (with a margin of 4) the clipping term, `resolvable` `r` sets
//! [`Recommendation::polygon_offset`]'s units `(Δw − 2S)/(r·q)`, and the facing figures are the
//! decal's own (next section).
//!
//! # Correlated errors
//! Base and decal errors are independent in size in general: the rounding of two different
//! products is. One case is correlated in full: a plane facing the camera whose every corner
//! (base and decal) has the same f32 z ([`Scene::exact_depth`]), drawn with the same program.
//! Every vertex of both then has the same computed depth but for element 10, the plane is
//! constant (zero gradients are exact), and every step of the chain — `m10·z`, `+ m14`, the
//! division by `w`, the viewport map, the conversion — is monotone in element 10: the decal's
//! stored depth is never behind the base's. Under `GL_LEQUAL`/`GL_GEQUAL` (a tie passes) that
//! is enough, and the recommendation is no offset at all ([`ErrorTerms::correlated`]); the gap
//! keeps the occluder's error. Under the strict tests the decal's depth must drop a whole
//! quantum, and each rounding step can lose up to one unit of its own result whatever the
//! correlation, so (R1) stands as a bound; but the whole chain is one function of element 10
//! and the depth, the same for every such scene, so the probe measures it directly
//! ([`RasterizerProfile::facing_quanta`]: the offset the worst of 256 depth phases needs, 3 D24
//! quanta on llvmpipe where `q + 2T` is about 7; under `[0, 1]`
//! [`RasterizerProfile::facing_quanta_zero_to_one`]), and a measured profile uses that figure
//! instead ([`ErrorTerms::facing`]). Under reversed Z the offset is relative (element 14), so the
//! probe measures the relative `ε` on D32F ([`RasterizerProfile::facing_reversed`]), which
//! replaces `reversed_epsilon`'s for such scenes.
//!
//! Where the probe has also **identified the chain** ([`RasterizerProfile::facing_chain`]: the
//! one candidate f32 arithmetic of [`crate::depth_chain`] that reproduced every stored depth of
//! its facing planes bit for bit), no worst phase is needed: the exact f32 steps this scene's
//! depth needs are computed by emulating that arithmetic ([`crate::depth_chain::steps_to_pass`]),
//! the largest over elements 10 and 14 within 2 f32 steps of zshift's matrix (an engine's own
//! `glFrustum` code may round them differently) and over `m10·z + m14` fused or not (it runs in
//! the engine's own vertex shader, which its compiler may contract differently from the probe's),
//! and the offset requested is `k − 0.45` steps,
//! which the outward rounding of the offset matrix turns into `k` (or `k + 1`). This needs the
//! decal's depth as the f32 it is drawn at (`depth_range[0] == depth_range[1]`, an f32 value).
//! It costs 50 emulated searches, about 2–3 µs per recommendation (against about 0.1 µs for the
//! bound).
//!
//! # Other clip conventions
//! Every `glFrustum`-family mapping stores `w(d) = α ± b/d` with the same `b = f·n/(f − n)` (`n`
//! for `f = ∞`; [`crate::precision::DepthMapping`]), so `|dw/dd| = b/d²` and the window
//! gradients of a sloped plane are the same in every convention: `V`, `I`, `S` and `C` keep their
//! form (`C` through the convention's `m10`, `m14`). What changes:
//!
//! | term | `[−1, 1]` (`GL_LESS`/`GL_LEQUAL`) | `[0, 1]` (`GL_LESS`/`GL_LEQUAL`) | reversed `[0, 1]` (`GL_GREATER`/`GL_GEQUAL`, clear 0) |
//! |---|---|---|---|
//! | window depth | `½·ndc + ½` | `ndc` | `ndc`, `n(f − d)/((f − n)d)` |
//! | `q` | at `w(d₂)` | at `w(d₂)` | at `w(d₂)`: relative for D32F, `2^(e−23)` at `w ≈ n/d` |
//! | `T` | `u·(│m10│/2 + 1.5·│ndc│ + w)` | `u·(│m10│ + 4·w_max)` | `u·(│m10│ + 4·w_max)`, `m10 = n/(f−n)` (0 at `f = ∞`) |
//! | offset | `ε` on element 10 | constant `c = −Δw` on element 10 | relative `ε` on element 14 |
//! | `Δw` at `d` | `Δw` | `Δw` | `ε·b/d` |
//!
//! Under `[0, 1]` the NDC depth is the window depth, so the transform's roundings are no longer
//! halved ([`crate::model::transform`]). The offset stays a constant through element 10
//! ([`crate::clip_offset::ndc_offset_matrix`]), (R1) unchanged.
//!
//! Under reversed Z the offset is relative ([`crate::clip_offset::relative_offset_matrix`]:
//! element 14 scaled by `1 + ε` moves every point from `d` to `d/(1 + ε)`), which gives the
//! window offset `ε·b/d` at `d`: it shrinks with distance as D32F's spacing does, and exists
//! where `m10 = 0`. (R1) must hold at every `d` of the decal, so
//! `ε = max_d (q(w(d)) + 2(E + S) + C)·d/b` (no `q` under `GL_GEQUAL`): the budget part peaks at
//! `d₂`, the quantum part at `d₂` or where `w(d)` crosses a power of two (within a binade the
//! spacing is constant and `d/b` grows as `w` falls); both are evaluated, and `ε` is divided by
//! `1 − u` for element 14's own f32 rounding. The bleed gap is (R2) at `d₁` and `d₂`, the larger.
//!
//! # Verified on llvmpipe
//! `tests/gl_scenes.rs` draws ground planes running behind the camera (clipped by the
//! rasterizer, and cut by [`clip_to_frustum`]), screen-fitted bases, slopes 0 to 10 with horizons
//! on screen, 97×211, 320×180 and 64×48 viewports, centred and off-centre frusta (one with the
//! view axis off screen), f/n from 10 to 1e7 and ∞, D16/D24/D32F under all three conventions and
//! both kinds of depth test, decals whose corners are not the base's, with the worst-case
//! profile and the profile [`crate::probe::probe`] measures in the test's context: no pixel lost
//! at the recommendation, none bled at the gap, in every scene; the README ("Verified on a rasterizer") has the ratios per class.
//!
//! # Relation to glPolygonOffset
//! `glPolygonOffset(factor, units)` adds `factor·M + units·r` to window depth, `M` the polygon's
//! largest depth gradient per pixel and `r` the format's smallest resolvable difference. (R1)
//! is the same shape: `q`, `2E` and `C` are constants (`units = (Δw − 2S)/r`) and the snapping
//! term `2S ≤ 2^-b·2M` is slope-scaled (`factor = 2^(1−b)`). The matrix offset is one constant
//! for the whole decal, so zshift evaluates the slope term at the decal's worst depth instead of
//! per polygon; [`Recommendation::polygon_offset`] gives the equivalent pair, with `r` the
//! profile's [`RasterizerProfile::resolvable`] quanta (1 in the worst case, the smallest known;
//! 2 measured on llvmpipe, whose `lp_state_setup.c` scales units by `2·mrd`).

use crate::domain::{domain, finite, representable};
use crate::error::Result;
use crate::model::gradient::{half_extent_tangent, scale, tangents_of};
use crate::model::measured::{measured_figure, measured_plane_error, profile_index};
use crate::model::quantum::unit_quantum;
use crate::model::F32_UNIT_ROUNDOFF;
use crate::model::{clip as clip_model, interpolation, snap as snap_model, transform};
use crate::precision::{DepthMapping, WINDOW_ESTIMATE_ERROR};
use crate::projection::{ClipDepth, Frustum};

/// Cuts a base polygon to the view frustum in f64, so the rasterizer clips nothing (the term
/// `C`'s remedy, see [`crate::model::clip`]).
pub use crate::model::clip::clip_to_frustum;

/// The decal's window-space geometry (see [`crate::footprint`]).
pub use crate::footprint::{decal_shape, DecalShape, Footprint};

/// How the engine draws besides its projection (see [`crate::model::pipeline`]).
pub use crate::model::Pipeline;
use crate::model::{vertex, PlaneForm};

/// What the depth attachment stores: the crate's one depth-format type.
pub use crate::precision::DepthFormat;

/// Whether the rasterizer snaps vertex positions before depth setup (see [`crate::profile`]).
pub use crate::profile::Snapping;

/// The per-device facts the model takes (see [`crate::profile`]).
pub use crate::profile::{NearClip, RasterizerProfile};

/// The depth test of the decal pass (`glDepthFunc`). The strict tests need the decal's stored
/// depth a quantum past the base's; the `…Equal` tests let a tie pass, so the decal needs one
/// quantum less offset and an occluder one quantum more separation (see "The depth test").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DepthTest {
    /// `GL_LESS` (`[−1, 1]` and `[0, 1]` clip depth).
    #[default]
    Less,
    /// `GL_LEQUAL` (`[−1, 1]` and `[0, 1]` clip depth).
    LessEqual,
    /// `GL_GREATER` (reversed Z).
    Greater,
    /// `GL_GEQUAL` (reversed Z).
    GreaterEqual,
}

impl DepthTest {
    /// The test for a `glDepthFunc` enum value (`GL_LESS` 0x0201, `GL_LEQUAL` 0x0203,
    /// `GL_GREATER` 0x0204, `GL_GEQUAL` 0x0206).
    ///
    /// # Errors
    /// [`crate::ErrorKind::Domain`] for any other value (`GL_EQUAL`, `GL_ALWAYS`, …: no offset
    /// makes a decal win under them).
    pub fn from_gl(func: u32) -> Result<Self> {
        match func {
            0x0201 => Ok(Self::Less),
            0x0203 => Ok(Self::LessEqual),
            0x0204 => Ok(Self::Greater),
            0x0206 => Ok(Self::GreaterEqual),
            _ => Err(domain(
                "the depth test must be GL_LESS, GL_LEQUAL, GL_GREATER or GL_GEQUAL",
            )),
        }
    }

    /// The `glDepthFunc` enum value.
    pub fn gl_enum(self) -> u32 {
        match self {
            Self::Less => 0x0201,
            Self::LessEqual => 0x0203,
            Self::Greater => 0x0204,
            Self::GreaterEqual => 0x0206,
        }
    }

    /// `GL_LESS` or `GL_GREATER`: a tie fails.
    pub fn is_strict(self) -> bool {
        matches!(self, Self::Less | Self::Greater)
    }

    /// `GL_GREATER` or `GL_GEQUAL`: the reversed-Z tests.
    pub fn is_reversed(self) -> bool {
        matches!(self, Self::Greater | Self::GreaterEqual)
    }
}

/// What the engine knows about the base (the surface under the decal).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Base {
    /// Every vertex of the base lies inside the view frustum, so the rasterizer clips nothing
    /// (a base cut to the frustum by [`clip_to_frustum`], or one that fits the screen): the
    /// base's error is bounded like the decal's.
    #[default]
    InsideFrustum,
    /// The base may reach outside the view frustum (a ground plane running behind the camera,
    /// a wall wider than the screen): the rasterizer clips it in f32, which adds the term `C`.
    /// `reach` is the largest `|x|`, `|y|` or `|z|` of any of its eye-space vertices.
    Clipped {
        /// The largest eye-space coordinate magnitude of a base vertex (> 0).
        reach: f64,
    },
}

/// What a scene knows about one decal and the surface under it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    /// The `glFrustum` the base is drawn with (right-handed eye space looking down −z).
    pub frustum: Frustum,
    /// Viewport width and height in pixels (`glViewport`).
    pub viewport: [u32; 2],
    /// The depth attachment's format.
    pub format: DepthFormat,
    /// The decal's nearest and farthest eye distance (`−z`), `n ≤ d₁ ≤ d₂ ≤ f` (equal for a
    /// point estimate). `d₁` also stands for the distance at which the decal's plane crosses the
    /// view axis in the slope terms: exact for a decal centred on the axis, conservative when the
    /// plane's axis crossing is farther than the decal's nearest point.
    pub depth_range: [f64; 2],
    /// Eye-space tilt of the plane: `|∂z/∂x| + |∂z/∂y|` (0 facing the camera, 3 ≈ 72°).
    pub slope: f64,
    /// Every corner of base and decal has the same f32 eye-space z (a camera-facing plane whose
    /// vertices reach the vertex shader unrotated): the terms `V` and `I` vanish. Requires
    /// `slope == 0` and [`Base::InsideFrustum`]. With a probed profile that identified the depth
    /// chain ([`RasterizerProfile::facing_chain`]), pass the decal's depth as the f32 it is drawn
    /// at (`depth_range[0] == depth_range[1] == −z`) for the exact offset; the base must then be
    /// drawn with zshift's matrix for `frustum` or one within 2 f32 steps of it in elements 10
    /// and 14 (a `glFrustum` computed in f32, `f ≥ 2n`); `zshift_decal_matrix` checks the
    /// engine's own matrix itself.
    pub exact_depth: bool,
    /// The decal pass's depth test; it must match the clip convention (`Less`/`LessEqual`
    /// for `[−1, 1]` and `[0, 1]`, `Greater`/`GreaterEqual` for reversed Z).
    pub depth_test: DepthTest,
    /// What is known of the base's extent.
    pub base: Base,
    /// What the rasterizer does ([`RasterizerProfile::worst_case`] unless measured).
    pub profile: RasterizerProfile,
    /// The decal's window-space geometry, when known ([`crate::footprint::decal_shape`] computes
    /// it, with `depth_range` and `slope`, from the decal's eye-space corners): its exact window
    /// gradients and screen position replace the bounds over every plane of that slope and every
    /// pixel of the viewport in `I`, `S` and `M` (see "A measured profile"). `None`: those bounds.
    /// With a footprint the plane may contain the view direction (`slope = +∞`: level ground
    /// under a level camera): every term is then taken from the window plane ("The engine's
    /// pipeline").
    pub footprint: Option<Footprint>,
    /// How the engine draws besides the projection: world-space vertices, the viewport's
    /// origin, `glDepthRange` ([`Pipeline::default`]: eye-space vertices, the viewport at the
    /// framebuffer's origin, `glDepthRange(0, 1)`).
    pub pipeline: Pipeline,
}

/// The error of the two quads' computed window depths, term by term (window-depth units),
/// and the depth quantum. See the module docs for each.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorTerms {
    /// `q`: the smallest difference the stored format keeps.
    pub quantum: f64,
    /// `T`: f32 rounding in the vertex transform and viewport mapping (worst case, per quad).
    pub transform: f64,
    /// `V`: f32 rounding of the eye-space coordinates (worst case, per quad).
    pub vertex: f64,
    /// `I`: f32 rounding in the rasterizer's depth-plane evaluation (worst case, per quad).
    pub interpolation: f64,
    /// `S`: sub-pixel snapping of a sloped plane (per quad; 0 unsnapped).
    pub snap: f64,
    /// `E`, the per-quad plane error the offset uses: `T + V + I` (see "A measured profile" for
    /// why no probed figure replaces it).
    pub plane: f64,
    /// `C`: the base's f32 clipping and far-vertex term (0 for [`Base::InsideFrustum`]).
    pub clip: f64,
    /// Whether the depth test is strict (`GL_LESS`/`GL_GREATER`): the offset then needs `q`.
    pub strict: bool,
    /// Base and decal err alike (a facing plane with shared f32 z under an `…EQUAL` test, see
    /// "Correlated errors"): the offset needs no budget for them.
    pub correlated: bool,
    /// The measured offset a facing plane with shared f32 z needs under a strict test
    /// ([`RasterizerProfile::facing_quanta`] or, under `[0, 1]`,
    /// [`RasterizerProfile::facing_quanta_zero_to_one`], times its unit), which replaces
    /// `q + 2E` in (R1); 0 where not used.
    pub facing: f64,
    /// The decal's own clipping term, where its corners reach outside the frustum (a decal
    /// partly off screen: [`Footprint::clipped_reach`]); 0 otherwise. It adds to the decal's
    /// error, so to the offset and to the bleed gap.
    pub decal_clip: f64,
}

impl ErrorTerms {
    /// The errors of base and decal together: `2(E + S) + C` (with the decal's own clipping
    /// term), or 0 when they are correlated.
    pub fn budget(&self) -> f64 {
        if self.correlated {
            0.0
        } else {
            2.0 * (self.plane + self.snap) + self.clip + self.decal_clip
        }
    }

    /// The window offset (R1): `q + 2(E + S) + C` under a strict test, `2(E + S) + C` under
    /// `GL_LEQUAL`/`GL_GEQUAL`.
    pub fn window_offset(&self) -> f64 {
        if self.facing > 0.0 {
            self.facing
        } else {
            self.strict_quantum() + self.budget()
        }
    }

    /// The window-depth separation an occluder needs in front of the base (R2): the offset,
    /// the errors of decal and occluder `2(E + S)`, and under `GL_LEQUAL`/`GL_GEQUAL` one
    /// quantum more (a tie passes).
    pub fn gap_window(&self, offset: f64) -> f64 {
        let tie = if self.strict { 0.0 } else { self.quantum };
        offset + 2.0 * (self.plane + self.snap) + self.decal_clip + tie
    }

    fn strict_quantum(&self) -> f64 {
        if self.strict {
            self.quantum
        } else {
            0.0
        }
    }
}

/// The recommended offset for a [`Scene`], in every form an engine may apply it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Recommendation {
    /// ε for [`crate::offset::epsilon_matrix`] (negative: toward the camera), eq. 4.1.3.
    pub epsilon: f64,
    /// The NDC depth offset `−ε·m10 = 2·window_offset`.
    pub ndc_offset: f64,
    /// The window-depth offset (R1).
    pub window_offset: f64,
    /// The eye-space shift δ (toward the camera) at `Pz = −d₂` that gives the same ε through
    /// eq. 4.1.7, for `zshift_load_offset_matrix(…, delta, pz = −d₂)`.
    pub delta_at_far: f64,
    /// Occluders whose eye depth (`−z`) at the same pixel is smaller than the base's by at least
    /// this are never overdrawn by the decal (R2).
    pub bleed_gap: f64,
    /// The equivalent `glPolygonOffset(−factor, −units)` magnitudes, `units` counted in the
    /// profile's [`RasterizerProfile::resolvable`] quanta.
    pub polygon_offset: [f64; 2],
    /// The terms the offset was built from.
    pub terms: ErrorTerms,
}

/// The smallest offset that model (R1) guarantees ends z-fighting for `scene`, with its bleed gap.
///
/// Convention: OpenGL, NDC depth `[−1, 1]`, the decal drawn with element 10 scaled by `1 + ε`
/// (seed 000 eq. 4.1.3), the base with the plain matrix, depth test `scene.depth_test`
/// (`GL_LESS` or `GL_LEQUAL`).
///
/// # Errors
/// [`crate::ErrorKind::NotFinite`] for NaN or infinite depths, slope or reach;
/// [`crate::ErrorKind::Domain`] for a zero viewport, `depth_range` outside `[n, f]` or
/// decreasing, a negative slope, `exact_depth` with a nonzero slope or a clipped base, a
/// reversed-Z depth test, bits outside 0..=32, or a base reach too large for f32 clipping to be
/// bounded (clip it with [`clip_to_frustum`]); [`crate::ErrorKind::Overflow`] if a result
/// overflows.
#[inline(always)]
pub fn recommend(scene: &Scene) -> Result<Recommendation> {
    let terms = error_terms(scene)?; // which checks the scene first
    let window_offset = terms.window_offset();
    check_in_range(
        &mapping_of(scene, ClipDepth::NegOneToOne)?,
        scene.depth_range[0],
        window_offset,
        &terms,
    )?;
    let planes = scene.frustum.planes();
    let m10 = planes.sum_over_span();
    let epsilon = representable(-2.0 * window_offset / m10, "epsilon overflows")?;
    let d2 = scene.depth_range[1];
    let delta_at_far = delta_for_epsilon(scene, epsilon, -d2)?;
    let bleed_gap = gap_for_window_difference(scene, terms.gap_window(window_offset), d2);
    let units = polygon_units(scene, &terms, window_offset);
    // Every output must fit a double (a zero quantum made `units` +∞ with ZSHIFT_OK).
    let fits = |x: f64| representable(x, "a recommended value overflows f64");
    Ok(Recommendation {
        epsilon,
        ndc_offset: fits(2.0 * window_offset)?,
        window_offset: fits(window_offset)?,
        delta_at_far: fits(delta_at_far)?,
        bleed_gap: fits(bleed_gap)?,
        polygon_offset: [fits(slope_factor(scene))?, fits(units)?],
        terms,
    })
}

/// The model's terms for `scene` (see the module docs), without the final sum.
///
/// # Errors
/// As [`recommend`].
pub fn error_terms(scene: &Scene) -> Result<ErrorTerms> {
    clip_error_terms(scene, ClipDepth::NegOneToOne)
}

/// The window-depth gradient per pixel `(gₓ, g_y)` of a plane of eye-space slope `s` that
/// crosses the view axis at distance `d`: `s·F·(r−l)/(W·d)` and `s·F·(t−b)/(H·d)`.
///
/// # Errors
/// As [`recommend`].
pub fn window_gradient(scene: &Scene, d: f64) -> Result<[f64; 2]> {
    Ok(crate::model::gradient::window_gradient(
        &scene.frustum,
        scene.viewport,
        scene.slope,
        d,
    ))
}

/// `glPolygonOffset`'s units equivalent to the constant part of the offset, `(Δw − 2S)/(r·q)`,
/// `r` the profile's [`RasterizerProfile::resolvable`] for the format (quanta per unit).
fn polygon_units(scene: &Scene, terms: &ErrorTerms, window_offset: f64) -> f64 {
    let r = scene.profile.resolvable[profile_index(scene.format)];
    (window_offset - 2.0 * terms.snap).max(0.0) / (r * terms.quantum)
}

/// `glPolygonOffset`'s factor equivalent to the snapping term ([`crate::model::snap`]).
fn slope_factor(scene: &Scene) -> f64 {
    snap_model::slope_factor(scene.profile.snapping)
}

/// The term `S` ([`crate::model::snap`]): from the footprint's exact gradients, else the bound
/// over every plane of the scene's slope crossing the axis at `d₁` or beyond.
fn snap(scene: &Scene) -> Result<f64> {
    let snapping = scene.profile.snapping;
    match scene.footprint {
        _ if snapping == Snapping::Unsnapped => Ok(0.0),
        Some(footprint) => Ok(snap_model::snap(snapping, footprint.gradient, 1.0)),
        None => {
            // The plane's axis crossing d_a is unknown: the tilt (1 + s·e)/d₁ (first-order,
            // crate::model::gradient).
            let gradient = window_gradient(scene, scene.depth_range[0])?;
            let tilt = 1.0 + scene.slope * half_extent_tangent(&scene.frustum)?;
            Ok(snap_model::snap(snapping, gradient, tilt))
        }
    }
}

/// The profile's measured offset for a shared-z facing plane under a strict test, in window
/// depth: [`RasterizerProfile::facing_quanta`] (under `[0, 1]`
/// [`RasterizerProfile::facing_quanta_zero_to_one`]) times the format's quantum (D32F: 2⁻²⁴),
/// from a measured profile; 0 otherwise (and under reversed Z, where the probe does not measure
/// it).
fn measured_facing(scene: &Scene, clip: ClipDepth) -> f64 {
    if let Some(offset) = chain_facing(scene, clip) {
        return offset;
    }
    let p = scene.profile;
    let figure = match clip {
        ClipDepth::NegOneToOne => p.facing_quanta[profile_index(scene.format)],
        ClipDepth::ZeroToOne => p.facing_quanta_zero_to_one[profile_index(scene.format)],
        ClipDepth::ReversedZeroToOne => f64::NAN,
    };
    let Some(k) = measured_figure(&p, figure) else {
        return 0.0;
    };
    let unit = match scene.format {
        DepthFormat::Float32 => F32_UNIT_ROUNDOFF,
        format => format.spacing_at(0.5).unwrap_or(0.0),
    };
    k * unit
}

/// The profile's measured relative ε for a shared-z facing plane under reversed Z and a strict
/// test on D32F ([`RasterizerProfile::facing_reversed`] times 2⁻²⁴), divided by `1 − u` for
/// element 14's own rounding as [`reversed_epsilon`] is; `None` where not measured or not such a
/// scene.
fn measured_facing_reversed(scene: &Scene) -> Option<f64> {
    if !scene.pipeline.is_default_depth() {
        return None;
    }
    if let Some(eps) = chain_facing(scene, ClipDepth::ReversedZeroToOne) {
        return Some(eps);
    }
    let k = measured_figure(&scene.profile, scene.profile.facing_reversed)?;
    (scene.exact_depth && scene.depth_test.is_strict() && scene.format == DepthFormat::Float32)
        .then(|| k * F32_UNIT_ROUNDOFF / (1.0 - F32_UNIT_ROUNDOFF))
}

/// How far, in f32 steps of the engine's elements, the chain's answer is checked around zshift's
/// own matrix: an engine that computes `glFrustum`'s elements in its own f32 code may be an ulp or
/// two off the correctly rounded ones, and the answer must hold for it too.
const CHAIN_ELEMENT_SPREAD: u32 = 2;

/// Whether the chain's answer, checked within [`CHAIN_ELEMENT_SPREAD`] f32 steps of zshift's
/// matrix `plain`, covers a base drawn with `engine`: its elements 10 and 14 (in magnitude, so a
/// left-handed matrix compares with its right-handed twin) lie within that spread.
pub(crate) fn chain_covers(plain: &[f32; 16], engine: &[f32; 16]) -> bool {
    [10, 14].iter().all(|&i| {
        let (a, b) = (plain[i].abs().to_bits(), engine[i].abs().to_bits());
        a.abs_diff(b) <= CHAIN_ELEMENT_SPREAD
    })
}

/// A shared-z facing decal under a strict test with a profile whose probe identified the depth
/// chain ([`RasterizerProfile::facing_chain`]): the exact number of f32 steps `k` of the offset
/// element it needs ([`crate::depth_chain::steps_to_pass`]; the largest over element 10 and 14
/// within [`CHAIN_ELEMENT_SPREAD`] steps of zshift's matrix, and over `m10·z + m14` fused or not,
/// the one step that runs in the engine's own shader), as the offset to request: the move
/// of `k − 0.45` steps, which the outward rounding of the offset matrix (from the exact element,
/// within half a step of the f32 one) turns into `k` steps, or `k + 1` in a sliver. Under `[−1, 1]`
/// and `[0, 1]` a window-depth offset (half the element's move, or all of it); under reversed Z a
/// relative ε of element 14. `None` where the chain is not known, the scene is not such a decal,
/// its depth is not an f32, the format is D32 (UNORM, whose conversion the probe cannot see), or
/// `f < 2n`. The base must be drawn with zshift's matrix for the frustum, or one whose elements 10
/// and 14 are within [`CHAIN_ELEMENT_SPREAD`] f32 steps of it (any `glFrustum` computed in f32 or
/// better with `f ≥ 2n`); the matrix-in calls check the engine's own and fall back otherwise.
fn chain_facing(scene: &Scene, clip: ClipDepth) -> Option<f64> {
    let p = scene.profile;
    let chain = p.facing_chain?;
    let [d1, d2] = scene.depth_range;
    let z = -(d1 as f32);
    let planes = scene.frustum.planes();
    // Below f = 2n an engine's f32 (f + n)/(f − n) cancels and may stray far from zshift's
    // element (Mesa's own glFrustum by 2 to 582912 f32 steps): the worst phase stands in.
    let near_far_apart = planes.far() >= 2.0 * planes.near();
    if !(p.measured && scene.exact_depth && scene.depth_test.is_strict() && near_far_apart)
        || d1 != d2
        || f64::from(z) != -d1
    {
        return None;
    }
    let bits = match scene.format {
        DepthFormat::Unorm16 => 16,
        DepthFormat::Unorm24 => 24,
        DepthFormat::Unorm32 => return None,
        DepthFormat::Float32 => 0,
    };
    let m = crate::projection::projection(&scene.frustum, clip).ok()?;
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    let spread = CHAIN_ELEMENT_SPREAD;
    let around = |x: f32| {
        (0..=2 * spread).filter_map(move |i| {
            let bits = x.to_bits().checked_add(i)?.checked_sub(spread)?;
            let y = f32::from_bits(bits);
            (y.is_finite() && y.signum() == x.signum()).then_some(y)
        })
    };
    // The product and sum m10·z + m14 run in the engine's own vertex shader, which a compiler
    // may fuse or not whatever the probe's shader got: both are covered. (The division by w,
    // the viewport map and the conversion are the fixed-function part the probe identified.)
    let shader_variants = [
        chain,
        crate::depth_chain::DepthChain {
            fused_clip: !chain.fused_clip,
            ..chain
        },
    ];
    let mut k = 0;
    for variant in shader_variants {
        for m10 in around(m[10]) {
            for m14 in around(m[14]) {
                let steps = |limit| {
                    crate::depth_chain::steps_to_pass(variant, clip, bits, (m10, m14), z, limit)
                };
                // Nearby elements need nearby steps: bisect a short range first.
                let near = if k > 0 { steps(2 * k + 16) } else { None };
                k = k.max(near.or_else(|| steps(1 << 20))?);
            }
        }
    }
    let element = |k: u32| {
        let (m10, m14) = crate::depth_chain::stepped((m[10], m[14]), reversed, k)?;
        Some(f64::from(if reversed { m14 } else { m10 }))
    };
    let (before, at, start) = (element(k - 1)?, element(k)?, element(0)?);
    let moved = ((before - start) + 0.55 * (at - before)).abs();
    Some(match clip {
        ClipDepth::NegOneToOne => 0.5 * moved,
        ClipDepth::ZeroToOne => moved,
        ClipDepth::ReversedZeroToOne => moved / start.abs(),
    })
}

/// The term `C` of a base the rasterizer clips ([`crate::model::clip`]), 0 for
/// [`Base::InsideFrustum`]: with the convention's projection, the plane's form (exact from the
/// footprint, else bounds over every plane of the slope, see [`plane_form`]) and the clipper's
/// measured roundings where the probe found them.
fn clip_term(scene: &Scene, clip: ClipDepth, mapping: &DepthMapping) -> Result<f64> {
    let Base::Clipped { reach } = scene.base else {
        return Ok(0.0);
    };
    clip_term_of_reach(scene, clip, mapping, reach)
}

/// [`clip_term`] for a primitive of eye-space `reach` on the decal's plane (the base, or the
/// decal itself where it reaches outside the frustum).
fn clip_term_of_reach(
    scene: &Scene,
    clip: ClipDepth,
    mapping: &DepthMapping,
    reach: f64,
) -> Result<f64> {
    let m = crate::projection::projection_f64(&scene.frustum, clip)?;
    // The bound on six clip stages of f32 rounding, or the probe's clip_ulps with its margin.
    let gamma = clip_model::clip_gamma(&scene.profile);
    let form = plane_form(scene, clip, &m)?;
    clip_model::clip_term(
        &m,
        reach,
        scene.depth_range[0],
        gamma,
        &form,
        scene.footprint.is_some(),
        &scene.pipeline,
        mapping.window_per_ndc(),
    )
}

/// Refuses an offset that would move the decal's nearest point out of the depth range (past
/// the near plane's window depth 0, or 1 under reversed Z): no offset then ends z-fighting,
/// which happens when the clipping term `C` of a large clipped base, or the vertex term of
/// world-space vertices far from the origin, dwarfs the decal's depth. The message names the
/// larger of the two and what to do about it.
pub(crate) fn check_in_range(
    mapping: &DepthMapping,
    d1: f64,
    offset_at_d1: f64,
    terms: &ErrorTerms,
) -> Result<()> {
    let moved_from = |w1: f64| {
        if mapping.is_reversed() {
            w1 + offset_at_d1
        } else {
            w1 - offset_at_d1
        }
    };
    // The f64 estimate decides unless its error could cross an end of [0, 1].
    let estimate = moved_from(mapping.window_depth_estimate(d1));
    let margin = 4.0 * WINDOW_ESTIMATE_ERROR;
    let moved = if (margin..=1.0 - margin).contains(&estimate) {
        estimate
    } else {
        moved_from(mapping.window_depth(d1)?)
    };
    if (0.0..=1.0).contains(&moved) {
        Ok(())
    } else if terms.clip >= terms.vertex {
        Err(crate::error::Error::new(
            crate::ErrorKind::Unresolvable,
            "the offset this scene needs moves the decal past the near plane (the float clipping of a large base): cut the base to the frustum (zshift_clip_to_frustum in C, zshift.clip_to_frustum in Python) and pass base_reach = 0, pass a probed profile (zshift_probe), or move the near plane out",
        ))
    } else {
        Err(crate::error::Error::new(
            crate::ErrorKind::Unresolvable,
            "the offset this scene needs moves the decal past the near plane (the float rounding of world-space vertices far from the origin): pass view_matrix and world_box (C fields; Python keywords) for the exact term, render relative to the camera, or move the near plane out",
        ))
    }
}

/// The δ with `ε(δ, Pz) = epsilon` (eq. 4.1.7 solved for δ): `δ = −ε·Pz² / (K + ε·Pz)`,
/// `K = 2fn/(f+n)`.
fn delta_for_epsilon(scene: &Scene, epsilon: f64, pz: f64) -> Result<f64> {
    let planes = scene.frustum.planes();
    let k = 2.0 * planes.near() / planes.sum_over_span() * planes.far_over_span();
    let denominator = k + epsilon * pz;
    if denominator <= 0.0 {
        return Err(domain(
            "the recommended offset exceeds what element 10 can carry at this depth",
        ));
    }
    representable(-epsilon * pz * (pz / denominator), "delta overflows")
}

/// The eye depth `G` in front of depth `d` (both `−z`, at the same pixel) whose window depth is
/// lower by `dw`: `F·n·(1/(d−G) − 1/d) = dw`, so `G = d·x/(1 + x)` with `x = dw·d/(F·n)`.
fn gap_for_window_difference(scene: &Scene, dw: f64, d: f64) -> f64 {
    let planes = scene.frustum.planes();
    let x = dw * d / (planes.far_over_span() * planes.near());
    if x.is_infinite() {
        // A near plane so small that x overflows: x/(1 + x) → 1 (∞/∞ gave NaN).
        return d;
    }
    d * (x / (1.0 + x))
}

/// Checks one of the decal's eye distances against the frustum, naming the field (C
/// `decal_near`/`decal_far`; Python `decal_depths`), its value, and the plane it crossed.
fn check_decal_distance(planes: &crate::domain::Planes, field: &'static str, d: f64) -> Result<()> {
    finite(d, "a decal distance is NaN or infinite").map_err(|e| e.with_value(field, d))?;
    if d < planes.near() {
        return Err(domain(
            "the decal's eye distance lies in front of the near plane: pass the decal's distances along the view axis (decal_near <= decal_far, Python decal_depths), or its corners",
        )
        .with_value(field, d)
        .with_bound("near plane n", planes.near()));
    }
    if d > planes.far() {
        return Err(domain(
            "the decal's eye distance lies beyond the far plane: pass distances within the frustum (Python decal_depths), or its corners",
        )
        .with_value(field, d)
        .with_bound("far plane f", planes.far()));
    }
    Ok(())
}

fn check(scene: &Scene, clip: ClipDepth) -> Result<()> {
    let planes = scene.frustum.planes();
    let [d1, d2] = scene.depth_range;
    check_decal_distance(&planes, "decal_near", d1)?;
    check_decal_distance(&planes, "decal_far", d2)?;
    if d1 > d2 {
        return Err(domain(
            "the decal's depth range must be [nearest, farthest]: decal_far must be >= decal_near",
        )
        .with_value("decal_far", d2)
        .with_bound("decal_near", d1));
    }
    if scene.viewport.contains(&0) {
        return Err(domain("the viewport must have a nonzero width and height"));
    }
    scene.pipeline.check()?;
    // A plane containing the view direction has an infinite eye-space slope; with the decal's
    // footprint the model runs on its window plane and needs no slope.
    if !(scene.footprint.is_some() && scene.slope == f64::INFINITY) {
        finite(scene.slope, "the plane slope is NaN or infinite (pass the decal's corners for a plane that contains the view direction)")
            .map_err(|e| e.with_value("slope", scene.slope))?;
    }
    if scene.slope < 0.0 {
        return Err(domain("the plane slope |dz/dx| + |dz/dy| must be >= 0")
            .with_value("slope", scene.slope));
    }
    if scene.exact_depth && scene.pipeline.world_space() {
        return Err(domain(
            "exact_depth needs vertices in eye space: with world_reach > 0 the f32 model-view computes each vertex's z",
        )
        .with_value("world_reach", scene.pipeline.world_reach));
    }
    if scene.exact_depth && scene.slope != 0.0 {
        return Err(domain(
            "exact_depth needs a plane facing the camera (slope 0)",
        ));
    }
    if let Base::Clipped { reach } = scene.base {
        finite(reach, "the base reach is NaN or infinite")?;
        if reach <= 0.0 {
            return Err(domain(
                "the base reach (largest |x|, |y|, |z| of a base vertex) must be > 0",
            ));
        }
        if scene.exact_depth {
            return Err(domain(
                "exact_depth needs a base the rasterizer does not clip: base_reach must be 0 (Rust: Base::InsideFrustum)",
            ));
        }
    }
    if let Snapping::SubpixelBits(b) = scene.profile.snapping {
        if b > 32 {
            return Err(domain("GL_SUBPIXEL_BITS must lie in 0..=32"));
        }
    }
    let r = scene.profile.resolvable[profile_index(scene.format)];
    if !(r.is_finite() && r > 0.0) {
        return Err(
            domain("the profile's resolvable r for this format must be finite and > 0")
                .with_value("resolvable", r),
        );
    }
    let reversed = clip == ClipDepth::ReversedZeroToOne;
    if scene.depth_test.is_reversed() != reversed {
        return Err(domain(if reversed {
            "reversed Z needs the depth test GL_GREATER or GL_GEQUAL"
        } else {
            "this clip convention needs the depth test GL_LESS or GL_LEQUAL (GL_GREATER/GL_GEQUAL are for reversed Z)"
        }));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// The same model under the other clip conventions: `[0, 1]` clip depth and reversed Z.
// ---------------------------------------------------------------------------------------------

/// The recommended offset for a [`Scene`] drawn under a clip-depth convention, in the form that
/// convention needs, with the decal's matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClipRecommendation {
    /// The convention the offset is for.
    pub clip: ClipDepth,
    /// The constant NDC depth offset `c` for [`crate::clip_offset::ndc_offset_matrix`] (element
    /// 10 becomes `m10 − c`; negative: toward the camera) under `NegOneToOne` and `ZeroToOne`;
    /// 0 under `ReversedZeroToOne`.
    pub ndc_offset: f64,
    /// The relative offset `ε` for [`crate::clip_offset::relative_offset_matrix`] (element 14
    /// scaled by `1 + ε`, every point moved from `d` to `d/(1 + ε)`) under
    /// `ReversedZeroToOne`; 0 otherwise.
    pub relative_epsilon: f64,
    /// The convention's ε in one number: Lengyel's element-10 ε (`m10·(1 + ε)` is `m10 − c`,
    /// so `ε = −c/m10`, negative) under `NegOneToOne` and `ZeroToOne`; [`Self::relative_epsilon`]
    /// (positive) under `ReversedZeroToOne`.
    pub epsilon: f64,
    /// The equivalent `glPolygonOffset(−factor, −units)` magnitudes, as
    /// [`Recommendation::polygon_offset`], under `NegOneToOne` and `ZeroToOne`; `[0, 0]` under
    /// reversed Z, where the offset is relative and no constant `units` matches it.
    pub polygon_offset: [f64; 2],
    /// The smallest window-depth offset over the decal (at `d₂`; constant under `NegOneToOne`
    /// and `ZeroToOne`, `ε·b/d₂` under reversed Z).
    pub window_offset: f64,
    /// The eye-space shift toward the camera at `d₂` that the offset amounts to there.
    pub delta_at_far: f64,
    /// Occluders whose eye depth (`−z`) at the same pixel is smaller than the base's by at least
    /// this are never overdrawn by the decal (R2).
    pub bleed_gap: f64,
    /// The decal's projection matrix (f32, column-major), offset rounded outward; draw the base
    /// with [`crate::projection::projection`] of the same frustum and convention.
    pub matrix: [f32; 16],
    /// The terms the offset was built from (window-depth units; `quantum` at the decal's
    /// farthest point).
    pub terms: ErrorTerms,
}

/// The smallest offset that model (R1) guarantees ends z-fighting for `scene` drawn under
/// `clip` (see "Other clip conventions" in the module docs), with its matrix and bleed gap.
///
/// Conventions: OpenGL right-handed eye space; `NegOneToOne` is `glFrustum` with `GL_LESS` or
/// `GL_LEQUAL` and gives exactly [`recommend`]'s offset; `ZeroToOne` is
/// `glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)` with `GL_LESS` or `GL_LEQUAL`
/// (Direct3D/Vulkan clip space), offset through element 10; `ReversedZeroToOne` adds
/// `glDepthFunc(GL_GREATER or GL_GEQUAL)` and `glClearDepth(0)`, offset through element 14
/// (relative, works where `m10 = 0`). `f` may be `+∞` in every convention; `scene.depth_test`
/// must match the convention.
///
/// # Errors
/// As [`recommend`]; [`crate::ErrorKind::Overflow`] if an element of the matrix leaves f32.
pub fn recommend_clip(scene: &Scene, clip: ClipDepth) -> Result<ClipRecommendation> {
    recommend_clip_building(scene, clip, true)
}

/// [`recommend_clip`], with the offset matrix built from zshift's own projection only when
/// `build` (the matrix-in calls apply the offset to the engine's matrix instead: `matrix` is then
/// all zeros).
pub(crate) fn recommend_clip_building(
    scene: &Scene,
    clip: ClipDepth,
    build: bool,
) -> Result<ClipRecommendation> {
    let frustum = &scene.frustum;
    if clip == ClipDepth::NegOneToOne {
        // `recommend` checks the scene itself.
        let r = recommend(scene)?;
        return Ok(ClipRecommendation {
            clip,
            epsilon: r.epsilon,
            polygon_offset: r.polygon_offset,
            ndc_offset: -r.ndc_offset,
            relative_epsilon: 0.0,
            window_offset: r.window_offset,
            delta_at_far: r.delta_at_far,
            bleed_gap: r.bleed_gap,
            matrix: if build {
                crate::offset::epsilon_matrix(frustum, r.epsilon)?
            } else {
                [0.0; 16]
            },
            terms: r.terms,
        });
    }
    check(scene, clip)?;
    let m = crate::projection::projection_f64(frustum, clip)?;
    let mapping = mapping_of(scene, clip)?;
    let terms = clip_error_terms(scene, clip)?;
    let [d1, d2] = scene.depth_range;
    let fits = |x: f64| representable(x, "a recommended value overflows f64");
    let (ndc_offset, relative_epsilon, window_offset, matrix) = if clip == ClipDepth::ZeroToOne {
        // Window depth = NDC depth: the constant offset is (R1) itself.
        let dw = fits(terms.window_offset())?;
        let c = -dw / mapping.window_per_ndc();
        (
            c,
            0.0,
            dw,
            if build {
                crate::clip_offset::ndc_offset_projection(frustum, clip, c)?
            } else {
                [0.0; 16]
            },
        )
    } else {
        let eps = match measured_facing_reversed(scene) {
            Some(eps) => eps,
            None => reversed_epsilon(scene, &mapping, &terms)?,
        };
        let b = scale(&scene.frustum);
        let matrix = if build {
            crate::clip_offset::relative_offset_projection(frustum, clip, eps)?
        } else {
            [0.0; 16]
        };
        (0.0, eps, fits(eps * (b / d2))?, matrix)
    };
    // The window offset at d: constant, or ε·b/d under reversed Z.
    let offset_at = |d: f64| {
        if clip == ClipDepth::ReversedZeroToOne {
            relative_epsilon * (scale(&scene.frustum) / d)
        } else {
            window_offset
        }
    };
    check_in_range(&mapping, d1, offset_at(d1), &terms)?;
    let toward = |dw: f64| if mapping.is_reversed() { dw } else { -dw };
    let delta_at_far = mapping.shift_of_window_change(toward(window_offset), d2)?;
    let mut bleed_gap = 0.0f64;
    for d in [d1, d2] {
        let at_d = ErrorTerms {
            quantum: unit_quantum(scene.format, &scene.pipeline, mapping.window_depth(d)?)?,
            ..terms
        };
        let g = match mapping.shift_of_window_change(toward(at_d.gap_window(offset_at(d))), d) {
            Ok(g) => g.min(d),
            // Past the eye: no occluder in front of the base is safe from the decal.
            Err(_) => d,
        };
        bleed_gap = bleed_gap.max(g);
    }
    let (epsilon, polygon_offset) = if clip == ClipDepth::ReversedZeroToOne {
        (relative_epsilon, [0.0, 0.0])
    } else {
        let units = polygon_units(scene, &terms, window_offset);
        (-ndc_offset / m[10], [slope_factor(scene), fits(units)?])
    };
    Ok(ClipRecommendation {
        clip,
        epsilon: fits(epsilon)?,
        polygon_offset,
        ndc_offset: fits(ndc_offset)?,
        relative_epsilon,
        window_offset,
        delta_at_far: fits(delta_at_far)?,
        bleed_gap: fits(bleed_gap)?,
        matrix,
        terms,
    })
}

/// The model's terms for `scene` under `clip` (see the module docs); `NegOneToOne` gives
/// exactly [`error_terms`].
///
/// # Errors
/// As [`recommend`].
pub fn clip_error_terms(scene: &Scene, clip: ClipDepth) -> Result<ErrorTerms> {
    check(scene, clip)?;
    let mapping = mapping_of(scene, clip)?;
    let pipeline = scene.pipeline;
    let (m10, _) = crate::projection::depth_row(&scene.frustum.planes(), clip);
    let [d1, d2] = scene.depth_range;
    // In plain f64 (d₁, d₂ are checked): within 2⁻⁵⁰ of the correctly rounded window depths,
    // as close as the f64 evaluation of the terms below is to their formulas.
    let (w1, w2) = (
        mapping.window_depth_estimate(d1),
        mapping.window_depth_estimate(d2),
    );
    let (w_min, w_max) = (w1.min(w2), w1.max(w2));
    // Under glDepthRange(near, far) the stored depth is near + (far − near)·w: the roundings of
    // the viewport map and of the interpolation are relative to it, i.e. to w + lift in unit
    // window depth (0 for the default range).
    let lift = pipeline.depth_range[0] / pipeline.span();
    // T (crate::model::transform).
    let transform = transform::transform(clip, m10, [w1, w2], lift);
    // The footprint measured from the framebuffer's origin, where the rasterizer's plane
    // starts (the viewport may lie inside a larger framebuffer).
    let footprint = scene
        .footprint
        .map(|f| f.in_framebuffer(pipeline.viewport_origin, d2));
    // G: how far the plane's window depth runs across the framebuffer (with the axis-crossing
    // bound 1 + s·e; crate::model::interpolation); with the decal's footprint, the exact run
    // from the origin to its farthest pixel.
    let extrapolated = match footprint {
        Some(footprint) => footprint.extrapolation(),
        None => {
            let gradient = window_gradient(scene, d1)?;
            let extent = interpolation::framebuffer_extent(&pipeline, scene.viewport);
            let tilt = 1.0 + scene.slope * half_extent_tangent(&scene.frustum)?;
            interpolation::extrapolation_bound(gradient, extent, tilt)
        }
    };
    // V and I (crate::model::vertex, crate::model::interpolation).
    let (vertex, interpolation) = if scene.exact_depth {
        (0.0, 0.0)
    } else {
        (
            vertex_term(scene, clip, mapping.window_per_ndc())?,
            interpolation::interpolation(w_min, w_max, extrapolated, lift),
        )
    };
    // The spacing at the decal's farthest point: its largest window depth, or under reversed Z
    // its smallest.
    let far_w = if mapping.is_reversed() { w_min } else { w_max };
    // That point is d₂ either way; the estimate decides the spacing unless near a binade edge.
    let q = if pipeline.depth_range == [0.0, 1.0] {
        mapping.spacing_at_estimate(scene.format, d2, far_w)?
    } else {
        unit_quantum(scene.format, &pipeline, mapping.window_depth(d2)?)?
    };
    let bound = transform + vertex + interpolation;
    // M, the largest magnitude of the plane's terms from the window origin over the decal's
    // pixels (crate::model::interpolation).
    let magnitude = lift
        + match footprint {
            Some(footprint) => footprint.magnitude(),
            None => interpolation::magnitude_bound(w_max, extrapolated),
        };
    let plane = match measured_plane_error(&scene.profile, clip, m10, magnitude) {
        Some(measured) => (measured + vertex).min(bound),
        None => bound,
    };
    let snap = snap(scene)?;
    let clip_term = match scene.profile.near_clip {
        NearClip::ClippedF32 => clip_term(scene, clip, &mapping)?,
        // The probe found clipped planes within twice the unclipped error plus 2 D24 quanta.
        NearClip::PlanePreserving if matches!(scene.base, Base::Clipped { .. }) => {
            plane + snap + pipeline.per_unit(2.0 / 16_777_215.0)
        }
        NearClip::PlanePreserving => 0.0,
    };
    // A decal partly off screen is clipped too, its own corners the reach.
    let decal_reach = scene.footprint.map_or(0.0, |f| f.clipped_reach);
    let decal_clip = match scene.profile.near_clip {
        _ if decal_reach == 0.0 => 0.0,
        NearClip::ClippedF32 => clip_term_of_reach(scene, clip, &mapping, decal_reach)?,
        NearClip::PlanePreserving => plane + snap + pipeline.per_unit(2.0 / 16_777_215.0),
    };
    // A facing plane whose every corner has the same f32 z (base and decal) is drawn at one
    // depth, and each step of the depth chain is monotone in element 10: the decal's computed
    // depth is never behind the base's, so under an …EQUAL test (a tie passes) no offset is
    // needed. The budget of base and decal is then 0; the occluder's error stays in the gap.
    let correlated = scene.exact_depth && !scene.depth_test.is_strict();
    // The probe measured the facing figures with glDepthRange(0, 1) and eye-space vertices.
    let facing = if scene.exact_depth && scene.depth_test.is_strict() && pipeline.is_default_depth()
    {
        measured_facing(scene, clip)
    } else {
        0.0
    };
    Ok(ErrorTerms {
        quantum: q,
        transform,
        vertex,
        interpolation,
        snap,
        plane,
        clip: clip_term,
        strict: scene.depth_test.is_strict(),
        correlated,
        facing,
        decal_clip,
    })
}

/// The plane's form on clip coordinates ([`crate::model::plane_form`]): exact from the decal's
/// footprint, else bounds on its coefficients' magnitudes over every plane of the scene's slope
/// whose axis crossing lies at `d₁` or beyond ([`PlaneForm::of_slope`]).
fn plane_form(scene: &Scene, clip: ClipDepth, m: &[f64; 16]) -> Result<PlaneForm> {
    if let Some(footprint) = scene.footprint {
        return Ok(PlaneForm::of_footprint(&footprint, scene.viewport, clip));
    }
    let e = half_extent_tangent(&scene.frustum)?;
    Ok(PlaneForm::of_slope(m, scene.slope, scene.depth_range[0], e))
}

/// The term `V` ([`crate::model::vertex`]), in unit window depth: with the decal's footprint
/// the eye-rounding bound from the plane's form (finite for planes containing the view
/// direction), else `u·(b/d₁)·(1 + s·e)` (a plane of slope `s` crossing the axis at `d₁` or
/// beyond); with world-space vertices ([`Pipeline::world_reach`]) the larger of that and the
/// f32 model-view term.
#[inline]
fn vertex_term(scene: &Scene, clip: ClipDepth, per_ndc: f64) -> Result<f64> {
    let bound = || -> Result<f64> {
        let e = half_extent_tangent(&scene.frustum)?;
        Ok(vertex::eye_rounding_bound(
            scale(&scene.frustum),
            scene.depth_range[0],
            scene.slope,
            e,
        ))
    };
    // The common case (no corners, eye-space vertices) needs neither the f64 matrix nor the form.
    if scene.footprint.is_none() && !scene.pipeline.world_space() {
        return bound();
    }
    let m = crate::projection::projection_f64(&scene.frustum, clip)?;
    let form = plane_form(scene, clip, &m)?;
    let eye = match scene.footprint {
        Some(_) => per_ndc * vertex::eye_rounding(&form, &m, tangents_of(&scene.frustum)),
        None => bound()?,
    };
    if !scene.pipeline.world_space() {
        return Ok(eye);
    }
    // One combined matrix errs in each clip coordinate independently; the eye position computed
    // first errs in eye space, and only its part off the plane counts (needs the exact form).
    let world = per_ndc
        * vertex::world_rounding(
            &form,
            scene.footprint.is_some(),
            &m,
            &scene.pipeline,
            scene.depth_range[0],
            tangents_of(&scene.frustum),
        );
    representable(eye.max(world), "the vertex term overflows f64")
}

pub(crate) fn mapping_of(scene: &Scene, clip: ClipDepth) -> Result<DepthMapping> {
    // A Frustum's planes are checked.
    Ok(DepthMapping::of_planes(scene.frustum.planes(), clip))
}

/// Under reversed Z with the decal's footprint and a measured `error_ulps_reversed` `k`: a bound
/// on `budget·d/b` over every pixel of the decal, from each term's own largest product with the
/// depth: `2k·u·(|m10|·d₂ + max M·d)` ([`Footprint::magnitude_depth`]), `2V·d = 2u·b·(1 + s·e)`
/// (the vertex term is `u·(b/d)(1 + s·e)` at depth `d`), `(2S + C)·d₂`; over `b`. The budget
/// evaluated at its worst pixel and carried to the farthest one (`budget·d₂/b`) overstates it by
/// up to `d₂/d₁`. `None` without a footprint, a measured figure, or when the errors are
/// correlated.
fn footprint_relative_budget(scene: &Scene, terms: &ErrorTerms, b: f64) -> Option<f64> {
    let footprint = scene.footprint?;
    let k = measured_figure(&scene.profile, scene.profile.error_ulps_reversed)?;
    if terms.correlated {
        return None;
    }
    let [d1, d2] = scene.depth_range;
    let (m10, _) =
        crate::projection::depth_row(&scene.frustum.planes(), ClipDepth::ReversedZeroToOne);
    let u = F32_UNIT_ROUNDOFF;
    let pipeline = scene.pipeline;
    let lift = pipeline.depth_range[0] / pipeline.span();
    let shifted = footprint.in_framebuffer(pipeline.viewport_origin, d2);
    let magnitude_depth = shifted.magnitude_depth + lift * d2;
    let plane = k * u * (m10.abs() * d2 + magnitude_depth) + terms.vertex * d1;
    Some((2.0 * plane + (2.0 * terms.snap + terms.clip) * d2) / b)
}

/// The relative ε under reversed Z: the window offset it gives at `d` is `ε·b/d`, which must
/// reach `q(w(d)) + budget` (strict test) or `budget` at every `d` of the decal. The budget
/// part is largest at `d₂`; the quantum part `q(w)·d/b` peaks, within each binade of float
/// depth, where `w` is smallest, so at `d₂` or where `w(d)` is a power of two. Element 14
/// rounded to f32 (`p ≥ b·(1 − u)`) carries `ε·p`, hence the final `1/(1 − u)`.
fn reversed_epsilon(scene: &Scene, mapping: &DepthMapping, terms: &ErrorTerms) -> Result<f64> {
    reversed_epsilon_with(scene, mapping, terms, 0.0)
}

/// [`reversed_epsilon`] with `extra`, a constant window-depth error beside the budget (the line
/// term of [`crate::lines`]), added to the budget at every depth.
pub(crate) fn reversed_epsilon_with(
    scene: &Scene,
    mapping: &DepthMapping,
    terms: &ErrorTerms,
    extra: f64,
) -> Result<f64> {
    let b = scale(&scene.frustum);
    let [d1, d2] = scene.depth_range;
    let budget = terms.budget() + extra;
    let strict = if terms.strict { 1.0 } else { 0.0 };
    let relative_budget = footprint_relative_budget(scene, terms, b).unwrap_or(f64::INFINITY);
    let need = |d: f64| -> Result<f64> {
        let q = unit_quantum(scene.format, &scene.pipeline, mapping.window_depth(d)?)?;
        Ok(strict * q * (d / b) + (budget * (d / b)).min(relative_budget))
    };
    let mut eps = need(d1)?.max(need(d2)?);
    // The binades are those of the stored depth, near + (far − near)·w under glDepthRange.
    let pipeline = scene.pipeline;
    let (w_lo, w_hi) = (
        pipeline.actual(mapping.window_depth(d2)?),
        pipeline.actual(mapping.window_depth(d1)?),
    );
    if !scene.format.is_unorm() && w_lo > 0.0 {
        // exp2, not powi: powi(k) for k < −1022 is 1/2^−k, which overflows to ∞ and gives 0,
        // and a walk from 0 never ends (a subnormal window depth reaches here).
        let mut p = (w_lo.log2().floor() + 1.0).exp2();
        while p > 0.0 && p <= w_hi {
            let unit = ((p - pipeline.depth_range[0]) / pipeline.span()).clamp(0.0, 1.0);
            let d = mapping.distance_at_window(unit)?;
            let q = pipeline.per_unit(p * 2f64.powi(-23));
            eps = eps.max(strict * q * (d / b) + (budget * (d / b)).min(relative_budget));
            p *= 2.0;
        }
    }
    representable(
        eps / (1.0 - F32_UNIT_ROUNDOFF),
        "the relative epsilon overflows f64",
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ErrorKind;

    fn scene(format: DepthFormat, slope: f64, snapping: Snapping) -> Scene {
        let profile = RasterizerProfile {
            snapping,
            ..RasterizerProfile::worst_case()
        };
        let e = 0.577_350_269_189_625_7;
        Scene {
            pipeline: Default::default(),
            footprint: None,
            frustum: Frustum::new(-e, e, -e, e, 1.0, 1e3).unwrap(),
            viewport: [256, 256],
            format,
            depth_range: [80.0, 120.0],
            slope,
            exact_depth: false,
            depth_test: DepthTest::Less,
            base: Base::InsideFrustum,
            profile,
        }
    }

    /// With an identified depth chain, a shared-z facing decal's matrix moves the offset element
    /// by exactly the steps the chain needs, the largest over the elements an engine's own f32
    /// code might hold (within two steps) and over its shader fusing `m10·z + m14` or not, or one
    /// more: checked against the chain emulated here
    /// on every nearby element, for every format and convention, at depths the probe never drew.
    #[test]
    fn an_identified_chain_gives_the_steps_it_needs() {
        use crate::depth_chain::{stepped, DepthChain};
        let chain = DepthChain::from_code(2).unwrap(); // Mesa llvmpipe's
        for clip in [
            ClipDepth::NegOneToOne,
            ClipDepth::ZeroToOne,
            ClipDepth::ReversedZeroToOne,
        ] {
            for format in [
                DepthFormat::Unorm16,
                DepthFormat::Unorm24,
                DepthFormat::Float32,
            ] {
                for d in [1.37f32, 11.25, 80.0, 333.3] {
                    let mut s = scene(format, 0.0, Snapping::Unsnapped);
                    s.exact_depth = true;
                    s.depth_range = [f64::from(d); 2];
                    s.depth_test = if clip == ClipDepth::ReversedZeroToOne {
                        DepthTest::Greater
                    } else {
                        DepthTest::Less
                    };
                    s.profile.measured = true;
                    s.profile.facing_chain = Some(chain);
                    let plain = crate::projection::projection(&s.frustum, clip).unwrap();
                    let r = recommend_clip(&s, clip).unwrap();
                    let reversed = clip == ClipDepth::ReversedZeroToOne;
                    let element = if reversed { 14 } else { 10 };
                    let taken = r.matrix[element]
                        .to_bits()
                        .abs_diff(plain[element].to_bits());
                    let bits = match format {
                        DepthFormat::Unorm16 => 16,
                        DepthFormat::Unorm24 => 24,
                        _ => 0,
                    };
                    // The smallest k that passes on the matrix an engine might hold, its
                    // shader fusing m10·z + m14 or not.
                    let mut need = 0;
                    for fused_clip in [false, true] {
                        let chain = DepthChain {
                            fused_clip,
                            ..chain
                        };
                        let stored = |m10: f32, m14: f32, k: u32| {
                            let (a, b) = stepped((m10, m14), reversed, k).unwrap();
                            chain.stored(bits, chain.window_depth(clip, a, b, -d))
                        };
                        for i in 0..5u32 {
                            for j in 0..5u32 {
                                let m10 = f32::from_bits(plain[10].to_bits() + i - 2);
                                let m14 = f32::from_bits(plain[14].to_bits() + j - 2);
                                let base = stored(m10, m14, 0);
                                let k = (1..1 << 16)
                                    .find(|&k| {
                                        let s = stored(m10, m14, k);
                                        if reversed {
                                            s > base
                                        } else {
                                            s < base
                                        }
                                    })
                                    .unwrap();
                                need = need.max(k);
                            }
                        }
                    }
                    assert!(
                        taken == need || taken == need + 1,
                        "{clip:?} {format:?} d {d}: {taken} steps taken, {need} needed"
                    );
                }
            }
        }
    }

    /// ε, δ and the NDC offset agree through the seed's own equations (4.1.4 and 4.1.7, the
    /// latter through `offset::epsilon`, an independent implementation).
    #[test]
    fn the_forms_of_the_offset_agree_through_the_seed_equations() {
        let s = scene(DepthFormat::Unorm24, 1.0, Snapping::SubpixelBits(8));
        let r = recommend(&s).unwrap();
        let m10 = (1e3 + 1.0) / (1e3 - 1.0);
        assert!((-r.epsilon * m10 - r.ndc_offset).abs() <= 1e-15 * r.ndc_offset);
        assert_eq!(r.ndc_offset, 2.0 * r.window_offset);
        let eps = crate::offset::epsilon(1.0, 1e3, r.delta_at_far, -120.0).unwrap();
        assert!(
            (eps - r.epsilon).abs() <= 1e-12 * r.epsilon.abs(),
            "{eps} vs {}",
            r.epsilon
        );
    }

    /// The bleed gap is the eye distance whose window-depth difference (Walker's f(d), through
    /// `precision::window_depth`) is `2Δw − q` at the far end of the decal.
    #[test]
    fn the_bleed_gap_spans_twice_the_offset_less_a_quantum_in_window_depth() {
        let s = scene(DepthFormat::Unorm16, 3.0, Snapping::SubpixelBits(8));
        let r = recommend(&s).unwrap();
        let w = |d| crate::precision::window_depth(1.0, 1e3, d).unwrap();
        let dw = w(120.0) - w(120.0 - r.bleed_gap);
        let want = 2.0 * r.window_offset - r.terms.quantum;
        assert!((dw - want).abs() <= 1e-9 * want, "{dw} vs {want}");
    }

    /// Terms that the model says vanish do, and the ones that grow with slope do.
    #[test]
    fn terms_vanish_and_grow_where_the_model_says() {
        let facing = Scene {
            exact_depth: true,
            ..scene(DepthFormat::Float32, 0.0, Snapping::SubpixelBits(8))
        };
        let t = error_terms(&facing).unwrap();
        assert_eq!((t.vertex, t.interpolation, t.snap), (0.0, 0.0, 0.0));
        assert_eq!(
            t.quantum,
            2f64.powi(-24),
            "window depths near 1 have f32 spacing 2^-24"
        );
        let unsnapped =
            error_terms(&scene(DepthFormat::Float32, 3.0, Snapping::Unsnapped)).unwrap();
        assert_eq!(unsnapped.snap, 0.0);
        let s1 = error_terms(&scene(DepthFormat::Float32, 1.0, Snapping::SubpixelBits(8))).unwrap();
        let s3 = error_terms(&scene(DepthFormat::Float32, 3.0, Snapping::SubpixelBits(8))).unwrap();
        // S grows with the slope and with the axis-crossing tilt (1 + s·e)/d₁.
        let e = 0.577_350_269_189_625_7;
        let want = 3.0 * (1.0 + 3.0 * e) / (1.0 + e);
        assert!((s3.snap / s1.snap - want).abs() < 1e-12);
        assert!(s3.vertex > s1.vertex);
    }

    fn f32_spacing(w: f64) -> f64 {
        // The gap to the next f32 above w as f32 (w a normal number, not a power of two's edge
        // case: the spacing above and below agree inside a binade).
        let x = w as f32;
        f64::from(f32::from_bits(x.to_bits() + 1)) - f64::from(x)
    }

    /// `NegOneToOne` through `recommend_clip` is `recommend`'s offset and matrix.
    #[test]
    fn the_standard_convention_is_unchanged() {
        let s = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
        let r = recommend(&s).unwrap();
        let c = recommend_clip(&s, ClipDepth::NegOneToOne).unwrap();
        assert_eq!(c.ndc_offset, -r.ndc_offset);
        assert_eq!(c.bleed_gap, r.bleed_gap);
        assert_eq!(
            c.matrix,
            crate::offset::epsilon_matrix(&s.frustum, r.epsilon).unwrap()
        );
    }

    /// Under `[0, 1]` the f32 matrix lowers NDC (= window) depth by at least the window offset
    /// and by at most one f32 step of element 10 more; the plain projection is untouched
    /// elsewhere. Differences of nearby f32 values are exact in f64.
    #[test]
    fn zero_to_one_carries_the_window_offset_in_element_10() {
        let s = scene(DepthFormat::Unorm24, 3.0, Snapping::SubpixelBits(8));
        let c = recommend_clip(&s, ClipDepth::ZeroToOne).unwrap();
        let plain = crate::projection::projection(&s.frustum, ClipDepth::ZeroToOne).unwrap();
        let lowered = f64::from(c.matrix[10]) - f64::from(plain[10]);
        let ulp = f64::from(plain[10].abs()) * 2f64.powi(-23);
        assert!(lowered >= c.window_offset && lowered <= c.window_offset + ulp);
        assert_eq!(c.ndc_offset, -c.window_offset);
        assert_eq!(
            (c.relative_epsilon, c.terms.quantum),
            (0.0, 1.0 / 16_777_215.0)
        );
        for i in (0..16).filter(|&i| i != 10) {
            assert_eq!(c.matrix[i], plain[i]);
        }
    }

    /// Reversed Z, infinite far, D32F: element 10 is 0 and stays 0; element 14 is scaled by at
    /// least 1 + ε; and at both ends of the decal (and where `w = n/d` crosses ⅛, a binade
    /// edge inside it) the window offset `ε·n/d` beats the f32 spacing there plus the error
    /// budget, the spacing taken from the bits of the stored value.
    #[test]
    fn reversed_infinite_float_beats_the_spacing_everywhere_on_the_decal() {
        let e = 0.5;
        let s = Scene {
            frustum: Frustum::new(-e, e, -e, e, 1.0, f64::INFINITY).unwrap(),
            depth_range: [6.0, 10.0],
            depth_test: DepthTest::Greater,
            ..scene(DepthFormat::Float32, 1.0, Snapping::Unsnapped)
        };
        let c = recommend_clip(&s, ClipDepth::ReversedZeroToOne).unwrap();
        let plain =
            crate::projection::projection(&s.frustum, ClipDepth::ReversedZeroToOne).unwrap();
        assert_eq!((plain[10], c.matrix[10]), (0.0, 0.0));
        assert!(f64::from(c.matrix[14]) / f64::from(plain[14]) - 1.0 >= c.relative_epsilon);
        let t = c.terms;
        let budget = 2.0 * (t.transform + t.vertex + t.interpolation + t.snap);
        for d in [6.0, 8.0, 10.0] {
            let w = 1.0 / d;
            let need = if d == 8.0 {
                2f64.powi(-26)
            } else {
                f32_spacing(w)
            } + budget;
            assert!(c.relative_epsilon * w >= need, "d = {d}");
        }
        // The binade edge decides: without it the far end alone would ask less.
        let far_only = (f32_spacing(0.1) + budget) * 10.0;
        assert!(c.relative_epsilon > far_only);
    }

    /// The bleed gap under reversed Z moves the base's window depth (n/d, infinite far) by the
    /// offset plus the budget at the decal's far end: `n/(d − G) − n/d`.
    #[test]
    fn reversed_bleed_gap_spans_the_offset_and_the_budget() {
        let e = 0.5;
        let s = Scene {
            frustum: Frustum::new(-e, e, -e, e, 1.0, f64::INFINITY).unwrap(),
            depth_range: [50.0, 60.0],
            depth_test: DepthTest::Greater,
            ..scene(DepthFormat::Float32, 0.5, Snapping::Unsnapped)
        };
        let c = recommend_clip(&s, ClipDepth::ReversedZeroToOne).unwrap();
        let t = c.terms;
        let budget = 2.0 * (t.transform + t.vertex + t.interpolation + t.snap);
        let dw = 1.0 / (60.0 - c.bleed_gap) - 1.0 / 60.0;
        let want = c.relative_epsilon / 60.0 + budget;
        assert!((dw - want).abs() <= 1e-9 * want, "{dw} vs {want}");
    }

    /// Under GL_LEQUAL a tie passes: the offset is one quantum smaller and the gap's window
    /// separation one quantum larger than under GL_LESS, for the same terms. The gap is an eye
    /// depth (−z) at the same pixel: Walker's window depth through `precision::window_depth`.
    #[test]
    fn or_equal_tests_trade_a_quantum_of_offset_for_a_quantum_of_gap() {
        let less = scene(DepthFormat::Unorm16, 1.0, Snapping::Unsnapped);
        let lequal = Scene {
            depth_test: DepthTest::LessEqual,
            ..less
        };
        let (a, b) = (recommend(&less).unwrap(), recommend(&lequal).unwrap());
        let q = a.terms.quantum;
        assert!((a.window_offset - b.window_offset - q).abs() <= 1e-12 * q);
        let w = |d| crate::precision::window_depth(1.0, 1e3, d).unwrap();
        let sep = |r: &Recommendation| w(120.0) - w(120.0 - r.bleed_gap);
        let budget = 2.0 * (a.terms.plane + a.terms.snap);
        assert!((sep(&a) - (a.window_offset + budget)).abs() <= 1e-9 * sep(&a));
        assert!((sep(&b) - (b.window_offset + budget + q)).abs() <= 1e-9 * sep(&b));
    }

    /// A base the rasterizer clips adds the term C, which grows with its reach; one inside the
    /// frustum adds nothing. A reach so large that the offset would push the decal past the
    /// near plane is refused as unresolvable, never answered.
    #[test]
    fn the_clip_term_grows_with_the_base_and_is_refused_when_unbounded() {
        let inside = scene(DepthFormat::Unorm24, 0.5, Snapping::Unsnapped);
        let clipped = |reach| Scene {
            base: Base::Clipped { reach },
            ..inside
        };
        assert_eq!(error_terms(&inside).unwrap().clip, 0.0);
        let (c1, c2) = (
            error_terms(&clipped(1e3)).unwrap().clip,
            error_terms(&clipped(1e4)).unwrap().clip,
        );
        assert!(c1 > 0.0 && c2 > 9.0 * c1, "{c1} {c2}");
        assert!(recommend(&clipped(1e3)).unwrap().window_offset > c1);
        // A costly base is answered, and the bleed gap says what it costs (an occluder in the
        // nearer part of the way to the eye is painted over) ...
        let costly = recommend(&clipped(1e7)).unwrap();
        assert!(costly.bleed_gap > 0.5 * inside.depth_range[1], "{costly:?}");
        // ... until the f32 clipper's error reaches the decal's own distance: refused, and the
        // message says what to do in C and Python.
        let e = recommend(&clipped(1e8)).unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Domain);
        assert!(
            e.to_string().contains("zshift_clip_to_frustum")
                && e.to_string().contains("base_reach"),
            "{e}"
        );
    }

    /// A measured `error_ulps` replaces `T + I` by `k·u·(1 + M)` (`M = w(d₂) + 2·G` without a
    /// footprint): the part above `V` doubles with `k`, stays below the bound, and the summary
    /// `plane_error` changes nothing.
    #[test]
    fn measured_error_ulps_scales_the_plane_error() {
        let worst = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
        let with = |k: f64, plane_error: f64| Scene {
            profile: RasterizerProfile {
                error_ulps: k,
                plane_error: [plane_error; 4],
                measured: true,
                ..worst.profile
            },
            ..worst
        };
        let bound = error_terms(&worst).unwrap();
        let a = error_terms(&with(1.4, f64::NAN)).unwrap();
        let b = error_terms(&with(2.8, f64::NAN)).unwrap();
        assert_eq!(
            bound.plane,
            bound.transform + bound.vertex + bound.interpolation
        );
        assert!(a.plane < bound.plane, "{a:?} vs {bound:?}");
        let above = |t: &ErrorTerms| t.plane - t.vertex;
        assert!((above(&b) - 2.0 * above(&a)).abs() <= 1e-12 * above(&b));
        assert_eq!(a, error_terms(&with(1.4, 0.5)).unwrap());
        // A huge figure never exceeds the bound.
        assert_eq!(
            error_terms(&with(1e6, f64::NAN)).unwrap().plane,
            bound.plane
        );
    }

    /// A facing plane with shared f32 z under GL_LEQUAL needs no offset (the chain is monotone in
    /// element 10); under GL_LESS it keeps q + 2E; the gap keeps the occluder's error either way.
    #[test]
    fn correlated_facing_planes_need_no_offset_under_an_equal_test() {
        let less = Scene {
            exact_depth: true,
            ..scene(DepthFormat::Unorm24, 0.0, Snapping::Unsnapped)
        };
        let lequal = Scene {
            depth_test: DepthTest::LessEqual,
            ..less
        };
        let (a, b) = (recommend(&less).unwrap(), recommend(&lequal).unwrap());
        assert!(!a.terms.correlated && b.terms.correlated);
        assert_eq!((b.window_offset, b.epsilon), (0.0, 0.0));
        assert!((a.window_offset - (a.terms.quantum + 2.0 * a.terms.plane)).abs() < 1e-20);
        assert!(b.bleed_gap > 0.0);
        let reversed = Scene {
            frustum: Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, f64::INFINITY).unwrap(),
            depth_test: DepthTest::GreaterEqual,
            ..lequal
        };
        let r = recommend_clip(&reversed, ClipDepth::ReversedZeroToOne).unwrap();
        assert_eq!(r.relative_epsilon, 0.0);
    }

    /// A measured facing figure replaces q + 2E for shared-z facing planes under a strict test and
    /// [−1, 1] only; never from the worst case, another convention or a sloped plane.
    #[test]
    fn a_measured_facing_offset_replaces_the_bound_where_measured() {
        let less = Scene {
            exact_depth: true,
            ..scene(DepthFormat::Unorm24, 0.0, Snapping::Unsnapped)
        };
        let measured = Scene {
            profile: RasterizerProfile {
                facing_quanta: [f64::NAN, 3.0, f64::NAN, 3.0],
                measured: true,
                ..less.profile
            },
            ..less
        };
        let q = 1.0 / 16_777_215.0;
        let (a, b) = (recommend(&less).unwrap(), recommend(&measured).unwrap());
        assert!((b.window_offset - 3.0 * q).abs() < 1e-20 && a.window_offset > b.window_offset);
        let float = Scene {
            format: DepthFormat::Float32,
            ..measured
        };
        assert_eq!(
            recommend(&float).unwrap().window_offset,
            3.0 * F32_UNIT_ROUNDOFF
        );
        let zero_to_one = recommend_clip(&measured, ClipDepth::ZeroToOne).unwrap();
        assert_eq!(zero_to_one.terms.facing, 0.0);
        // Reversed Z, D32F: the measured relative ε, over 1 − u for element 14's rounding.
        let reversed = Scene {
            frustum: Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, f64::INFINITY).unwrap(),
            format: DepthFormat::Float32,
            depth_test: DepthTest::Greater,
            profile: RasterizerProfile {
                facing_reversed: 2.5,
                ..measured.profile
            },
            ..measured
        };
        let r = recommend_clip(&reversed, ClipDepth::ReversedZeroToOne).unwrap();
        let want = 2.5 * F32_UNIT_ROUNDOFF / (1.0 - F32_UNIT_ROUNDOFF);
        assert_eq!(r.relative_epsilon, want);
        let unmeasured = Scene {
            profile: RasterizerProfile {
                measured: false,
                ..measured.profile
            },
            ..measured
        };
        assert_eq!(
            recommend(&unmeasured).unwrap().window_offset,
            a.window_offset
        );
    }

    /// A plane-preserving clipper replaces C by the base's own E + S plus 2 D24 quanta; the
    /// polygon-offset units divide by the profile's r.
    #[test]
    fn near_clip_and_resolvable_enter_where_documented() {
        let clipped = Scene {
            base: Base::Clipped { reach: 1e3 },
            ..scene(DepthFormat::Unorm24, 0.5, Snapping::Unsnapped)
        };
        let preserving = Scene {
            profile: RasterizerProfile {
                near_clip: NearClip::PlanePreserving,
                resolvable: [2.0; 4],
                ..clipped.profile
            },
            ..clipped
        };
        let (f32c, kept) = (
            error_terms(&clipped).unwrap(),
            error_terms(&preserving).unwrap(),
        );
        assert!((kept.clip - (kept.plane + kept.snap + 2.0 / 16_777_215.0)).abs() < 1e-20);
        assert!(kept.clip < f32c.clip);
        let (a, b) = (
            recommend(&clipped).unwrap(),
            recommend(&preserving).unwrap(),
        );
        let units = |r: &Recommendation, per: f64| r.window_offset / (per * r.terms.quantum);
        assert!((a.polygon_offset[1] - units(&a, 1.0)).abs() <= 1e-9 * a.polygon_offset[1]);
        assert!((b.polygon_offset[1] - units(&b, 2.0)).abs() <= 1e-9 * b.polygon_offset[1]);
        let zero_r = Scene {
            profile: RasterizerProfile {
                resolvable: [0.0; 4],
                ..clipped.profile
            },
            ..clipped
        };
        assert_eq!(recommend(&zero_r).unwrap_err().kind(), ErrorKind::Domain);
    }

    /// A measured `clip_ulps` `k` sets the clipper's `γ` to `4k·u` where that is below the bound
    /// `36u`: C is the bound's over 36/(4k), slightly more as the bound's larger `γ` also shrinks
    /// the denominator `d₁ − γR`; a figure above 9 keeps the bound; NaN (not measured) too.
    #[test]
    fn a_measured_clipper_figure_enters_with_its_margin() {
        let clipped = Scene {
            base: Base::Clipped { reach: 1e3 },
            ..scene(DepthFormat::Unorm24, 0.5, Snapping::Unsnapped)
        };
        let with = |k: f64| Scene {
            profile: RasterizerProfile {
                measured: true,
                clip_ulps: k,
                ..clipped.profile
            },
            ..clipped
        };
        let c = |s: &Scene| error_terms(s).unwrap().clip;
        let bound = c(&clipped);
        let ratio = bound / c(&with(1.0));
        assert!((9.0..9.0 * 1.01).contains(&ratio), "{ratio}");
        assert_eq!(c(&with(9.5)), bound);
        assert_eq!(c(&with(f64::NAN)), bound);
    }

    /// The depth test must match the convention; `DepthTest` round-trips GL enums.
    #[test]
    fn depth_tests_match_their_convention() {
        let s = scene(DepthFormat::Float32, 1.0, Snapping::Unsnapped);
        let reversed = Scene {
            depth_test: DepthTest::GreaterEqual,
            ..s
        };
        assert_eq!(recommend(&reversed).unwrap_err().kind(), ErrorKind::Domain);
        assert_eq!(
            recommend_clip(&s, ClipDepth::ReversedZeroToOne)
                .unwrap_err()
                .kind(),
            ErrorKind::Domain
        );
        assert!(recommend_clip(&reversed, ClipDepth::ReversedZeroToOne).is_ok());
        for t in [
            DepthTest::Less,
            DepthTest::LessEqual,
            DepthTest::Greater,
            DepthTest::GreaterEqual,
        ] {
            assert_eq!(DepthTest::from_gl(t.gl_enum()).unwrap(), t);
        }
        assert!(DepthTest::from_gl(0x0202).is_err()); // GL_EQUAL
    }

    #[test]
    fn bad_scenes_are_refused_with_their_kind() {
        let good = scene(DepthFormat::Unorm24, 1.0, Snapping::Unsnapped);
        let kind = |s: Scene| recommend(&s).unwrap_err().kind();
        assert_eq!(
            kind(Scene {
                slope: f64::NAN,
                ..good
            }),
            ErrorKind::NotFinite
        );
        assert_eq!(
            kind(Scene {
                slope: -1.0,
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                exact_depth: true,
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                depth_range: [120.0, 80.0],
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                depth_range: [0.5, 80.0],
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                viewport: [0, 256],
                ..good
            }),
            ErrorKind::Domain
        );
        assert_eq!(
            kind(Scene {
                profile: RasterizerProfile {
                    snapping: Snapping::SubpixelBits(40),
                    ..good.profile
                },
                ..good
            }),
            ErrorKind::Domain
        );
    }
}

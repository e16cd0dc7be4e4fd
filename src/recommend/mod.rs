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

mod conventions;
mod facing;
mod terms;
#[cfg(test)]
mod tests;

pub(crate) use conventions::bleed_gap_with;
pub use conventions::{recommend_clip, ClipRecommendation};
pub(crate) use conventions::{recommend_clip_building, reversed_epsilon_with};
pub(crate) use facing::chain_covers;
use facing::{measured_facing, measured_facing_reversed};
pub use terms::clip_error_terms;
pub(crate) use terms::mapping_of;

/// Cuts a base polygon to the view frustum in f64, so the rasterizer clips nothing (the term
/// `C`'s remedy, see [`crate::model::clip`]).
pub use crate::model::clip::{clip_to_frustum, clip_to_frustum_stored};

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

    /// Refuses a decal pass's test whose direction is not `clip`'s (`GL_GREATER`/`GL_GEQUAL`
    /// under reversed Z only), naming it as `depth_func`: one rule for the perspective and the
    /// orthographic model.
    pub(crate) fn check_convention(self, clip: ClipDepth) -> Result<()> {
        let reversed = clip == ClipDepth::ReversedZeroToOne;
        if self.is_reversed() == reversed {
            return Ok(());
        }
        Err(domain(if reversed {
            "reversed Z needs the depth test GL_GREATER or GL_GEQUAL"
        } else {
            "this clip convention needs the depth test GL_LESS or GL_LEQUAL (GL_GREATER/GL_GEQUAL are for reversed Z)"
        })
        .with_code("depth_func", self.gl_enum()))
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
    /// profile's [`RasterizerProfile::resolvable`] quanta (1 in the worst case: the smallest `r`
    /// known, so the units suffice everywhere). [`Recommendation::bleed_gap`] is the matrix
    /// offset's: where `r` is larger than the profile's (2 on NVIDIA, and on llvmpipe's UNORM;
    /// up to 4 known), these units move depth up to 4 times as far.
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
        Remedies::of(&scene.pipeline, &scene.profile),
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

/// What a near-plane refusal ([`check_in_range`]) may suggest besides the terms: whether a
/// probed profile was given, and whether world-space vertices go through one combined matrix
/// (`eye_first` false), whose independent clip-coordinate errors computing the eye position
/// first would shrink.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Remedies {
    pub measured: bool,
    pub combined_world: bool,
    /// World-space vertices (through an f32 view matrix): their rounding may be the cause.
    pub world: bool,
}

impl Remedies {
    pub(crate) fn of(pipeline: &Pipeline, profile: &RasterizerProfile) -> Self {
        Self {
            measured: profile.measured,
            combined_world: pipeline.world_space() && !pipeline.eye_first,
            world: pipeline.world_space(),
        }
    }
}

/// The near-plane refusal's sentences: the cause and its remedies, then the remedies that
/// apply ([`Remedies`]; `Error`'s detail is a static sentence, so each combination is one).
macro_rules! near_plane {
    ($cause:expr) => {
        near_plane!($cause, "move the near plane out")
    };
    ($cause:expr, $last:expr) => {
        [
            concat!($cause, ", pass a probed profile (zshift_probe), or ", $last),
            concat!($cause, ", or ", $last),
            concat!($cause, ", compute the eye position first in the vertex shader (proj * (view * p)) and say so (eye_first; Python keyword eye_first=True), pass a probed profile (zshift_probe), or ", $last),
            concat!($cause, ", compute the eye position first in the vertex shader (proj * (view * p)) and say so (eye_first; Python keyword eye_first=True), or ", $last),
        ]
    };
}

/// [`near_plane`] for a large clipped base.
const NEAR_PLANE_CLIPPING: [&str; 4] = near_plane!("the offset this scene needs moves the decal past the near plane (the float clipping of a large base): cut the base to the frustum (zshift_clip_to_frustum in C, zshift.clip_to_frustum in Python; stored in world space, zshift_clip_to_frustum_stored, or the Python keywords world_reach or view_matrix and world_box) and pass base_reach = 0");

/// [`near_plane`] for world-space vertices.
const NEAR_PLANE_WORLD: [&str; 4] = near_plane!("the offset this scene needs moves the decal past the near plane (the float rounding of world-space vertices far from the origin, largest on a plane that passes close to the eye): pass view_matrix and world_box (C fields; Python keywords) for the exact term if not given (a model-view multiplied in float: multiply it in double first), render relative to the camera");

/// [`near_plane`] for a decal whose nearest point lies within its own offset of the near plane,
/// neither a clipped base nor world-space rounding to blame.
const NEAR_PLANE_DECAL: [&str; 4] = near_plane!(
    "the offset this scene needs moves the decal past the near plane (the decal's nearest point lies within that offset of it): leave the part of the decal nearest the camera out of the decal pass",
    "pull the near plane in (a smaller n)"
);

/// [`near_plane`] for a decal that the rasterizer clips (off screen, or behind the camera).
const NEAR_PLANE_DECAL_CLIPPING: [&str; 4] = near_plane!("the offset this scene needs moves the decal past the near plane (the float clipping of a decal that reaches off screen or behind the camera): cut the decal to the frustum (zshift_clip_to_frustum in C, zshift.clip_to_frustum in Python; stored in world space, zshift_clip_to_frustum_stored), draw the cut polygon and pass its corners");

/// Whether `e` is a refusal of an offset that moves the decal past the near plane
/// ([`check_in_range`], or [`crate::orthographic`]'s), known by its sentence, not its wording.
pub(crate) fn moves_past_the_near_plane(e: &crate::Error) -> bool {
    let perspective = [
        NEAR_PLANE_CLIPPING,
        NEAR_PLANE_WORLD,
        NEAR_PLANE_DECAL,
        NEAR_PLANE_DECAL_CLIPPING,
    ];
    e.kind() == crate::ErrorKind::Unresolvable
        && (e.detail() == crate::orthographic::PAST_THE_NEAR_PLANE
            || perspective.iter().flatten().any(|s| *s == e.detail()))
}

/// Refuses an offset that would move the decal's nearest point out of the depth range (past
/// the near plane's window depth 0, or 1 under reversed Z): no offset then ends z-fighting,
/// which happens when the clipping term `C` of a large clipped base, or the vertex term of
/// world-space vertices far from the origin, dwarfs the decal's depth. The message names the
/// larger of the two and what to do about it (with `remedies`).
pub(crate) fn check_in_range(
    mapping: &DepthMapping,
    d1: f64,
    offset_at_d1: f64,
    terms: &ErrorTerms,
    remedies: Remedies,
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
        return Ok(());
    }
    // The larger of the two large terms names the cause; with neither (no clipped base, eye-space
    // vertices), the decal itself lies too near the near plane.
    let sentences = if terms.clip > 0.0 && terms.clip >= terms.vertex.max(terms.decal_clip) {
        NEAR_PLANE_CLIPPING
    } else if terms.decal_clip > 0.0 && terms.decal_clip >= terms.vertex {
        NEAR_PLANE_DECAL_CLIPPING
    } else if remedies.world {
        NEAR_PLANE_WORLD
    } else {
        NEAR_PLANE_DECAL
    };
    let index = usize::from(remedies.measured) + 2 * usize::from(remedies.combined_world);
    Err(crate::error::Error::new(
        crate::ErrorKind::Unresolvable,
        sentences[index],
    ))
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
    scene.depth_test.check_convention(clip)
}

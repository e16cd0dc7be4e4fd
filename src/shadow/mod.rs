//! Shadow-map bias: the smallest caster-side bias (in every API's units) that keeps a receiver
//! from shadowing itself ("acne"), from what an engine knows about its light and map, and what
//! that bias costs (peter-panning).
//!
//! # The problem
//! A shadow map stores, per texel, the window depth (in the light's view) of the nearest
//! caster at the texel's centre. A receiver point `p` is lit when its own light-space depth,
//! computed in the lookup shader, is not behind the stored depth of the texels its lookup reads.
//! For a surface that is its own caster the two depths are of one surface, computed differently
//! and at different places — the coplanar question of the seeds (004 lists shadows among the
//! problems of coplanar primitives), with two new terms: the texel's footprint and the lookup.
//!
//! # The model
//! All terms in unit window depth of the map; `u = 2⁻²⁴`. `p` is lit (standard conventions,
//! `GL_LEQUAL` comparison; reversed Z mirrors every sign) when
//!
//! `z_r(p) + e_r ≤ z_c(c) + e_c + e_q + β`
//!
//! with `z_r(p)` the exact depth of the receiver at `p`, `z_c(c)` the exact depth of the same
//! surface at the centre `c` of a texel the lookup reads, `e_r` the lookup's rounding, `e_c`
//! the caster's rasterization error, `e_q` the storage and read-back rounding and `β` the bias.
//! No pixel is darkened by its own surface when `β` covers every term:
//!
//! `β ≥ F + S + K`,   `K = q + E + (T + V) + R`                                     (B1)
//!
//! * `F`, **the texel footprint**: `z_r(p) − z_c(c) = g·(c − p)` on a plane whose window depth
//!   has gradient `g = (gₓ, g_y)` per map texel (a plane's window depth is affine in the map's
//!   pixels, under an orthographic and a perspective light alike). Every texel centre a lookup
//!   reads lies within `a` texels of `p` per axis: `a = ½` for nearest sampling (the centre of
//!   the texel containing `p`), `1` for hardware 2×2 comparison (the four texels around `p`),
//!   `k/2` for `k×k` PCF of nearest taps (taps `(k−1)/2` texels out, each to its own texel's
//!   centre), `ρ + ½` for a kernel of radius `ρ` texels. So `F ≤ a·(|gₓ| + |g_y|)`.
//!   * **Caster side**, the polygon-offset slope term adds `factor·m`, `m` the caster's own
//!     `max(|gₓ|, |g_y|)` (GL, D3D; Vulkan allows up to `√(gₓ² + g_y²)`, which only adds). Since
//!     `|gₓ| + |g_y| ≤ 2·max(|gₓ|, |g_y|)`, **`factor = 2a` covers `F` at every angle**, for
//!     the plane that is its own caster; the rasterizer computes `m·factor` in f32 from
//!     gradients set up to a relative `3u` (as in the decal's `I`), so the factor is taken
//!     `2a·(1 + 6u)`, rounded up to f32.
//!   * **At the limit angle** (for the clamp, the receiver-side offsets and the refusal), `g`
//!     follows from the angle `θ` between the light and the surface normal. *Orthographic*
//!     (texel `sₓ = (r − l)/W`, `s_y = (t − b)/H` in light units, depth `1/(f − n)` per unit):
//!     the plane's depth runs `tan θ` per unit along its steepest direction, so
//!     `|gₓ| + |g_y| ≤ tan θ·(|cos φ|·sₓ + |sin φ|·s_y)/(f − n) ≤ tan θ·σ/(f − n)`,
//!     `σ = √(sₓ² + s_y²)` the texel diagonal. *Perspective* (`w = F − b/d`, `b = fn/(f − n)`;
//!     `sₓ`, `s_y` the texel at the near plane): on the plane through `p` with unit normal `N`,
//!     `1/d = N·(kₓ, k_y, −1)/(N·p)` along the ray of tangents `k`, and a texel moves `k` by
//!     `s/n`, so `|gₓ| + |g_y| = b·(|Nₓ|sₓ + |N_y|s_y)/(n·|p|·cos θ_ray)` with `θ_ray` the angle
//!     between the normal and the ray to `p`. Writing `N = −cos θ·r̂ + sin θ·t̂` (`r̂` the ray,
//!     `t̂ ⊥ r̂`) and `|p| ≥ d`: `|gₓ| + |g_y| ≤ b/(n·d)·(Ψ + tan θ_ray·σ)`, with
//!     `Ψ = sₓ·eₓ/√(1 + eₓ²) + s_y·e_y/√(1 + e_y²)` (a surface facing the ray still has a
//!     gradient off the axis; `eₓ`, `e_y` the frustum's largest half-extent tangents). For a spot
//!     light the limit angle is taken to the light's **axis** (a ground plane has one angle to
//!     it), so `θ_ray ≤ θ + ψ`, `ψ = atan √(eₓ² + e_y²)` the widest ray's angle; at
//!     `θ + ψ ≥ 90°` no clamp is set. The largest `F` is at the nearest receiver, `d₁`.
//! * `q`, `E = T + V + I`, `S`: **the caster's own error**, one primitive of the decal model —
//!   [`crate::recommend`] (perspective light) or [`crate::orthographic`] (orthographic light),
//!   with the map as viewport, the receivers' light depths as the decal's range and the
//!   eye-space slope `√2·tan θ` of a plane at the limit angle to the light's axis (a measured
//!   profile enters as it does there). `q` bounds the storage: the stored value is within one
//!   quantum of the computed one under any rounding GL allows, and within `q/2 + u·w_max` where
//!   a measured profile identified the conversion (every candidate rounds to nearest; the `u`
//!   is the f32 product `w·(2^m − 1)` it may round first). `S ≤ 2^−(b+1)·(|gₓ| + |g_y|) ≤
//!   2^−b·m` grows with the caster's own slope `m` (below), so the slope factor carries it
//!   (`2a + 2^−b`) and the constant `K` leaves it out. With world-space vertices (`world_reach > 0`, or the light's view
//!   matrix given), `V` is the larger of the eye-space term and the f32 model-view term of
//!   [`crate::model::vertex`] ("The light's pipeline", below).
//! * `T + V`: **the lookup's own rounding**. The shader computes the receiver's light-space
//!   position `P·(V·p)` in f32 from its world position, divides by `w` and maps to window depth:
//!   the same f32 steps, on the same coordinates, as the caster's vertex transform, bounded by the
//!   same `T + V`. This assumes the receiver's position reaches the fragment on its surface to
//!   within the rounding of its coordinates (a world position interpolated from the vertices of
//!   a flat face, as engines pass it); interpolation error that moves the point *along* its
//!   surface only changes `p`, which `F` already allows for anywhere.
//! * `R`: **the read-back**: a UNORM texel sampled as float is rounded once, `u·w_max`
//!   (0 on D32F, whose texel is the f32 stored).
//!
//! No term is a fudge factor: each bounds one step, as in [`crate::recommend`].
//!
//! # The light's pipeline
//! Engines draw casters and look receivers up from world space: the caster's vertex shader
//! and the lookup's fragment shader both apply the light's f32 view matrix `V` (and its
//! projection `P`) to a world position `p`. The roundings of that product are relative to the
//! magnitudes of the terms each light-space eye coordinate `k` sums, not to `p`'s distance from
//! the light ([`crate::model::vertex`]). [`ShadowMap::pipeline`] says what the engine knows:
//!
//! * **nothing but `world_reach` `W`** (the default): every eye coordinate is bounded over every
//!   rotation, `A = √3·(4W + extent)`, `extent` the farthest point of the light's box from the
//!   light, and each clip coordinate errs independently by `γ_W·Bᵢ`,
//!   `Bᵢ = Σₖ |Pᵢₖ|·A + |Pᵢ₃|` (`γ_W = 14u`) — [`crate::model::vertex::world_error`] with the scalar reach;
//! * **the light's view matrix and the box `[lo, hi]` of every caster and receiver position**
//!   ([`crate::model::Pipeline::view`], [`crate::model::Pipeline::world_box`]): a term
//!   `Vₖⱼ·pⱼ` is at most `|Vₖⱼ|·max(|loⱼ|, |hiⱼ|)` for `p` in the box, and the translation
//!   `|Vₖ₃|`, so `Aₖ = Σⱼ |Vₖⱼ|·max(|loⱼ|, |hiⱼ|) + |Vₖ₃|` exactly per coordinate
//!   ([`crate::model::vertex::eye_magnitudes`]), whatever the light's rotation; the clip errors are
//!   `γ_W·Bᵢ` with `Bᵢ = Σₖ |Pᵢₖ|·Aₖ + |Pᵢ₃|`;
//! * **and the eye position computed first** (`proj * (view * p)` in both shaders,
//!   [`crate::model::Pipeline::eye_first`]) **with a listed receiver**: the error is an
//!   eye-space vector `δp`, `|δpₖ| ≤ γ_E·Aₖ` (`γ_E = 6u`), and it moves depth off the
//!   receiver's plane only through the plane's form on eye coordinates `g = L∘P`
//!   ([`crate::model::plane_form`]; `L` exact from the receiver's window plane in the map):
//!   `|L(P·δp)| ≤ γ_E·Σₖ |gₖ|·Aₖ`. A move along the plane costs nothing here: for the caster it
//!   leaves the stored surface where it was, for the lookup it moves the sample point along its
//!   surface, which `F` allows for at any point. Without a listed receiver the form is only
//!   bounded (over every plane of the limit angle's slope), and the independent clip errors
//!   above are used (they cover either order of the products).
//!
//! `V` is the bound on `|L(e)|` over the vertices, in NDC through the form, to unit window depth
//! by `½` under `[−1, 1]`: under an orthographic light `w = 1` and that is the term; under a
//! perspective light a pixel at light depth `d ≥ d₁` weighs its vertices' errors by `μᵢ/d`
//! (`Σ μᵢ = 1`), so the term is the bound over `d₁`, the nearest receiver
//! ([`crate::model::vertex::world_rounding`]). The lookup transforms a receiver position of the same box
//! with the same `V` and `P`, so its `V` is the same bound, counted a second time in `T + V`.
//!
//! **Shadow atlases.** A map drawn as a tile of a larger texture passes the tile's corner as
//! [`crate::model::Pipeline::viewport_origin`] and its `glDepthRange` as
//! [`crate::model::Pipeline::depth_range`]: the caster's interpolation term `I` then counts the
//! plane's run from the atlas's corner ([`crate::model::interpolation`]), the quantum is taken at
//! the stored depth and counted in unit window depth ([`crate::model::quantum`]), and the
//! roundings after the projection (`T`, the read `R`) are relative to the stored depth. The
//! terms stay in unit window depth; the units (against each API's `r` of stored depth) and the
//! clamp are in stored depth, as the APIs apply them (the slope factor needs no change: the
//! slope it multiplies is of stored depth too). `tests/gl_shadow.rs`
//! (`atlas_tiles_are_acne_free`) draws such tiles.
//!
//! # Outputs
//! The constant part `K` goes to each API's units against its own resolvable difference `r`
//! ([`crate::polygon_offset::resolvable_difference`]: Mesa's `1/(2^m − 1)` for GL over the
//! profile's `resolvable` factor, D3D's `1/(2^m − 1)`, Vulkan's and WebGPU's `2^−m` (the smaller
//! candidate, so the larger count); on D32F `2^(e − 23)` at the receivers' smallest window
//! depth, where it is smallest), rounded up (integers away from zero). The slope part is
//! `factor = 2a` (above). The clamp (`DepthBiasClamp`, Vulkan's `depthBiasClamp`,
//! `glPolygonOffsetClamp`) is `K + S + F(θ_max)`: the bias never exceeds what the limit angle needs,
//! and surfaces beyond it (facing away, hidden by shading) are left to acne; 0 means "no clamp"
//! in every API, which is what a spot light gets when its rays can graze, and any light where
//! the clamp would span the map's whole depth range (a grazing limit angle under a wide kernel
//! at a low resolution): the slope factor still covers every plane's footprint, and casters
//! that steep are pushed past the far plane and cast no shadow. Only a constant `K` that spans
//! the range is refused.
//!
//! **Receiver-side alternatives** (an engine biasing in the lookup shader): along the light,
//! the world distance whose depth change is `K + S + F(θ_max)` at the farthest receiver
//! (orthographic: `·(f − n)`; perspective: the eye shift `δ = β·d²/(b − β·d)` along the ray,
//! times `√(1 + e²)` for the widest ray). Along the normal by `δ_N`, a point lies
//! `δ_N/cos θ` in front of its surface along the light, which must reach `K_L + D_L·tan θ`
//! (`K_L` the constant, `D_L` the footprint per `tan θ`, as distances along the light):
//! `δ_N = max over θ ≤ θ_max of K_L·cos θ + D_L·sin θ`, at most `√(K_L² + D_L²)` — finite at
//! every angle, which is why engines bias along the normal.
//!
//! **The cost**: a caster biased by `δ_L` along the light is lit through a thickness `δ_L`
//! ([`ShadowBias::leak_thickness`]), and its shadow on ground lit at elevation `e` starts
//! `δ_L·cos e` away from a wall standing on it ([`ShadowBias::peter_panning`]), with `δ_L` the
//! clamp (the most any caster within the limit angle gets).
//!
//! # Receivers of known geometry
//! The bounds above hold for every plane within the limit angle anywhere in the light's
//! frustum. For a spot light that is costly: `K` takes the decal model's worst-case
//! extrapolation of a plane of slope `√2·tan θ` across the whole map, and `F(θ)` takes the
//! widest ray, so where `θ + ψ` reaches 90° no clamp can be set and grazing casters get an
//! unbounded slope-scaled bias (their shadows leak). An engine usually knows its receivers —
//! the ground, a terrain patch, the faces of large props — and [`shadow_bias_for_receivers`]
//! takes each as a planar polygon in the light's view space. For each receiver `i`:
//!
//! * its window-depth plane in the map, `w = w₀ + gₓ·x + g_y·y`, exact in f64 from its corners
//!   ([`crate::footprint::decal_shape_for_matrix`] with the light's projection and the map as
//!   viewport — the decal's footprint, reused). A plane's window depth is affine in the map's
//!   texels under either projection, so `F_i = a·(|gₓ| + |g_y|)` holds at every point of the
//!   receiver and every angle short of edge-on (widened by the corners' coplanarity tolerance,
//!   2⁻¹⁶ relative);
//! * `K_i`, `S_i`: the decal model on that footprint ([`crate::recommend::Scene::footprint`]):
//!   the run `|gₓ|·x + |g_y|·y` to its farthest texel and `|w₀|` replace the worst-case
//!   extrapolation, with the receiver's own depth range and slope (under an orthographic light
//!   the model has no footprint input, so only its slope and depth range tighten `K_i`);
//! * the caster side is unchanged: the factor `2a + 2^−b` covers `F_i + S_i` of each receiver
//!   through its own `m`, so the constant is `K = maxᵢ K_i` and the **clamp is
//!   `maxᵢ (K_i + S_i + F_i)`** — finite at every angle, because it bounds the receivers'
//!   actual gradients rather than the gradient of every plane the light could see. A receiver
//!   `i` is then lit where (B1) asks: its own caster bias is `min(K + factor·m_i, clamp)`, and
//!   both arguments reach `K_i + S_i + F_i`.
//!
//! A receiver whose front faces away from the light by more than the limit angle at every
//! point (for a spot light, the angle to the ray from the light to the point) is skipped: the
//! largest cosine of that angle over the polygon is `N_z` under an
//! orthographic light, and at most `h/d_min` under a spot (`h` the light's height above the
//! plane, `d_min` the receiver's nearest light depth, `|p| ≥ d_min`). Casters that are not
//! listed receivers (the far side of a box, a thin pole) get at most the clamp: they may show
//! acne where they are lit at a steeper angle than any listed receiver, which is the contract
//! ("list every surface that must stay clean"). The receiver-side offsets follow per receiver:
//! along the light, the eye shift `δ = β_i·d²/(b − β_i·d)` at its farthest point `d`, times
//! the largest `|p|/d` of its corners (orthographic: `β_i·(f − n)`); along the normal, that
//! times the largest cosine above (a point moved `δ_N` along the normal lies `δ_N/cos θ`
//! from its surface along the ray).
//!
//! **Meshes.** A kernel tap that lands on a neighbouring receiver `j` reads that receiver's
//! caster depth, biased by *its* slope term `factor·m_j` (of which `2a·m_j` is for the run of
//! depth, the rest its own snapping), while the lookup point lies up to `a` texels away along a
//! path across receivers near `j`, where the depth runs up to `a·(Gₓ + G_y)` (`G` the largest
//! `|gₓ|` and `|g_y|` of the receivers near `j`): where the neighbour is flatter (a facet nearer
//! a sphere's lit pole, a terrain's valley floor beside its slope) its slope term falls short.
//! Measured: a UV sphere and a terrain with hills under 5×5 PCF showed acne (up to 18 pixels of
//! 5376) with the receivers' own planes alone. So the constant gains `a·(Gₓ + G_y − 2·m_j)` at
//! its largest over the receivers (near: extents within `a + 1` texels of each other in the
//! map), and the clamp at least `K + S + a·(Gₓ + G_y)` at its largest (the run a tap can read
//! across them); one planar receiver, or several of one slope, are unchanged. [`shadow_bias`]
//! promises planar receivers only (planar across the kernel: every tap on the receiver's own
//! plane); for curved or creased ones list their faces (`tests/gl_shadow/receivers.rs`: 0 acne
//! on both, every lookup).
//!
//! **Refusal.** When `K + S + F(θ_max)` reaches the map's whole depth range (1), the bias would lift
//! every caster past the far plane: no bias both ends acne at that angle and still shadows
//! anything. [`shadow_bias`] then refuses with [`crate::ErrorKind::Unresolvable`], naming the
//! remedy for the larger part: a higher resolution, a smaller kernel or a smaller limit angle
//! for `F`; a tighter near/far or a deeper format for `K`.

use crate::domain::{domain, finite};
use crate::error::{Error, ErrorKind, Result};
use crate::orthographic::Ortho;
use crate::polygon_offset::{resolvable_difference, BiasApi};
use crate::precision::DepthFormat;
use crate::profile::RasterizerProfile;
use crate::projection::{ClipDepth, Frustum};
use crate::recommend::{Base, DepthTest, Scene};

// `u = 2⁻²⁴`, the unit roundoff of f32 (one home: crate::model).
use crate::model::F32_UNIT_ROUNDOFF as U;

mod outputs;
mod receivers;
mod terms;
#[cfg(test)]
mod tests;

use outputs::finish;
pub use receivers::shadow_bias_for_receivers;
use terms::terms_of;

/// The light's projection.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightProjection {
    /// A directional light or a cascade: `glOrtho(l, r, b, t, n, f)` in the light's view.
    Orthographic(Ortho),
    /// A spot light: `glFrustum(l, r, b, t, n, f)` in the light's view (finite `f`).
    Perspective(Frustum),
}

/// How the lookup reads the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lookup {
    /// One texel, the one containing the sample point.
    Nearest,
    /// Hardware depth comparison with linear filtering: the four texels around the point.
    Hardware2x2,
    /// `k×k` percentage-closer filtering of nearest taps one texel apart (`k` odd or even, ≥ 1).
    Pcf(u32),
    /// Taps up to `radius` texels from the point per axis (a Poisson disc, a rotated kernel),
    /// each reading its nearest texel.
    Radius(f64),
}

impl Lookup {
    /// `a`: how far, in texels per axis, a texel centre the lookup reads can lie from the
    /// sample point (module docs).
    ///
    /// # Errors
    /// [`ErrorKind::Domain`] for `Pcf(0)` or a negative radius; [`ErrorKind::NotFinite`] for a
    /// NaN or infinite radius.
    pub fn reach(self) -> Result<f64> {
        match self {
            Lookup::Nearest => Ok(0.5),
            Lookup::Hardware2x2 => Ok(1.0),
            Lookup::Pcf(0) => Err(domain("a k x k PCF kernel needs k >= 1").with_integer("pcf", 0)),
            Lookup::Pcf(k) => Ok(f64::from(k) / 2.0),
            Lookup::Radius(r) => {
                finite(r, "the kernel radius is NaN or infinite")
                    .map_err(|e| e.with_value("kernel_radius", r))?;
                if r < 0.0 {
                    return Err(domain("the kernel radius must be >= 0 texels")
                        .with_value("kernel_radius", r));
                }
                Ok(r + 0.5)
            }
        }
    }
}

/// What an engine knows about one shadow map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowMap {
    /// The light's projection (its view is a rigid transform of world space).
    pub light: LightProjection,
    /// The map's clip convention (reversed: `GL_GEQUAL` comparison, map cleared to 0).
    pub clip: ClipDepth,
    /// The map's width and height in texels.
    pub resolution: [u32; 2],
    /// The map's depth format.
    pub format: DepthFormat,
    /// How the lookup reads it.
    pub lookup: Lookup,
    /// The limit angle, in degrees, between the light and a surface normal beyond which the
    /// surface counts as facing away: `0 ≤ θ < 90`. Surfaces beyond it may show acne (shading
    /// hides them). The light is an orthographic light's direction; for a spot light,
    /// [`shadow_bias`] takes its axis (it knows no positions) and
    /// [`shadow_bias_for_receivers`] the ray from the light to each point of a receiver, the
    /// angle the shading sees (a face at 78° to the axis may be 85° to its ray).
    pub limit_angle_deg: f64,
    /// The receivers' nearest and farthest light-space depth (`−z` in the light's view), inside
    /// `[n, f]`: pass `[n, f]` when unknown.
    pub receiver_depths: [f64; 2],
    /// The largest world coordinate of the light's position and of every model origin (the
    /// f32 model-view term, [`crate::model::vertex`]); 0 for vertices already in the light's
    /// view space.
    pub world_reach: f64,
    /// The light's elevation above the ground, in degrees (`0 < e ≤ 90`), for the
    /// peter-panning figure only.
    pub elevation_deg: f64,
    /// The rasterizer that draws the map ([`RasterizerProfile::worst_case`] unless measured).
    pub profile: RasterizerProfile,
    /// What the engine knows about the light's vertex pipeline ([`crate::model::Pipeline`]):
    /// the light's view matrix with the box of the world positions it maps
    /// ([`crate::model::Pipeline::view`], [`crate::model::Pipeline::world_box`]), and whether
    /// the shaders compute the light-space eye position first
    /// ([`crate::model::Pipeline::eye_first`]). Its `world_reach` adds to the map's (the larger
    /// counts). [`Default`]: today's scalar bound from `world_reach` alone. Its framebuffer
    /// state is the map's: [`crate::model::Pipeline::viewport_origin`] is the tile's corner in
    /// a shadow atlas (the rasterizer extrapolates the caster's depth plane from the atlas's
    /// origin, [`crate::model::interpolation`]), [`crate::model::Pipeline::depth_range`] the
    /// `glDepthRange` the map is drawn with (the lookup must compare against
    /// `near + (far − near)·w` too). The terms stay in unit window depth; the bias's units
    /// and clamp are in stored depth, as the APIs apply them.
    pub pipeline: crate::model::Pipeline,
}

/// The terms of (B1), in unit window depth of the map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowTerms {
    /// `a`: texels per axis from the sample point to the farthest texel centre read.
    pub reach: f64,
    /// `q`: the storage term, the format's quantum at the receivers' largest window depth, or
    /// `min(q, q/2 + u·w_max)` where a measured profile identified the rasterizer's conversion
    /// to UNORM (its `facing_chain`).
    pub quantum: f64,
    /// `E = T + V + I`: the caster's rasterization error (the decal model's per-primitive
    /// terms).
    pub caster: f64,
    /// `S`: sub-pixel snapping of the caster at the limit angle (0 unsnapped). It grows with the
    /// caster's slope, so the slope factor carries it (`2^−b` per unit of `m`) and only the
    /// clamp counts it here.
    pub snap: f64,
    /// The slope factor per unit of `m = max(|gₓ|, |g_y|)`, before f32 rounding: `2a + 2^−b`
    /// (`b` the profile's sub-pixel bits; `2a` unsnapped).
    pub slope_factor: f64,
    /// `T + V`: the lookup's rounding of the receiver's light-space depth.
    pub lookup: f64,
    /// `R`: rounding of a UNORM texel read back as float.
    pub read: f64,
    /// `K = q + E + (T + V) + R`.
    pub constant: f64,
    /// `F` at the limit angle and the nearest receiver (`+∞` where a spot light's rays can
    /// reach 90°).
    pub footprint: f64,
}

/// Direct3D 10–12's rasterizer-state depth bias.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct D3dBias {
    /// `DepthBias` (INT).
    pub depth_bias: i32,
    /// `SlopeScaledDepthBias` (FLOAT).
    pub slope_scaled: f32,
    /// `DepthBiasClamp` (FLOAT; 0: none).
    pub clamp: f32,
}

/// The recommendation for a [`ShadowMap`]. Signs are as each API adds the bias to the caster's
/// depth: positive (away from the light) under `[−1, 1]` and `[0, 1]`, negative reversed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowBias {
    /// The terms.
    pub terms: ShadowTerms,
    /// `glPolygonOffset(factor, units)` with the profile's `r`, and the clamp for
    /// `glPolygonOffsetClamp` (0: none).
    pub gl_polygon_offset: [f64; 3],
    /// Direct3D's `DepthBias`, `SlopeScaledDepthBias`, `DepthBiasClamp`.
    pub d3d: D3dBias,
    /// Vulkan's `depthBiasConstantFactor`, `depthBiasSlopeFactor`, `depthBiasClamp` (default
    /// `LEAST_REPRESENTABLE_VALUE_FORMAT` representation).
    pub vulkan: [f32; 3],
    /// WebGPU's `DepthBiasState`: `depthBias` (integer).
    pub webgpu_depth_bias: i32,
    /// WebGPU's `depthBiasSlopeScale` and `depthBiasClamp`.
    pub webgpu_slope_clamp: [f32; 2],
    /// Receiver side: the world distance to move the receiver toward the light, at the
    /// farthest receiver (+∞ where no such offset exists: a spot light whose rays can graze the
    /// limit, or whose depth range ends within the bias behind the farthest receiver, or an
    /// offset that would move the nearest receiver onto or past a spot light).
    pub along_light: f64,
    /// Receiver side: the world distance to move the receiver along its normal (+∞ where the
    /// bias reaches past a spot light's far plane at the farthest receiver, or where it would
    /// move the nearest receiver onto or past a spot light). The move also shifts the
    /// receiver's shadow sideways by up to this times the sine of its angle to the light
    /// (normal-offset shadows).
    pub along_normal: f64,
    /// The most a caster within the limit angle is biased, as a distance along the light: a
    /// caster thinner than this casts no shadow (+∞ without a clamp).
    pub leak_thickness: f64,
    /// How far from a wall standing on the ground its shadow starts, at the light's elevation:
    /// `leak_thickness·cos e`.
    pub peter_panning: f64,
}

/// The smallest caster-side bias that (B1) guarantees keeps every surface within the limit
/// angle free of acne, in every API's units, with its receiver-side alternatives and its cost
/// (module docs). Receivers must be planar across the lookup's reach (every kernel tap on the
/// receiver's own plane): a mesh whose faces bend within a few texels (a sphere, a terrain) can
/// show acne under wide kernels; list its faces with [`shadow_bias_for_receivers`] ("Meshes" in
/// the module docs).
///
/// # Errors
/// [`ErrorKind::NotFinite`] or [`ErrorKind::Domain`] for a bad input, naming it;
/// [`ErrorKind::Unresolvable`] where the bias would span the map's whole depth range (the
/// detail names the remedy); [`ErrorKind::Overflow`] where an integer bias does not fit.
pub fn shadow_bias(map: &ShadowMap) -> Result<ShadowBias> {
    let terms = shadow_terms(map)?;
    let needed = terms.constant + terms.snap + terms.footprint;
    finish(map, terms, needed, None)
}

/// The terms of (B1) for `map` (module docs).
///
/// # Errors
/// As [`shadow_bias`], without the refusal.
pub fn shadow_terms(map: &ShadowMap) -> Result<ShadowTerms> {
    check(map)?;
    let theta = map.limit_angle_deg.to_radians();
    terms_of(
        map,
        map.receiver_depths,
        std::f64::consts::SQRT_2 * theta.tan(),
        None,
    )
}

/// The rules: receivers inside `[n, f]` and ordered, a nonzero map, an angle in `[0, 90)`, an
/// elevation in `(0, 90]`, a finite non-negative world reach, a finite far plane.
///
/// # Errors
/// [`ErrorKind::NotFinite`] and [`ErrorKind::Domain`], naming the input.
pub fn check(map: &ShadowMap) -> Result<()> {
    if map.resolution.contains(&0) {
        return Err(domain("the shadow map needs a nonzero width and height"));
    }
    let a = map.limit_angle_deg;
    finite(a, "the limit angle is NaN or infinite")
        .map_err(|e| e.with_value("limit_angle_deg", a))?;
    if !(0.0..90.0).contains(&a) {
        return Err(
            domain("the limit angle must lie in [0, 90) degrees").with_value("limit_angle_deg", a)
        );
    }
    let e = map.elevation_deg;
    finite(e, "the light's elevation is NaN or infinite")
        .map_err(|x| x.with_value("elevation_deg", e))?;
    if !(e > 0.0 && e <= 90.0) {
        return Err(domain("the light's elevation must lie in (0, 90] degrees")
            .with_value("elevation_deg", e));
    }
    let w = map.world_reach;
    finite(w, "world_reach is NaN or infinite").map_err(|x| x.with_value("world_reach", w))?;
    if w < 0.0 {
        return Err(domain("world_reach must be >= 0").with_value("world_reach", w));
    }
    map.pipeline.check()?;
    let [d1, d2] = map.receiver_depths;
    for (name, d) in [("receiver_near", d1), ("receiver_far", d2)] {
        finite(d, "a receiver depth is NaN or infinite").map_err(|x| x.with_value(name, d))?;
    }
    let (n, f) = match map.light {
        LightProjection::Orthographic(o) => (o.near(), o.far()),
        LightProjection::Perspective(fr) => {
            let (_, _, _, _, n, f) = fr.parameters();
            if f.is_infinite() {
                return Err(domain("a spot light's far plane must be finite").with_value("f", f));
            }
            (n, f)
        }
    };
    if !(n <= d1 && d1 <= d2 && d2 <= f) {
        return Err(domain(
            "the receiver depths must satisfy n <= receiver_near <= receiver_far <= f",
        )
        .with_value(
            if d1 > d2 || d1 < n {
                "receiver_near"
            } else {
                "receiver_far"
            },
            if d1 > d2 || d1 < n { d1 } else { d2 },
        ));
    }
    let r = map.profile.resolvable[crate::model::measured::profile_index(map.format)];
    if !(r.is_finite() && r > 0.0) {
        return Err(
            domain("the profile's resolvable r for this format must be finite and > 0")
                .with_value("resolvable", r),
        );
    }
    Ok(())
}

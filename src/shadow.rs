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
//!   `Bᵢ = Σₖ |Pᵢₖ|·A + |Pᵢ₃|` (`γ_W = 14u`) — [`vertex::world_error`] with the scalar reach;
//! * **the light's view matrix and the box `[lo, hi]` of every caster and receiver position**
//!   ([`crate::model::Pipeline::view`], [`crate::model::Pipeline::world_box`]): a term
//!   `Vₖⱼ·pⱼ` is at most `|Vₖⱼ|·max(|loⱼ|, |hiⱼ|)` for `p` in the box, and the translation
//!   `|Vₖ₃|`, so `Aₖ = Σⱼ |Vₖⱼ|·max(|loⱼ|, |hiⱼ|) + |Vₖ₃|` exactly per coordinate
//!   ([`vertex::eye_magnitudes`]), whatever the light's rotation; the clip errors are
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
//! ([`vertex::world_rounding`]). The lookup transforms a receiver position of the same box
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
//! in every API, which is what a spot light gets when its rays can graze.
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
//! **Meshes.** A kernel tap that lands on a neighbouring receiver reads that receiver's caster
//! depth, biased by *its* slope term `factor·m_j`, while the lookup point sits on a receiver `i`
//! whose depth runs up to `a·(|gₓ| + |g_y|)` of the steepest faces the path crosses: where the
//! neighbour is flatter (a facet nearer a sphere's lit pole, a terrain's valley floor beside its
//! slope) its slope term falls short. Measured: a UV sphere and a terrain with hills under 5×5
//! PCF showed acne (up to 18 pixels of 5376) with the receivers' own planes alone. So the
//! constant gains `factor·(m_i − m_j)` at its largest over receivers a kernel reads across
//! (extents within `a + 1` texels of each other in the map: the flatter one's caster bias then
//! reaches the steeper one's slope term) and the clamp at least
//! `K + S + a·(max |gₓ| + max |g_y|)` (the largest run a tap can read across them); one planar
//! receiver, or several of one slope, are unchanged. [`shadow_bias`] promises planar receivers
//! only (planar across the kernel: every tap on the receiver's own plane); for curved or creased
//! ones list their faces (`tests/gl_shadow/receivers.rs`: 0 acne on both, every lookup).
//!
//! **Refusal.** When `K + S + F(θ_max)` reaches the map's whole depth range (1), the bias would lift
//! every caster past the far plane: no bias both ends acne at that angle and still shadows
//! anything. [`shadow_bias`] then refuses with [`crate::ErrorKind::Unresolvable`], naming the
//! remedy for the larger part: a higher resolution, a smaller kernel or a smaller limit angle
//! for `F`; a tighter near/far or a deeper format for `K`.

use crate::domain::{domain, finite};
use crate::error::{Error, ErrorKind, Result};
use crate::model::{vertex, PlaneForm};
use crate::orthographic::Ortho;
use crate::polygon_offset::{resolvable_difference, BiasApi};
use crate::precision::DepthFormat;
use crate::profile::RasterizerProfile;
use crate::projection::{ClipDepth, Frustum};
use crate::recommend::{Base, DepthTest, Scene};

// `u = 2⁻²⁴`, the unit roundoff of f32 (one home: crate::model).
use crate::model::F32_UNIT_ROUNDOFF as U;

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

/// The outputs for `terms` with the clamp `needed` (`+∞`: none) and, when known, the
/// receiver-side offsets `(along_light, along_normal)`; else they follow from the limit angle.
fn finish(
    map: &ShadowMap,
    terms: ShadowTerms,
    needed: f64,
    offsets: Option<(f64, f64)>,
) -> Result<ShadowBias> {
    // An infinite footprint (a spot light whose rays can graze) sets no clamp: not a refusal.
    if (needed.is_finite() && needed >= 1.0) || terms.constant.is_nan() || terms.constant >= 1.0 {
        return Err(Error::new(
            ErrorKind::Unresolvable,
            if terms.footprint > terms.constant {
                "no shadow bias is acne-free at this limit angle: the texel footprint spans the map's depth range (raise the resolution, use a smaller kernel, or lower limit_angle_deg)"
            } else {
                "no shadow bias is acne-free: the rounding terms span the map's depth range (tighten the light's near/far or use a deeper format)"
            },
        )
        .with_value("limit_angle_deg", map.limit_angle_deg));
    }
    let sign = if map.clip == ClipDepth::ReversedZeroToOne {
        -1.0
    } else {
        1.0
    };
    let factor = round_up_f32(terms.slope_factor * (1.0 + 6.0 * U));
    // The clamp bounds the offset in stored depth: the unit window depth it needs, times
    // far − near of glDepthRange (the slope factor needs no change: the slope it multiplies is
    // of stored depth too).
    let clamp = if needed.is_finite() {
        needed * map.pipeline.span()
    } else {
        0.0
    };
    let clamp32 = round_up_f32(clamp);
    // The smallest resolvable difference over the receivers: UNORM's is constant; float's
    // grows with depth, so take it at the smallest window depth.
    let w_small = smallest_window_depth(map)?;
    let units_of = |r: f64| -> f64 { terms.constant / r };
    // Each API's r is a difference of stored depth, taken at the stored depth of w_small under
    // glDepthRange; counted here in unit window depth, as the terms are.
    let pipeline = &map.pipeline;
    let unit_r = |api: BiasApi| -> Result<f64> {
        Ok(pipeline.per_unit(resolvable_difference(
            api,
            map.format,
            pipeline.actual(w_small),
        )?))
    };
    let gl_r = unit_r(BiasApi::OpenGl)?
        * map.profile.resolvable[crate::model::measured::profile_index(map.format)];
    let d3d_r = unit_r(BiasApi::Direct3d)?;
    let vk_r = unit_r(BiasApi::Vulkan)?;
    let gl_units = units_of(gl_r);
    let vk_count = units_of(vk_r);
    if vk_count.is_nan() || vk_count > f64::from(i32::MAX) {
        return Err(Error::new(
            ErrorKind::Unresolvable,
            "on D32F the polygon-offset unit vanishes at the receivers' smallest window depth: keep receivers off window depth 0 (the far plane under reversed Z, the near plane otherwise) or bias on the receiver side",
        )
        .with_value("receiver_near", map.receiver_depths[0]));
    }
    let int_units = |x: f64, what: &'static str| -> Result<i32> {
        let c = x.ceil();
        if c.is_nan() || c > f64::from(i32::MAX) {
            return Err(Error::new(ErrorKind::Overflow, what));
        }
        Ok(c as i32)
    };
    let d3d_units = int_units(
        units_of(d3d_r),
        "the Direct3D DepthBias does not fit in INT",
    )?;
    let webgpu_units = int_units(units_of(vk_r), "the WebGPU depthBias does not fit in i32")?;
    let vk_units = round_up_f32(units_of(vk_r));
    let isign = sign as i32;
    let (along_light, along_normal, leak) = match offsets {
        Some((light, normal)) => (light, normal, light),
        None => receiver_offsets(map, &terms)?,
    };
    // A receiver moved toward a spot light by its light depth or more reaches or passes the
    // light, where the projection flips: no such offset works. (Short of it, past the near
    // plane, the lookup's depth leaves the map's range on the lit side; along the ray its map
    // position stays. A directional light has no such point.)
    let room = match map.light {
        LightProjection::Perspective(_) => map.receiver_depths[0],
        LightProjection::Orthographic(_) => f64::INFINITY,
    };
    let usable = |offset: f64| if offset < room { offset } else { f64::INFINITY };
    let (along_light, along_normal) = (usable(along_light), usable(along_normal));
    let e = map.elevation_deg.to_radians();
    Ok(ShadowBias {
        terms,
        gl_polygon_offset: [
            sign * f64::from(factor),
            sign * gl_units.ceil(),
            sign * f64::from(clamp32),
        ],
        d3d: D3dBias {
            depth_bias: isign * d3d_units,
            slope_scaled: sign as f32 * factor,
            clamp: sign as f32 * clamp32,
        },
        vulkan: [
            sign as f32 * vk_units,
            sign as f32 * factor,
            sign as f32 * clamp32,
        ],
        webgpu_depth_bias: isign * webgpu_units,
        webgpu_slope_clamp: [sign as f32 * factor, sign as f32 * clamp32],
        along_light,
        along_normal,
        leak_thickness: leak,
        peter_panning: leak * e.cos(),
    })
}

/// The recommendation for the receivers an engine lists, from their own planes (module docs,
/// "Receivers of known geometry"): each receiver is a planar polygon in the light's view space
/// (right-handed, looking down −z; for a spot light the light at the origin), its corners
/// counter-clockwise seen from its front (the side that is lit), every corner inside the light's
/// frustum (clip a larger polygon to it first). A receiver whose front faces away from the light
/// by more than `map.limit_angle_deg` at every point is skipped (shading hides it); the others
/// are acne-free at the returned bias, at every angle short of edge-on, also where a kernel
/// reads across from one to another (the faces of a mesh: "Meshes" in the module docs).
/// `map.receiver_depths` is not used (the receivers' own depths are).
///
/// # Errors
/// As [`shadow_bias`]; [`ErrorKind::Domain`] for a receiver that is not a planar polygon inside
/// the frustum (named by its index), or when every receiver is skipped.
pub fn shadow_bias_for_receivers(
    map: &ShadowMap,
    receivers: &[&[glam::Vec3]],
) -> Result<ShadowBias> {
    check(map)?;
    let (n, f) = light_range(map);
    let matrix = match map.light {
        LightProjection::Perspective(frustum) => {
            crate::projection::projection_f64(&frustum, map.clip)?
        }
        LightProjection::Orthographic(ortho) => crate::orthographic::ortho_f64(&ortho, map.clip),
    };
    let cos_limit = map.limit_angle_deg.to_radians().cos();
    let mut all: Option<ShadowTerms> = None;
    let (mut needed, mut along_light, mut along_normal) = (0.0f64, 0.0f64, 0.0f64);
    let mut depths = [f64::INFINITY, 0.0f64];
    let mut slopes = SlopeSpread::default();
    for (i, corners) in receivers.iter().enumerate() {
        let named = |e: Error| e.with_integer("receiver", i as i64);
        let eye: Vec<[f64; 3]> = corners
            .iter()
            .map(|c| [f64::from(c.x), f64::from(c.y), f64::from(c.z)])
            .collect();
        if eye.len() < 3 {
            return Err(named(domain("a receiver needs at least 3 corners")));
        }
        for p in &eye {
            for &c in p {
                finite(c, "a receiver corner is not finite").map_err(named)?;
            }
            let d = -p[2];
            if d < n || d > f {
                return Err(named(domain(
                    "every receiver corner's light depth -z must lie within the light's [n, f]",
                )));
            }
        }
        let (normal, offset) = crate::footprint::plane_through(&eye).map_err(named)?;
        let (d_min, d_max) = eye.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(-p[2]), b.max(-p[2]))
        });
        // The largest cosine of the angle between the front normal and the direction to the
        // light over the polygon: `N_z` under an orthographic light; `h/|p| ≤ h/d_min` under a
        // spot (`h = −N·p` the light's height above the plane, `|p| ≥ −z`).
        let cos_max = match map.light {
            LightProjection::Orthographic(_) => normal[2],
            LightProjection::Perspective(_) => (-offset / d_min).min(1.0),
        };
        if !(cos_max > 0.0 && cos_max >= cos_limit) {
            continue;
        }
        let shape =
            crate::footprint::decal_shape_for_matrix(&matrix, map.clip, map.resolution, corners)
                .map_err(named)?;
        let [w, h] = map.resolution.map(f64::from);
        let slack = 1e-6 * w.max(h);
        // The receiver's extent in the map (texels), for the kernels that read across to it.
        let mut extent = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for p in &eye {
            let c = [0, 1, 3].map(|r| {
                matrix[r] * p[0] + matrix[4 + r] * p[1] + matrix[8 + r] * p[2] + matrix[12 + r]
            });
            let (x, y) = ((0.5 * c[0] / c[2] + 0.5) * w, (0.5 * c[1] / c[2] + 0.5) * h);
            extent = [
                extent[0].min(x),
                extent[1].max(x),
                extent[2].min(y),
                extent[3].max(y),
            ];
            if !(-slack..=w + slack).contains(&x) || !(-slack..=h + slack).contains(&y) {
                return Err(named(domain(
                    "every receiver corner must lie inside the light's frustum (clip the receiver to it)",
                )));
            }
        }
        let t =
            terms_of(map, [d_min, d_max], shape.slope, Some(&shape.footprint)).map_err(named)?;
        let own = t.constant + t.snap + t.footprint;
        // As distances along the light: the shift whose window change is `own` at the
        // receiver's farthest point, and along the normal that times the largest cosine.
        let light_distance = match map.light {
            LightProjection::Orthographic(_) => own * (f - n),
            LightProjection::Perspective(_) => {
                let bb = f * n / (f - n);
                let den = bb - own * d_max;
                let along = eye
                    .iter()
                    .map(|p| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() / -p[2])
                    .fold(1.0f64, f64::max);
                if den <= 0.0 {
                    f64::INFINITY
                } else {
                    own * d_max * d_max / den * along
                }
            }
        };
        needed = needed.max(own);
        slopes.add(shape.footprint.gradient, t.snap, extent);
        along_light = along_light.max(light_distance);
        along_normal = along_normal.max(light_distance * cos_max);
        depths = [depths[0].min(d_min), depths[1].max(d_max)];
        all = Some(match all {
            None => t,
            Some(a) => ShadowTerms {
                reach: a.reach,
                quantum: a.quantum.max(t.quantum),
                caster: a.caster.max(t.caster),
                snap: a.snap.max(t.snap),
                slope_factor: a.slope_factor,
                lookup: a.lookup.max(t.lookup),
                read: a.read.max(t.read),
                constant: a.constant.max(t.constant),
                footprint: a.footprint.max(t.footprint),
            },
        });
    }
    let Some(mut terms) = all else {
        return Err(domain(
            "no receiver faces the light within limit_angle_deg: list a lit receiver or raise the limit",
        )
        .with_value("limit_angle_deg", map.limit_angle_deg));
    };
    // Receivers of different slopes meet (a mesh: "Meshes" in the module docs). The clamp
    // reaches the largest run a tap can read across them (`a` texels of the largest |gₓ| and of
    // the largest |g_y|) on top of the constant and snapping terms, and a tap that reads a
    // flatter neighbour gets, in the constant, what its smaller slope term lacks.
    needed = needed.max(terms.constant + slopes.snap + terms.reach * slopes.run());
    terms.constant += terms.slope_factor * slopes.spread(terms.reach);
    let map = ShadowMap {
        receiver_depths: depths,
        ..*map
    };
    finish(&map, terms, needed, Some((along_light, along_normal)))
}

/// A receiver's footprint term is widened by the coplanarity tolerance its corners are accepted
/// with (2⁻¹⁶ of their size).
const COPLANARITY_WIDENING: f64 = 1.0 + 1.0 / 65_536.0;

/// The slopes of the listed receivers, for a kernel that reads across from one to another.
#[derive(Default)]
struct SlopeSpread {
    /// Each receiver's `m = max(|gₓ|, |g_y|)` and its extent in the map, `[x₀, x₁, y₀, y₁]`
    /// (texels).
    faces: Vec<(f64, [f64; 4])>,
    /// The largest `|gₓ|` and `|g_y|`, each over every receiver.
    g: [f64; 2],
    /// The largest snapping term.
    snap: f64,
}

impl SlopeSpread {
    fn add(&mut self, gradient: [f64; 2], snap: f64, extent: [f64; 4]) {
        let [gx, gy] = gradient.map(f64::abs);
        self.faces.push((gx.max(gy), extent));
        self.g = [self.g[0].max(gx), self.g[1].max(gy)];
        self.snap = self.snap.max(snap);
    }

    /// The largest `m_i − m_j` over receivers a kernel of `reach` texels reads across: a tap on
    /// `j` reads a caster biased by `j`'s slope term while the lookup on `i` runs at `i`'s, so
    /// the constant adds the difference. A tap lands at most `reach` texels from the lookup
    /// point and takes the texel whose centre its face covers, half a texel further: only
    /// receivers whose extents come within `reach + 1` texels of each other count (a sweep
    /// over the extents sorted by `x₀`). Separate meshes listed together then do not pay for
    /// each other's slopes; on one smooth mesh (a sphere towards its terminator) neighbours'
    /// slopes differ almost as much as the mesh's extremes, and little changes.
    fn spread(&self, reach: f64) -> f64 {
        let near = reach + 1.0;
        let mut order: Vec<&(f64, [f64; 4])> = self.faces.iter().collect();
        order.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]));
        let mut spread = 0.0f64;
        for (i, (m_i, e_i)) in order.iter().enumerate() {
            for (m_j, e_j) in order[i + 1..]
                .iter()
                .take_while(|(_, e)| e[0] <= e_i[1] + near)
            {
                if e_j[2] <= e_i[3] + near && e_i[2] <= e_j[3] + near {
                    spread = spread.max((m_i - m_j).abs());
                }
            }
        }
        spread
    }

    /// `(max |gₓ| + max |g_y|)·(1 + 2⁻¹⁶)`: the largest depth run per texel of reach along a
    /// path that crosses receivers (each texel step inside one of them), widened as each
    /// receiver's own footprint term is.
    fn run(&self) -> f64 {
        (self.g[0] + self.g[1]) * COPLANARITY_WIDENING
    }
}

/// The storage term of `K`: the stored UNORM value is within the quantum `q` of the computed
/// depth under any rounding GL allows; where the probe identified the rasterizer's conversion
/// (a measured profile's [`RasterizerProfile::facing_chain`], every one of its candidates rounds
/// to the nearest integer), within `q/2` plus the f32 rounding of the product `w·(2^m − 1)`
/// the conversion may take first (`u·w_max`, relative). The smaller of the two. D32F stores
/// the computed depth: `quantum` is its own term there and is left as it is.
fn storage(map: &ShadowMap, quantum: f64, w_max: f64) -> f64 {
    match map.profile.facing_chain {
        Some(_) if map.profile.measured && map.format.is_unorm() => {
            quantum.min(0.5 * quantum + U * w_max)
        }
        _ => quantum,
    }
}

/// The vertex pipeline of the light's caster and lookup shaders ([`crate::model::vertex`]): the
/// map's pipeline with the larger of the two `world_reach`es (both bound the same
/// coordinates).
fn vertex_pipeline(map: &ShadowMap) -> crate::model::Pipeline {
    crate::model::Pipeline {
        world_reach: map.world_reach.max(map.pipeline.world_reach),
        ..map.pipeline
    }
}

/// The light's near and far distances.
fn light_range(map: &ShadowMap) -> (f64, f64) {
    match map.light {
        LightProjection::Orthographic(o) => (o.near(), o.far()),
        LightProjection::Perspective(fr) => {
            let (_, _, _, _, n, f) = fr.parameters();
            (n, f)
        }
    }
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

/// The terms of (B1) for receivers at light depths `[d1, d2]` of eye-space slope `slope`: every
/// plane within the limit angle (`receiver = None`), or one receiver plane with its exact
/// window-depth plane in the map (`Some`: the decal model runs on that footprint, and `F` is
/// `a·(|gₓ| + |g_y|)` of its gradient).
fn terms_of(
    map: &ShadowMap,
    [d1, d2]: [f64; 2],
    slope: f64,
    receiver: Option<&crate::footprint::Footprint>,
) -> Result<ShadowTerms> {
    let reach = map.lookup.reach()?;
    let theta = map.limit_angle_deg.to_radians();
    // The receiver's own footprint term: exact in f64 from its window plane, widened.
    let own = receiver
        .map(|fp| reach * (fp.gradient[0].abs() + fp.gradient[1].abs()) * COPLANARITY_WIDENING);
    let [w_px, h_px] = map.resolution.map(f64::from);
    let (caster, snap, lookup, quantum, footprint, w_max) = match map.light {
        LightProjection::Perspective(frustum) => {
            let scene = Scene {
                frustum,
                viewport: map.resolution,
                format: map.format,
                depth_range: [d1, d2],
                slope,
                exact_depth: false,
                depth_test: if map.clip == ClipDepth::ReversedZeroToOne {
                    DepthTest::Greater
                } else {
                    DepthTest::Less
                },
                base: Base::InsideFrustum,
                profile: map.profile,
                footprint: receiver.copied(),
                pipeline: vertex_pipeline(map),
            };
            let t = crate::recommend::clip_error_terms(&scene, map.clip)?;
            let (l, r, b, top, n, f) = frustum.parameters();
            let (sx, sy) = ((r - l).abs() / w_px, (top - b).abs() / h_px);
            let (ex, ey) = (l.abs().max(r.abs()) / n, b.abs().max(top.abs()) / n);
            let psi_xy = sx * ex / (1.0 + ex * ex).sqrt() + sy * ey / (1.0 + ey * ey).sqrt();
            let psi = (ex.hypot(ey)).atan();
            let bb = f * n / (f - n);
            let ray = theta + psi;
            let footprint = if let Some(own) = own {
                own
            } else if ray >= std::f64::consts::FRAC_PI_2 {
                f64::INFINITY
            } else {
                reach * bb / (n * d1) * (psi_xy + ray.tan() * sx.hypot(sy))
            };
            let mapping = crate::precision::DepthMapping::projection(n, f, map.clip)?;
            let w_max = mapping.window_depth(d1)?.max(mapping.window_depth(d2)?);
            (
                t.plane,
                t.snap,
                t.transform + t.vertex,
                t.quantum,
                footprint,
                w_max,
            )
        }
        LightProjection::Orthographic(ortho) => {
            let decal = crate::decal::Decal {
                viewport: map.resolution,
                format: map.format,
                depth_range: [d1, d2],
                slope,
                exact_depth: false,
                snapping: map.profile.snapping,
                base: Base::InsideFrustum,
                profile: Some(map.profile),
                footprint: None,
                depth_test: None,
                // The framebuffer state (an atlas tile's origin, glDepthRange); the vertex
                // pipeline is the light's own term, ortho_world_term.
                pipeline: crate::model::Pipeline {
                    viewport_origin: map.pipeline.viewport_origin,
                    depth_range: map.pipeline.depth_range,
                    ..crate::model::Pipeline::default()
                },
            };
            let t = crate::orthographic::error_terms(
                &crate::orthographic::Scene { ortho, decal },
                map.clip,
            )?;
            let (l, r, b, top, n, f) = ortho.parameters();
            let span = f - n;
            let (sx, sy) = ((r - l).abs() / w_px, (top - b).abs() / h_px);
            let vertex = if vertex_pipeline(map).world_space() {
                t.vertex
                    .max(ortho_world_term(map, &ortho, slope, receiver)?)
            } else {
                t.vertex
            };
            let footprint = own.unwrap_or(reach * theta.tan() * sx.hypot(sy) / span);
            let w_max = ortho
                .window_depth(map.clip, d1)?
                .max(ortho.window_depth(map.clip, d2)?);
            let plane = t.plane - t.vertex + vertex;
            (
                plane,
                t.snap,
                t.transform + vertex,
                t.quantum,
                footprint,
                w_max,
            )
        }
    };
    // Under glDepthRange(near, far) the stored depth is near + (far − near)·w: roundings of it
    // are relative to w + lift in unit window depth.
    let lift = map.pipeline.depth_range[0] / map.pipeline.span();
    let read = if map.format.is_unorm() {
        U * (w_max + lift)
    } else {
        0.0
    };
    let quantum = storage(map, quantum, w_max + lift);
    let snap_factor = match map.profile.snapping {
        crate::profile::Snapping::SubpixelBits(b) => 2f64.powi(-(b as i32)),
        crate::profile::Snapping::Unsnapped => 0.0,
    };
    Ok(ShadowTerms {
        reach,
        quantum,
        caster,
        snap,
        slope_factor: 2.0 * reach + snap_factor,
        lookup,
        read,
        constant: quantum + caster + lookup + read,
        footprint,
    })
}

/// The f32 model-view term of an orthographic light ([`crate::model::vertex`]): the form of a
/// plane of slope `s` has `|aₓ| ≤ |A|·s·(r − l)/2`, `|a_y| ≤ |A|·s·(t − b)/2` (`A` the NDC
/// depth per eye unit) and `|a₀| ≤ 1 + |aₓ| + |a_y|` (the map's centre is at most one NDC unit
/// per axis from a point inside it); `w = 1`, and a point of the box lies within
/// `√(X² + Y² + max(|n|, |f|)²)` of the light.
fn ortho_world_term(
    map: &ShadowMap,
    ortho: &Ortho,
    slope: f64,
    receiver: Option<&crate::footprint::Footprint>,
) -> Result<f64> {
    let m = crate::orthographic::ortho_f64(ortho, map.clip);
    let (l, r, b, t, n, f) = ortho.parameters();
    let a = m[10].abs();
    let (ax, ay) = (
        a * slope * (r - l).abs() / 2.0,
        a * slope * (t - b).abs() / 2.0,
    );
    let form = PlaneForm {
        a0: 1.0 + ax + ay,
        ax,
        ay,
    };
    let extent = (l.abs().max(r.abs()).powi(2)
        + b.abs().max(t.abs()).powi(2)
        + n.abs().max(f.abs()).powi(2))
    .sqrt();
    let per_ndc = if map.clip == ClipDepth::NegOneToOne {
        0.5
    } else {
        1.0
    };
    // With a listed receiver, its exact form (the eye-first path needs it); else the bounds
    // over every plane of the slope.
    let (form, exact) = match receiver {
        Some(fp) => (PlaneForm::of_footprint(fp, map.resolution, map.clip), true),
        None => (form, false),
    };
    let (error, _) = vertex::world_error(&form, exact, &m, &vertex_pipeline(map), extent);
    crate::domain::representable(per_ndc * error, "the vertex term overflows f64")
}

/// The receivers' smallest window depth in the map (where float depth's `r` is smallest).
fn smallest_window_depth(map: &ShadowMap) -> Result<f64> {
    let [d1, d2] = map.receiver_depths;
    Ok(match map.light {
        LightProjection::Perspective(frustum) => {
            let (_, _, _, _, n, f) = frustum.parameters();
            let mapping = crate::precision::DepthMapping::projection(n, f, map.clip)?;
            mapping.window_depth(d1)?.min(mapping.window_depth(d2)?)
        }
        LightProjection::Orthographic(ortho) => ortho
            .window_depth(map.clip, d1)?
            .min(ortho.window_depth(map.clip, d2)?),
    })
}

/// `(along_light, along_normal, leak_thickness)` (module docs), at the farthest receiver.
fn receiver_offsets(map: &ShadowMap, terms: &ShadowTerms) -> Result<(f64, f64, f64)> {
    let theta = map.limit_angle_deg.to_radians();
    let d2 = map.receiver_depths[1];
    // Constant and footprint-per-tan as distances along the light.
    let (k_l, d_l, ray_limit) = match map.light {
        LightProjection::Orthographic(ortho) => {
            let span = ortho.far() - ortho.near();
            let per_tan = if theta == 0.0 {
                0.0
            } else {
                terms.footprint / theta.tan()
            };
            ((terms.constant + terms.snap) * span, per_tan * span, theta)
        }
        LightProjection::Perspective(frustum) => {
            let (l, r, b, t, n, f) = frustum.parameters();
            let bb = f * n / (f - n);
            let (ex, ey) = (l.abs().max(r.abs()) / n, b.abs().max(t.abs()) / n);
            let along = (1.0 + ex * ex + ey * ey).sqrt();
            let (w_px, h_px) = (f64::from(map.resolution[0]), f64::from(map.resolution[1]));
            let (sx, sy) = ((r - l).abs() / w_px, (t - b).abs() / h_px);
            let psi_xy = sx * ex / (1.0 + ex * ex).sqrt() + sy * ey / (1.0 + ey * ey).sqrt();
            // Eye shift for a window change β at d₂: β·d²/(b − β·d).
            // (+∞ where β reaches the end of the depth range: no receiver-side offset along the
            // light gives that window change there.)
            let shift = |beta: f64| -> Result<f64> {
                let den = bb - beta * d2;
                Ok(if den <= 0.0 {
                    f64::INFINITY
                } else {
                    beta * d2 * d2 / den
                })
            };
            let base = terms.constant + terms.snap + terms.reach * bb / (n * d2) * psi_xy;
            let per_tan = terms.reach * bb / (n * d2) * sx.hypot(sy);
            let k = shift(base)? * along;
            // The footprint's share, linear in the window change near 0: its eye size is the
            // shift of base + per_tan less that of base, at tan θ = 1 (an upper bound by the
            // convexity of the shift in β is not needed: d_l is used only with tan θ ≤ its
            // value at the limit, below).
            let psi = ex.hypot(ey).atan();
            let ray = (theta + psi).min(std::f64::consts::FRAC_PI_2);
            let d = if k.is_infinite() {
                f64::INFINITY
            } else if ray < std::f64::consts::FRAC_PI_2 && ray > 0.0 {
                (shift(base + per_tan * ray.tan())? * along - k) / ray.tan()
            } else {
                shift(per_tan)? * along
            };
            (k, d, ray)
        }
    };
    if !(k_l.is_finite() && d_l.is_finite()) {
        return Ok((f64::INFINITY, f64::INFINITY, f64::INFINITY));
    }
    let along_light = if ray_limit >= std::f64::consts::FRAC_PI_2 {
        f64::INFINITY
    } else {
        k_l + d_l * ray_limit.tan()
    };
    // max over θ ≤ limit of K·cos θ + D·sin θ: √(K² + D²) at atan(D/K) if inside, else at the
    // limit.
    let peak = d_l.atan2(k_l);
    let along_normal = if peak <= ray_limit {
        k_l.hypot(d_l)
    } else {
        k_l * ray_limit.cos() + d_l * ray_limit.sin()
    };
    Ok((along_light, along_normal, along_light))
}

/// The smallest f32 not below `x`.
fn round_up_f32(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) >= x {
        y
    } else {
        f32::from_bits(y.to_bits() + 1)
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn ground_map(lookup: Lookup, angle: f64) -> ShadowMap {
        ShadowMap {
            light: LightProjection::Orthographic(
                Ortho::new(-8.0, 8.0, -8.0, 8.0, 2.0, 30.0).unwrap(),
            ),
            clip: ClipDepth::NegOneToOne,
            resolution: [1024, 1024],
            format: DepthFormat::Unorm24,
            lookup,
            limit_angle_deg: angle,
            receiver_depths: [2.0, 30.0],
            world_reach: 0.0,
            elevation_deg: 90.0 - angle,
            profile: RasterizerProfile::worst_case(),
            pipeline: crate::model::Pipeline::default(),
        }
    }

    /// A measured profile whose conversion the probe identified stores D16 within half a
    /// quantum (plus the f32 product's rounding): the storage term halves; without the chain, or
    /// with the worst case, it stays a whole quantum; D32F has no conversion to halve.
    #[test]
    fn an_identified_conversion_halves_the_storage_term() {
        let q16 = 1.0 / 65_535.0;
        let chain = crate::depth_chain::DepthChain {
            fused_clip: false,
            reciprocal: true,
            fused_viewport: false,
            conversion: crate::depth_chain::Conversion::F32NearestEven,
        };
        let measured = RasterizerProfile {
            measured: true,
            facing_chain: Some(chain),
            ..RasterizerProfile::worst_case()
        };
        let d16 = ShadowMap {
            format: DepthFormat::Unorm16,
            ..ground_map(Lookup::Nearest, 60.0)
        };
        let worst = shadow_bias(&d16).unwrap().terms.quantum;
        assert!((worst - q16).abs() < 1e-12 * q16, "{worst}");
        let probed = shadow_bias(&ShadowMap {
            profile: measured,
            ..d16
        })
        .unwrap()
        .terms
        .quantum;
        assert!(probed >= 0.5 * q16 && probed <= 0.5 * q16 + U, "{probed}");
        let unidentified = RasterizerProfile {
            facing_chain: None,
            ..measured
        };
        let kept = shadow_bias(&ShadowMap {
            profile: unidentified,
            ..d16
        })
        .unwrap()
        .terms
        .quantum;
        assert_eq!(kept, worst);
        // Receivers off the near plane, where D32F's polygon-offset unit does not vanish.
        let d32f = ShadowMap {
            format: DepthFormat::Float32,
            receiver_depths: [3.0, 30.0],
            ..d16
        };
        let float = shadow_bias(&d32f).unwrap().terms.quantum;
        let measured_float = shadow_bias(&ShadowMap {
            profile: measured,
            ..d32f
        })
        .unwrap()
        .terms
        .quantum;
        assert_eq!(measured_float, float);
    }

    /// The slope factor is `2a`; the footprint at the limit is `a·tan θ·σ/(f − n)` (computed
    /// here from the texel geometry, not from the code); the constant holds the quantum.
    #[test]
    fn footprint_and_factor_follow_the_kernel() {
        for (lookup, a) in [
            (Lookup::Nearest, 0.5),
            (Lookup::Hardware2x2, 1.0),
            (Lookup::Pcf(3), 1.5),
            (Lookup::Radius(2.0), 2.5),
        ] {
            let map = ground_map(lookup, 60.0);
            let bias = shadow_bias(&map).unwrap();
            let texel = 16.0 / 1024.0;
            let want = a * 3f64.sqrt() * texel * 2f64.sqrt() / 28.0;
            assert!(
                (bias.terms.footprint - want).abs() < 1e-12 * want,
                "{lookup:?}"
            );
            let factor = 2.0 * a + 1.0 / 256.0; // 8 sub-pixel bits in the worst case
            assert!(f64::from(bias.d3d.slope_scaled) >= factor);
            assert!(f64::from(bias.d3d.slope_scaled) < factor * (1.0 + 1e-6));
            assert!(bias.terms.constant > 1.0 / 16_777_215.0);
            // A few tens of quanta: the caster's interpolation term counts the plane's run
            // from the map's origin (1.4 units of window depth at 60° here).
            assert!(
                bias.terms.constant < 30.0 / 16_777_215.0,
                "{:?}",
                bias.terms
            );
            // The clamp is the constant plus the footprint at the limit.
            let clamp = f64::from(bias.d3d.clamp);
            assert!(clamp >= bias.terms.constant + bias.terms.snap + bias.terms.footprint);
            // Receiver side: along the light, the window bias times f − n.
            let along = (bias.terms.constant + bias.terms.snap + bias.terms.footprint) * 28.0;
            assert!((bias.along_light - along).abs() < 1e-9 * along);
            assert!(bias.along_normal <= bias.along_light && bias.along_normal > 0.0);
            // D3D's integer covers the constant in units of 1/(2^24 − 1).
            assert!(f64::from(bias.d3d.depth_bias) / 16_777_215.0 >= bias.terms.constant);
            assert!(bias.webgpu_depth_bias >= bias.d3d.depth_bias);
        }
    }

    #[test]
    fn reversed_z_flips_the_signs() {
        let mut map = ground_map(Lookup::Nearest, 45.0);
        map.clip = ClipDepth::ReversedZeroToOne;
        map.format = DepthFormat::Float32;
        // Receivers at the far plane have window depth 0, where float's unit vanishes.
        let err = shadow_bias(&map).unwrap_err();
        assert_eq!(
            (err.kind(), err.input().unwrap().0),
            (ErrorKind::Unresolvable, "receiver_near")
        );
        map.receiver_depths = [2.0, 28.0];
        let bias = shadow_bias(&map).unwrap();
        assert!(bias.gl_polygon_offset[0] < 0.0 && bias.gl_polygon_offset[1] < 0.0);
        assert!(bias.d3d.depth_bias < 0 && bias.vulkan[2] < 0.0);
        assert!(bias.along_light > 0.0);
    }

    #[test]
    fn grazing_limits_are_refused_with_the_footprint_remedy() {
        let mut map = ground_map(Lookup::Pcf(5), 89.9);
        map.resolution = [64, 64];
        let err = shadow_bias(&map).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::Unresolvable);
        assert!(err.detail().contains("resolution"), "{err}");
        map.limit_angle_deg = 90.0;
        assert_eq!(shadow_bias(&map).unwrap_err().kind(), ErrorKind::Domain);
        map.limit_angle_deg = 30.0;
        map.receiver_depths = [1.0, 30.0];
        let err = shadow_bias(&map).unwrap_err();
        assert_eq!(err.input().unwrap().0, "receiver_near");
        map.receiver_depths = [2.0, 30.0];
        map.lookup = Lookup::Pcf(0);
        assert_eq!(shadow_bias(&map).unwrap_err().input().unwrap().0, "pcf");
    }

    /// A spot light: the footprint shrinks with the nearest receiver's distance, and a wide
    /// cone at a steep limit gets no clamp.
    #[test]
    fn spot_lights_take_the_ray_angle() {
        let frustum = Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, 100.0).unwrap();
        let mut map = ShadowMap {
            light: LightProjection::Perspective(frustum),
            receiver_depths: [10.0, 50.0],
            ..ground_map(Lookup::Nearest, 30.0)
        };
        let near = shadow_bias(&map).unwrap();
        map.receiver_depths = [20.0, 50.0];
        let far = shadow_bias(&map).unwrap();
        assert!((near.terms.footprint / far.terms.footprint - 2.0).abs() < 1e-9);
        map.limit_angle_deg = 60.0; // 60° + atan(0.707) = 95°
        let open = shadow_bias(&map).unwrap();
        assert!(open.terms.footprint.is_infinite());
        assert_eq!(open.d3d.clamp, 0.0);
        assert!(open.along_normal.is_finite() && open.along_light.is_infinite());
    }

    /// The light's pipeline: with its view matrix and the world box, the f32 view term is the
    /// exact per-coordinate one, no larger than the bound from `world_reach` (here far smaller);
    /// a zeroed pipeline is the scalar bound; a view without its box is refused by name.
    /// A directional light's box and a spot light's frustum over the same receivers.
    fn both_lights() -> [LightProjection; 2] {
        let frustum = Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, 100.0).unwrap();
        [
            LightProjection::Orthographic(Ortho::new(-8.0, 8.0, -8.0, 8.0, 2.0, 30.0).unwrap()),
            LightProjection::Perspective(frustum),
        ]
    }

    #[test]
    fn the_lights_view_tightens_the_vertex_term() {
        for light in both_lights() {
            let scalar = ShadowMap {
                light,
                world_reach: 25.0,
                receiver_depths: [10.0, 30.0],
                ..ground_map(Lookup::Nearest, 30.0)
            };
            let base = shadow_bias(&scalar).unwrap();
            let mut viewed = scalar;
            viewed.pipeline.view = Some([
                1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -25.0, 1.0,
            ]);
            viewed.pipeline.world_box = Some([[-8.0, -8.0, -5.0], [8.0, 8.0, 15.0]]);
            viewed.pipeline.eye_first = true;
            let tight = shadow_bias(&viewed).unwrap();
            assert!(tight.terms.lookup < 0.5 * base.terms.lookup, "{light:?}");
            assert!(tight.terms.constant < base.terms.constant);
            let mut boxless = viewed;
            boxless.pipeline.world_box = None;
            assert!(shadow_bias(&boxless)
                .unwrap_err()
                .to_string()
                .contains("world_box"));
        }
    }

    /// A map in a shadow atlas: a tile far from the atlas's origin extrapolates the caster's
    /// plane further (the caster term grows, the quantum does not); `glDepthRange(0.5, 1)`
    /// doubles a UNORM quantum in unit window depth, and the clamp, which GL applies to stored
    /// depth, is the unit bias times 0.5. Both answered, neither refused.
    #[test]
    fn an_atlas_tile_and_a_depth_range_are_modelled() {
        for light in both_lights() {
            let map = ShadowMap {
                light,
                receiver_depths: [10.0, 30.0],
                ..ground_map(Lookup::Nearest, 30.0)
            };
            let whole = shadow_bias(&map).unwrap();
            let mut tile = map;
            tile.pipeline.viewport_origin = [3072, 2048];
            let tiled = shadow_bias(&tile).unwrap();
            assert!(tiled.terms.caster > whole.terms.caster, "{light:?}");
            assert_eq!(tiled.terms.quantum, whole.terms.quantum);
            assert_eq!(tiled.terms.footprint, whole.terms.footprint);
            let mut ranged = map;
            ranged.pipeline.depth_range = [0.5, 1.0];
            let half = shadow_bias(&ranged).unwrap();
            assert_eq!(half.terms.quantum, 2.0 * whole.terms.quantum);
            let needed = half.terms.constant + half.terms.snap + half.terms.footprint;
            assert!((half.gl_polygon_offset[2] - 0.5 * needed).abs() <= 1e-6 * needed);
            // Units of the stored r: the unit constant times 0.5, over 2⁻²⁴ (D24).
            let units = half.terms.constant * 0.5 * 16_777_215.0;
            assert!(
                (half.gl_polygon_offset[1] - units.ceil()).abs() <= 1.0,
                "{half:?}"
            );
        }
    }

    /// A spot light over grazing ground: with the ground listed, the footprint is the ground's
    /// own `a·(|gₓ| + |g_y|)` (of its window plane in the map), the clamp is
    /// set, and the constant is no larger than the conservative one.
    #[test]
    fn listed_receivers_take_their_own_plane() {
        let frustum = Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, 100.0).unwrap();
        let map = ShadowMap {
            light: LightProjection::Perspective(frustum),
            receiver_depths: [10.0, 50.0],
            ..ground_map(Lookup::Nearest, 80.0)
        };
        let conservative = shadow_bias(&map).unwrap();
        assert!(conservative.terms.footprint.is_infinite());
        // Ground 3 units below the light, tilted 85° from the axis: y = −3 − z·tan 5°, seen
        // from above (+y), counter-clockwise.
        let y = |z: f32| -3.0 - (-z) * 5f32.to_radians().tan();
        let ground: Vec<glam::Vec3> = [(4.0, -12.0), (12.0, -45.0), (-12.0, -45.0), (-4.0, -12.0)]
            .iter()
            .map(|&(x, z)| glam::Vec3::new(x, y(z), z))
            .collect();
        let bias = shadow_bias_for_receivers(&map, &[&ground]).unwrap();
        let shape =
            crate::footprint::decal_shape(&frustum, map.clip, map.resolution, &ground).unwrap();
        let own = 0.5 * (shape.footprint.gradient[0].abs() + shape.footprint.gradient[1].abs());
        assert!(bias.terms.footprint >= own && bias.terms.footprint < own * 1.0001);
        assert!(bias.gl_polygon_offset[2] > 0.0 && bias.gl_polygon_offset[2] < 1.0);
        assert!(bias.terms.constant <= conservative.terms.constant);
        assert!(bias.along_light.is_finite() && bias.along_normal <= bias.along_light);
        // Facing away everywhere: skipped, and with nothing left, refused.
        let away: Vec<glam::Vec3> = ground.iter().rev().copied().collect();
        let err = shadow_bias_for_receivers(&map, &[&away]).unwrap_err();
        assert_eq!(err.kind(), ErrorKind::Domain);
        let both = shadow_bias_for_receivers(&map, &[&away, &ground]).unwrap();
        assert_eq!(both, bias);
        // A corner outside the frustum is named.
        let mut wide = ground.clone();
        wide[1].x = 40.0;
        let err = shadow_bias_for_receivers(&map, &[&ground, &wide]).unwrap_err();
        assert!(err.to_string().contains("frustum"), "{err}");
    }

    /// Two faces of a mesh under an orthographic light (window depth affine in the map, its
    /// gradient computed here from three projected corners): listed together, the constant
    /// gains `factor·(m_steep − m_flat)` over the larger of the two listed alone, and the clamp
    /// covers `a·(max |gₓ| + max |g_y|)` on top of the constant; two faces of one slope change
    /// nothing.
    #[test]
    fn faces_of_a_mesh_cover_the_spread_of_their_slopes() {
        let map = ground_map(Lookup::Pcf(5), 80.0);
        let [l, r, b, t, n, f] = [-8.0, 8.0, -8.0, 8.0, 2.0, 30.0];
        let texel = |x: f64, y: f64, z: f64| {
            // glOrtho's window position (texels) and window depth of an eye point.
            [
                (x - l) / (r - l) * 1024.0,
                (y - b) / (t - b) * 1024.0,
                (-z - n) / (f - n),
            ]
        };
        // A face of the plane z = z0 + sx·x + sy·y, counter-clockwise seen from the light.
        let face = |x0: f32, sx: f32, sy: f32, z0: f32| -> (Vec<glam::Vec3>, f64) {
            let z = |x: f32, y: f32| z0 + sx * x + sy * y;
            let corners: Vec<glam::Vec3> =
                [(x0, -1.0), (x0 + 2.0, -1.0), (x0 + 2.0, 1.0), (x0, 1.0)]
                    .iter()
                    .map(|&(x, y)| glam::Vec3::new(x, y, z(x, y)))
                    .collect();
            let p = |c: glam::Vec3| texel(c.x.into(), c.y.into(), c.z.into());
            let (a, b, c) = (p(corners[0]), p(corners[1]), p(corners[3]));
            let gx = (b[2] - a[2]) / (b[0] - a[0]);
            let gy = (c[2] - a[2]) / (c[1] - a[1]);
            (corners, gx.abs().max(gy.abs()))
        };
        let (flat, m_flat) = face(-2.0, 0.05, 0.0, -10.0);
        let (steep, m_steep) = face(0.0, 1.5, 0.0, -10.0);
        let (level, _) = face(2.0, 0.05, 0.0, -10.0);
        let alone = [&flat, &steep].map(|f| shadow_bias_for_receivers(&map, &[f]).unwrap());
        let both = shadow_bias_for_receivers(&map, &[&flat, &steep]).unwrap();
        let larger = alone[0].terms.constant.max(alone[1].terms.constant);
        let spread = both.terms.slope_factor * (m_steep - m_flat);
        assert!(m_steep > 10.0 * m_flat, "{m_steep} {m_flat}");
        let gained = both.terms.constant - larger;
        assert!(
            (gained - spread).abs() <= 1e-9 * spread,
            "{gained} vs {spread}"
        );
        let run = 2.5 * m_steep;
        assert!(
            both.gl_polygon_offset[2] >= larger + run,
            "{:?}",
            both.gl_polygon_offset
        );
        // A steep face far from the flat one in the map (x from 5 to 7: 320 texels off, beyond
        // the 5×5 kernel's reach): its slope does not enter the constant.
        let (far_steep, _) = face(5.0, 1.5, 0.0, -20.0);
        let apart = shadow_bias_for_receivers(&map, &[&flat, &far_steep]).unwrap();
        let far_alone = shadow_bias_for_receivers(&map, &[&far_steep]).unwrap();
        let k = alone[0].terms.constant.max(far_alone.terms.constant);
        assert!(
            (apart.terms.constant - k).abs() <= 1e-12 * k,
            "{} vs {k}",
            apart.terms.constant
        );
        // One slope (to the f32 rounding of the corners): the larger of the two alone.
        let same = shadow_bias_for_receivers(&map, &[&flat, &level]).unwrap();
        let level_alone = shadow_bias_for_receivers(&map, &[&level]).unwrap();
        let k = alone[0].terms.constant.max(level_alone.terms.constant);
        assert!(
            same.terms.constant >= k && same.terms.constant <= k * 1.01,
            "{} vs {k}",
            same.terms.constant
        );
    }
}

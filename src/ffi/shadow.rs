//! Shadow-map bias (src/shadow.rs): the ZshiftShadowMap and ZshiftShadowBias records and
//! zshift_shadow_bias.

use super::probe::{profile_or_worst, ZshiftProfile};
use super::recommend::{pipeline_from_c, ZshiftPipeline};
use super::{checked, clip_of, format_named, null_pointer, ZshiftClip, ZshiftStatus};
use crate::domain::domain;
use crate::error::Result;
use crate::orthographic::Ortho;
use crate::profile::Snapping;
use crate::projection::Frustum;
use crate::shadow::{LightProjection, Lookup, ShadowBias, ShadowMap};

/// `ZshiftShadowMap.light`: a directional light or a cascade, `glOrtho(l, r, b, t, n, f)`.
pub const ZSHIFT_LIGHT_ORTHOGRAPHIC: i32 = 0;
/// `ZshiftShadowMap.light`: a spot light, `glFrustum(l, r, b, t, n, f)` (finite f).
pub const ZSHIFT_LIGHT_PERSPECTIVE: i32 = 1;

/// `ZshiftShadowMap.lookup`: one texel, the one containing the sample point.
pub const ZSHIFT_LOOKUP_NEAREST: i32 = 0;
/// `ZshiftShadowMap.lookup`: hardware depth comparison with linear filtering (2x2 texels).
pub const ZSHIFT_LOOKUP_HARDWARE_2X2: i32 = 1;
/// `ZshiftShadowMap.lookup`: `pcf_size` x `pcf_size` PCF of nearest taps one texel apart.
pub const ZSHIFT_LOOKUP_PCF: i32 = 2;
/// `ZshiftShadowMap.lookup`: taps up to `kernel_radius` texels from the point per axis.
pub const ZSHIFT_LOOKUP_RADIUS: i32 = 3;

/// What an engine knows about one shadow map, for `zshift_shadow_bias`.
///
/// The light's projection in its own view space (right-handed, looking down -z), with the
/// map's clip convention `clip` (reversed: GL_GEQUAL comparison, map cleared to 0).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftShadowMap {
    /// ZSHIFT_LIGHT_ORTHOGRAPHIC or ZSHIFT_LIGHT_PERSPECTIVE.
    pub light: i32,
    /// The projection's left extent (`glOrtho`/`glFrustum` l).
    pub l: f64,
    /// Right extent.
    pub r: f64,
    /// Bottom extent.
    pub b: f64,
    /// Top extent.
    pub t: f64,
    /// Near plane distance.
    pub n: f64,
    /// Far plane distance (finite).
    pub f: f64,
    /// The map's clip convention.
    pub clip: ZshiftClip,
    /// The map's width in texels.
    pub width: u32,
    /// The map's height in texels.
    pub height: u32,
    /// The map's depth format, a ZSHIFT_FORMAT_* value (its GL internal format enum).
    pub format: u32,
    /// ZSHIFT_LOOKUP_NEAREST, _HARDWARE_2X2, _PCF or _RADIUS.
    pub lookup: i32,
    /// The kernel size k of ZSHIFT_LOOKUP_PCF (>= 1); ignored otherwise.
    pub pcf_size: u32,
    /// The kernel radius in texels of ZSHIFT_LOOKUP_RADIUS (>= 0); ignored otherwise.
    pub kernel_radius: f64,
    /// The limit angle in degrees, [0, 90), between the light and a surface normal beyond
    /// which a surface counts as facing away (acne allowed there). For a spot light,
    /// zshift_shadow_bias measures it to the light's axis, zshift_shadow_bias_receivers to the
    /// ray from the light to each point of a receiver (the angle shading sees).
    pub limit_angle_deg: f64,
    /// The receivers' nearest light-space depth (-z in the light's view), >= n.
    pub receiver_near: f64,
    /// The receivers' farthest light-space depth, <= f.
    pub receiver_far: f64,
    /// The largest world coordinate of the light's position and of every model origin (0 for
    /// vertices already in the light's view space).
    pub world_reach: f64,
    /// The light's elevation above the ground in degrees, (0, 90], for `peter_panning` only.
    pub elevation_deg: f64,
    /// The rasterizer's profile (`zshift_probe`), or NULL for the worst case.
    pub profile: *const ZshiftProfile,
    /// The light's vertex pipeline, as the decal's ZshiftScene.pipeline: `view_matrix` (the
    /// light's float view matrix the caster and lookup shaders apply to world positions, 16
    /// floats column-major) with `world_box` (the world-space box of every caster and receiver
    /// position), and `eye_first` (nonzero when both shaders compute `proj * (view * p)`); with
    /// them the model knows each light-space eye coordinate's float rounding exactly instead of
    /// bounding it from world_reach, and with listed receivers (zshift_shadow_bias_receivers)
    /// and eye_first only the error off each receiver's plane counts. `world_reach` here adds to
    /// the map's (the larger counts). A zeroed record is the behaviour without it.
    /// `viewport_x`/`viewport_y` place the map's tile in a shadow atlas (the glViewport the
    /// casters are drawn with; width and height are the tile's), and
    /// `depth_range_near`/`depth_range_far` are the glDepthRange they are drawn with (the lookup
    /// must compare against `near + (far - near) * depth`); the units and clamp returned are in
    /// stored depth, as the APIs apply them.
    pub pipeline: ZshiftPipeline,
}

/// The recommendation of `zshift_shadow_bias`: the error terms (unit window depth of the map),
/// the caster-side bias in every API's units (signed as the API adds it: positive under
/// [-1, 1] and [0, 1], negative reversed; a clamp of 0 means none), the receiver-side
/// alternatives and the cost (world units; +INFINITY where none exists).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZshiftShadowBias {
    /// a: texels per axis from the sample point to the farthest texel centre read.
    pub reach: f64,
    /// q: the storage term, the format's quantum, or min(q, q/2 + u*w_max) where a probed
    /// profile identified the rasterizer's conversion to UNORM.
    pub quantum: f64,
    /// E: the caster's rasterization error.
    pub caster: f64,
    /// S: sub-pixel snapping at the limit angle (carried by the slope factor).
    pub snap: f64,
    /// T + V: the lookup's rounding of the receiver's light-space depth.
    pub lookup: f64,
    /// R: the read-back rounding of a UNORM texel.
    pub read: f64,
    /// K = q + E + (T + V) + R, the constant part.
    pub constant: f64,
    /// F: the texel footprint at the limit angle and nearest receiver (+INFINITY: no clamp).
    pub footprint: f64,
    /// The slope factor per unit of max(|dz/dx|, |dz/dy|) before f32 rounding: 2a + 2^-b.
    pub slope_factor: f64,
    /// glPolygonOffset factor (also glPolygonOffsetClamp's).
    pub gl_factor: f64,
    /// glPolygonOffset units (against the profile's resolvable r).
    pub gl_units: f64,
    /// glPolygonOffsetClamp clamp (0: none).
    pub gl_clamp: f64,
    /// Direct3D DepthBias.
    pub d3d_depth_bias: i32,
    /// Direct3D SlopeScaledDepthBias.
    pub d3d_slope_scaled: f32,
    /// Direct3D DepthBiasClamp.
    pub d3d_clamp: f32,
    /// Vulkan depthBiasConstantFactor.
    pub vk_constant: f32,
    /// Vulkan depthBiasSlopeFactor.
    pub vk_slope: f32,
    /// Vulkan depthBiasClamp.
    pub vk_clamp: f32,
    /// WebGPU DepthBiasState depthBias.
    pub webgpu_depth_bias: i32,
    /// WebGPU depthBiasSlopeScale.
    pub webgpu_slope_scale: f32,
    /// WebGPU depthBiasClamp.
    pub webgpu_clamp: f32,
    /// Receiver side: the world distance to move a receiver toward the light (INFINITY where
    /// none works, e.g. where it would move the nearest receiver onto or past a spot light).
    pub along_light: f64,
    /// Receiver side: the world distance to move a receiver along its normal (INFINITY where
    /// none works); it also shifts shadows sideways by up to this times the sine of the angle
    /// to the light.
    pub along_normal: f64,
    /// The most a caster within the limit angle is biased along the light: thinner casters
    /// cast no shadow.
    pub leak_thickness: f64,
    /// How far from a wall standing on the ground its shadow starts, at `elevation_deg`.
    pub peter_panning: f64,
}

impl From<ShadowBias> for ZshiftShadowBias {
    fn from(s: ShadowBias) -> Self {
        let t = s.terms;
        ZshiftShadowBias {
            reach: t.reach,
            quantum: t.quantum,
            caster: t.caster,
            snap: t.snap,
            lookup: t.lookup,
            read: t.read,
            constant: t.constant,
            footprint: t.footprint,
            slope_factor: t.slope_factor,
            gl_factor: s.gl_polygon_offset[0],
            gl_units: s.gl_polygon_offset[1],
            gl_clamp: s.gl_polygon_offset[2],
            d3d_depth_bias: s.d3d.depth_bias,
            d3d_slope_scaled: s.d3d.slope_scaled,
            d3d_clamp: s.d3d.clamp,
            vk_constant: s.vulkan[0],
            vk_slope: s.vulkan[1],
            vk_clamp: s.vulkan[2],
            webgpu_depth_bias: s.webgpu_depth_bias,
            webgpu_slope_scale: s.webgpu_slope_clamp[0],
            webgpu_clamp: s.webgpu_slope_clamp[1],
            along_light: s.along_light,
            along_normal: s.along_normal,
            leak_thickness: s.leak_thickness,
            peter_panning: s.peter_panning,
        }
    }
}

impl ZshiftShadowMap {
    fn to_map(self) -> Result<ShadowMap> {
        let light = match self.light {
            ZSHIFT_LIGHT_ORTHOGRAPHIC => LightProjection::Orthographic(Ortho::new(
                self.l, self.r, self.b, self.t, self.n, self.f,
            )?),
            ZSHIFT_LIGHT_PERSPECTIVE => LightProjection::Perspective(Frustum::new(
                self.l, self.r, self.b, self.t, self.n, self.f,
            )?),
            other => {
                return Err(domain(
                    "ZshiftShadowMap.light is not ZSHIFT_LIGHT_ORTHOGRAPHIC or ZSHIFT_LIGHT_PERSPECTIVE",
                )
                .with_integer("light", i64::from(other)))
            }
        };
        let lookup = match self.lookup {
            ZSHIFT_LOOKUP_NEAREST => Lookup::Nearest,
            ZSHIFT_LOOKUP_HARDWARE_2X2 => Lookup::Hardware2x2,
            ZSHIFT_LOOKUP_PCF => Lookup::Pcf(self.pcf_size),
            ZSHIFT_LOOKUP_RADIUS => Lookup::Radius(self.kernel_radius),
            other => {
                return Err(
                    domain("ZshiftShadowMap.lookup is not a ZSHIFT_LOOKUP_* value")
                        .with_integer("lookup", i64::from(other)),
                )
            }
        };
        Ok(ShadowMap {
            light,
            clip: clip_of(self.clip)?,
            resolution: [self.width, self.height],
            format: format_named(self.format, "format")?,
            lookup,
            limit_angle_deg: self.limit_angle_deg,
            receiver_depths: [self.receiver_near, self.receiver_far],
            world_reach: self.world_reach,
            elevation_deg: self.elevation_deg,
            profile: profile_or_worst(self.profile, Snapping::SubpixelBits(8))?,
            pipeline: pipeline_from_c(&self.pipeline)?,
        })
    }
}

/// Writes the smallest caster-side shadow bias that keeps every receiver within the limit
/// angle free of acne on the rasterizer `map->profile` describes (NULL: the worst case), in
/// every API's units, with its receiver-side alternatives and its cost (docs/shadows.md).
/// Receivers must be planar across the lookup's reach: for a mesh whose faces bend within a
/// few texels (a sphere, a terrain) under a wide kernel, list its faces with
/// zshift_shadow_bias_receivers.
///
/// Errors: ZSHIFT_ERR_NULL_POINTER (map or out NULL), ZSHIFT_ERR_NOT_FINITE, ZSHIFT_ERR_DOMAIN
/// (bad projection, receivers outside [n, f], an angle outside [0, 90), an unknown enum, a
/// profile that fails its checks: zshift_last_error() names the field),
/// ZSHIFT_ERR_UNRESOLVABLE (the rounding terms alone would span the map's whole depth range;
/// the detail names the remedy: tighter near/far, a deeper format; where only the clamp would
/// span it, none is set: gl_clamp 0, as for a spot whose rays graze), ZSHIFT_ERR_OVERFLOW (an
/// integer bias does not fit). `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_shadow_bias(
    map: *const ZshiftShadowMap,
    out: *mut ZshiftShadowBias,
) -> ZshiftStatus {
    let Some(record) = map_from_c(map) else {
        return null_pointer("map");
    };
    checked(
        out,
        move || {
            Ok(ZshiftShadowBias::from(crate::shadow::shadow_bias(
                &record.to_map()?,
            )?))
        },
        // SAFETY: `checked` has refused NULL; the caller promises a writable ZshiftShadowBias.
        |out, value| unsafe { out.write_unaligned(value) },
    )
}

/// The caller's map, copied (`read_unaligned`: no alignment needed), or `None` for NULL.
fn map_from_c(map: *const ZshiftShadowMap) -> Option<ZshiftShadowMap> {
    if map.is_null() {
        return None;
    }
    // SAFETY: not NULL; the caller promises a readable ZshiftShadowMap; the struct is plain data.
    Some(unsafe { map.read_unaligned() })
}

/// The most receivers one call takes, and the most corners one receiver may have.
const MAX_RECEIVERS: usize = 1 << 16;
const MAX_RECEIVER_CORNERS: u32 = 64;

/// zshift_shadow_bias for the receivers the engine lists (docs/shadows.md, "Receivers of
/// known geometry"): `receiver_count` planar polygons in the light's view space (right-handed,
/// looking down -z; a spot light at the origin), their corners one receiver after another in
/// `corners` (3 floats each: x0, y0, z0, x1, ...), `corner_counts[i]` (3 to 64) corners for
/// receiver i, counter-clockwise seen from its lit front, every corner inside the light's
/// frustum. The bias, its clamp and its receiver-side offsets follow from each receiver's
/// own window-depth plane in the map, at any angle short of edge-on, also where a kernel reads
/// across from one receiver to another (the faces of one mesh may be listed: the constant then
/// covers the spread of their slopes); receivers facing away
/// from the light by more than `map->limit_angle_deg` everywhere are skipped (under a spot
/// light, the angle to the ray from the light to each point);
/// `map->receiver_near` and `receiver_far` are not used (but must lie in [n, f]).
///
/// Errors: as zshift_shadow_bias; ZSHIFT_ERR_NULL_POINTER (corners or corner_counts NULL with
/// a nonzero count); ZSHIFT_ERR_DOMAIN (no receiver, more than 65536, a corner count outside
/// 3..=64, a receiver that is not a planar polygon inside the frustum: zshift_last_error()
/// names it; every receiver skipped). `*out` untouched on error.
#[no_mangle]
pub extern "C" fn zshift_shadow_bias_receivers(
    map: *const ZshiftShadowMap,
    corners: *const f32,
    corner_counts: *const u32,
    receiver_count: u32,
    out: *mut ZshiftShadowBias,
) -> ZshiftStatus {
    let Some(record) = map_from_c(map) else {
        return null_pointer("map");
    };
    if receiver_count > 0 && corners.is_null() {
        return null_pointer("corners");
    }
    if receiver_count > 0 && corner_counts.is_null() {
        return null_pointer("corner_counts");
    }
    let (corners, counts) = (corners as usize, corner_counts as usize);
    checked(
        out,
        move || {
            if receiver_count == 0 || receiver_count as usize > MAX_RECEIVERS {
                return Err(domain("receiver_count must lie in 1..=65536")
                    .with_integer("receiver_count", i64::from(receiver_count)));
            }
            // SAFETY: not NULL; the caller promises `receiver_count` readable u32 (read
            // unaligned, copied).
            let counts: Vec<u32> = (0..receiver_count as usize)
                .map(|i| unsafe { (counts as *const u32).add(i).read_unaligned() })
                .collect();
            let mut polygons: Vec<Vec<glam::Vec3>> = Vec::with_capacity(receiver_count as usize);
            let mut at = 0usize;
            for (i, &c) in counts.iter().enumerate() {
                if !(3..=MAX_RECEIVER_CORNERS).contains(&c) {
                    return Err(domain("each corner_counts[i] must lie in 3..=64")
                        .with_integer("receiver", i as i64));
                }
                let polygon = (0..c as usize)
                    .map(|k| {
                        let base = 3 * (at + k);
                        // SAFETY: the caller promises 3 readable floats per corner counted.
                        let f = |j: usize| unsafe {
                            (corners as *const f32).add(base + j).read_unaligned()
                        };
                        glam::Vec3::new(f(0), f(1), f(2))
                    })
                    .collect();
                polygons.push(polygon);
                at += c as usize;
            }
            let slices: Vec<&[glam::Vec3]> = polygons.iter().map(Vec::as_slice).collect();
            Ok(ZshiftShadowBias::from(
                crate::shadow::shadow_bias_for_receivers(&record.to_map()?, &slices)?,
            ))
        },
        // SAFETY: `checked` has refused NULL; the caller promises a writable ZshiftShadowBias.
        |out, value| unsafe { out.write_unaligned(value) },
    )
}

//! The bias for receivers an engine lists ("Receivers of known geometry" in the module docs):
//! each receiver's own window-depth plane in the map and its terms, skipping those that face
//! away beyond the limit angle, the receiver-side offsets per receiver, and the spread of the
//! receivers' slopes a kernel can read across (the faces of a mesh), which the constant and the
//! clamp must cover.

use super::*;

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
    let (shortfall, run) = slopes.reads_across(terms.reach);
    needed = needed.max(terms.constant + slopes.snap + terms.reach * run);
    terms.constant += shortfall;
    let map = ShadowMap {
        receiver_depths: depths,
        ..*map
    };
    finish(&map, terms, needed, Some((along_light, along_normal)))
}

/// A receiver's footprint term is widened by the coplanarity tolerance its corners are accepted
/// with (2⁻¹⁶ of their size).
pub(super) const COPLANARITY_WIDENING: f64 = 1.0 + 1.0 / 65_536.0;

/// The slopes of the listed receivers, for a kernel that reads across from one to another.
#[derive(Default)]
struct SlopeSpread {
    /// Each receiver's `|gₓ|`, `|g_y|` and its extent in the map, `[x₀, x₁, y₀, y₁]` (texels).
    faces: Vec<([f64; 2], [f64; 4])>,
    /// The largest snapping term.
    snap: f64,
}

impl SlopeSpread {
    fn add(&mut self, gradient: [f64; 2], snap: f64, extent: [f64; 4]) {
        let g = gradient.map(f64::abs);
        self.faces.push((g, extent));
        self.snap = self.snap.max(snap);
    }

    /// Per receiver, its `|gₓ|, |g_y|` and the largest `|gₓ|` and `|g_y|` of the receivers a
    /// kernel of `reach` texels can read across from it, itself included: those whose extents
    /// come within `reach + 1` texels of its own (a tap lands at most `reach` texels from the
    /// lookup point and takes the texel whose centre its face covers, half a texel further).
    /// Separate meshes listed together then do not pay for each other's slopes. A sweep over
    /// the extents sorted by `x₀`.
    fn near_maxima(&self, reach: f64) -> Vec<([f64; 2], [f64; 2])> {
        let near = reach + 1.0;
        let mut order: Vec<&([f64; 2], [f64; 4])> = self.faces.iter().collect();
        order.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]));
        let mut out: Vec<([f64; 2], [f64; 2])> = order.iter().map(|(g, _)| (*g, *g)).collect();
        for i in 0..order.len() {
            let (g_i, e_i) = order[i];
            for j in i + 1..order.len() {
                let (g_j, e_j) = order[j];
                if e_j[0] > e_i[1] + near {
                    break;
                }
                if e_j[2] <= e_i[3] + near && e_i[2] <= e_j[3] + near {
                    out[i].1 = [0, 1].map(|k| out[i].1[k].max(g_j[k]));
                    out[j].1 = [0, 1].map(|k| out[j].1[k].max(g_i[k]));
                }
            }
        }
        out
    }

    /// The kernel's reads across receivers (module docs, "Meshes"), for a kernel of `reach`
    /// texels: `(shortfall, run)`. A tap on receiver `j` reads `j`'s caster while the lookup
    /// point lies at most `reach` texels away along a path that crosses receivers near `j`,
    /// where the depth runs up to `reach·(Gₓ + G_y)` (`G` the largest `|g|` near `j`, widened as
    /// each receiver's own footprint term is). `j`'s slope term `factor·m_j` holds
    /// `2·reach·m_j` of that beside its own snapping, so the constant adds the shortfall
    /// `reach·(Gₓ + G_y) − 2·reach·m_j` at its largest over `j`; and a clamp that binds at `j`
    /// must reach the whole run, `Gₓ + G_y` at its largest over `j` (per texel of reach).
    /// Before, the constant charged `factor·(m_i − m_j)` for every pair within reach and the
    /// clamp the largest `|gₓ|` and `|g_y|` over every receiver, near or not.
    fn reads_across(&self, reach: f64) -> (f64, f64) {
        self.near_maxima(reach)
            .iter()
            .fold((0.0f64, 0.0f64), |(short, run), (g, near_g)| {
                let across = (near_g[0] + near_g[1]) * COPLANARITY_WIDENING;
                (
                    short.max(reach * (across - 2.0 * g[0].max(g[1]))),
                    run.max(across),
                )
            })
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

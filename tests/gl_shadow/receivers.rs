//! Receivers other than flat ground: a UV sphere resting on the ground, a terrain with hills,
//! and a box standing on the ground turned 25° to it (its faces meet at right angles, the
//! widest spread of slopes a kernel can read across), each casting on itself. The map holds every mesh, the camera looks at every mesh
//! (its own depth test picks the nearest), and the reference is a ray test in f64 against the
//! very f32 triangles drawn.
//!
//! A camera pixel is **judged** when the five rays through its centre and ±0.6 pixel hit the
//! same object at nearly the same distance (no silhouette), the face hit is lit (nothing on the
//! segment to the light), it faces the light (`n·l > 0`) within the limit angle (what zshift
//! promises: to a spot light's axis for `shadow_bias`, to the ray from the light for
//! `shadow_bias_for_receivers`), and every light ray through a 5 × 5 grid of map positions within
//! `a + 1.5` texels of it first hits a lit face of the same object within the limit angle (no
//! shadow edge, no surface the promise leaves out, feeds the lookup). **Acne**: a judged pixel
//! the map darkens. Asserted: 0 acne at zshift's bias, from the limit angle alone
//! (`shadow_bias`) and with every face listed (`shadow_bias_for_receivers`), with the worst-case
//! and the probed profile; a refusal must be a scene where no constant lookup bias below 1 is
//! acne-free. `ZSHIFT_SHADOW_SCENES=full` draws every combination; `ZSHIFT_SHADOW_ONLY=<a>&<b>`
//! only the asks whose label contains every part; `ZSHIFT_SHADOW_SHARD=<i>/<n>` every `n`-th
//! case from the `i`-th, so that `n` processes share the full grid (`scripts/gpu-checks`).

use super::*;

/// One drawn triangle: its f32 corners (as f64), its face normal (outward, f64) and object.
#[derive(Clone, Copy)]
struct Tri {
    v: [[f64; 3]; 3],
    n: [f64; 3],
    object: u8,
}

/// A run of triangles with the sphere that bounds them (rays that miss it skip them).
struct Cluster {
    range: std::ops::Range<usize>,
    centre: [f64; 3],
    radius: f64,
}

/// A receiver scene: its triangles in clusters, and the vertex buffer the GPU draws.
struct World {
    name: &'static str,
    tris: Vec<Tri>,
    clusters: Vec<Cluster>,
}

impl World {
    /// Triangles from f32 corners, each turned so that its normal points along `outward` of
    /// its centroid; `groups` of consecutive triangles become clusters.
    fn new(
        name: &'static str,
        groups: Vec<(u8, Vec<[[f32; 3]; 3]>)>,
        outward: impl Fn(u8, [f64; 3]) -> [f64; 3],
    ) -> World {
        let mut tris = Vec::new();
        let mut clusters = Vec::new();
        for (object, group) in groups {
            let start = tris.len();
            for t in group {
                let mut v = t.map(|p| p.map(f64::from));
                let centroid = [0, 1, 2].map(|k| (v[0][k] + v[1][k] + v[2][k]) / 3.0);
                let mut n = norm(cross(sub(v[1], v[0]), sub(v[2], v[0])));
                if dot(n, outward(object, centroid)) < 0.0 {
                    v.swap(1, 2);
                    n = n.map(|c| -c);
                }
                tris.push(Tri { v, n, object });
            }
            let range = start..tris.len();
            let points: Vec<[f64; 3]> = tris[range.clone()].iter().flat_map(|t| t.v).collect();
            let centre =
                [0, 1, 2].map(|k| points.iter().map(|p| p[k]).sum::<f64>() / points.len() as f64);
            let radius = points
                .iter()
                .map(|p| dot(sub(*p, centre), sub(*p, centre)).sqrt())
                .fold(0.0, f64::max)
                * (1.0 + 1e-9)
                + 1e-9;
            clusters.push(Cluster {
                range,
                centre,
                radius,
            });
        }
        World {
            name,
            tris,
            clusters,
        }
    }

    /// The vertices as the shaders take them (flat normals).
    fn vertices(&self) -> Vec<[f32; 6]> {
        self.tris
            .iter()
            .flat_map(|t| {
                t.v.map(|p| {
                    [
                        p[0] as f32,
                        p[1] as f32,
                        p[2] as f32,
                        t.n[0] as f32,
                        t.n[1] as f32,
                        t.n[2] as f32,
                    ]
                })
            })
            .collect()
    }

    fn points(&self) -> Vec<[f64; 3]> {
        self.tris.iter().flat_map(|t| t.v).collect()
    }

    /// The first triangle the ray `o + t·d` hits for `t` in `(t_min, t_max)`, other than `skip`.
    fn first_hit(
        &self,
        o: [f64; 3],
        d: [f64; 3],
        t_min: f64,
        t_max: f64,
        skip: Option<usize>,
    ) -> Option<(f64, usize)> {
        let mut best: Option<(f64, usize)> = None;
        let dd = dot(d, d);
        for c in &self.clusters {
            let w = sub(c.centre, o);
            let tc = dot(w, d) / dd;
            let off = sub(w, d.map(|x| x * tc));
            if dot(off, off) > c.radius * c.radius {
                continue;
            }
            for i in c.range.clone() {
                if Some(i) == skip {
                    continue;
                }
                if let Some(t) = ray_triangle(o, d, &self.tris[i].v) {
                    if t > t_min && t < t_max && best.is_none_or(|(b, _)| t < b) {
                        best = Some((t, i));
                    }
                }
            }
        }
        best
    }
}

/// Möller–Trumbore in f64, edges included (a hair's tolerance so a shared edge is hit).
fn ray_triangle(o: [f64; 3], d: [f64; 3], v: &[[f64; 3]; 3]) -> Option<f64> {
    let (e1, e2) = (sub(v[1], v[0]), sub(v[2], v[0]));
    let p = cross(d, e2);
    let det = dot(e1, p);
    if det.abs() < 1e-300 {
        return None;
    }
    let inv = 1.0 / det;
    let s = sub(o, v[0]);
    let u = dot(s, p) * inv;
    const TOL: f64 = 1e-12;
    if !(-TOL..=1.0 + TOL).contains(&u) {
        return None;
    }
    let q = cross(s, e1);
    let w = dot(d, q) * inv;
    if w < -TOL || u + w > 1.0 + TOL {
        return None;
    }
    Some(dot(e2, q) * inv)
}

fn f32p(p: [f64; 3]) -> [f32; 3] {
    p.map(|c| c as f32)
}

/// The ground (object 0) and a UV sphere resting on it (object 1, 32 × 16).
fn sphere_world() -> World {
    let g = GROUND;
    let ground = vec![
        [[-g, 0.0, -g], [-g, 0.0, g], [g, 0.0, g]].map(f32p),
        [[-g, 0.0, -g], [g, 0.0, g], [g, 0.0, -g]].map(f32p),
    ];
    let (c, r) = ([-1.8, 1.2, 1.6], 1.2);
    let (nu, nv) = (32usize, 16usize);
    let at = |i: usize, j: usize| {
        let (theta, phi) = (
            std::f64::consts::PI * j as f64 / nv as f64,
            2.0 * std::f64::consts::PI * (i % nu) as f64 / nu as f64 + 0.2,
        );
        f32p([
            c[0] + r * theta.sin() * phi.cos(),
            c[1] + r * theta.cos(),
            c[2] + r * theta.sin() * phi.sin(),
        ])
    };
    let mut groups = vec![(0u8, ground)];
    for j in 0..nv {
        let mut ring = Vec::new();
        for i in 0..nu {
            let (a, b, cc, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if j > 0 {
                ring.push([a, b, cc]);
            }
            if j + 1 < nv {
                ring.push([a, cc, d]);
            }
        }
        groups.push((1, ring));
    }
    World::new("sphere on ground", groups, move |object, p| {
        if object == 0 {
            [0.0, 1.0, 0.0]
        } else {
            sub(p, c)
        }
    })
}

/// A 4 × 3 × 3 box (object 1: top and four sides) standing on the ground (object 0), turned
/// 25° about the vertical, so that no face is aligned with the map's axes.
fn box_world() -> World {
    let g = GROUND;
    let ground = vec![
        [[-g, 0.0, -g], [-g, 0.0, g], [g, 0.0, g]].map(f32p),
        [[-g, 0.0, -g], [g, 0.0, g], [g, 0.0, -g]].map(f32p),
    ];
    let (centre, half) = ([-1.5, 1.5, 1.5], [2.0, 1.5, 1.5]);
    let (s, c) = 25f64.to_radians().sin_cos();
    // Corner `k` (bits: x, y, z sign) in world space.
    let at = |k: usize| {
        let local = [0, 1, 2].map(|a| if k >> a & 1 == 1 { half[a] } else { -half[a] });
        f32p([
            centre[0] + c * local[0] - s * local[2],
            centre[1] + local[1],
            centre[2] + s * local[0] + c * local[2],
        ])
    };
    // Each face as two triangles of its four corners (the bottom, on the ground, left out).
    let faces = [
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 5, 7, 6],
        [0, 2, 6, 4],
        [1, 3, 7, 5],
    ];
    let sides = faces
        .iter()
        .flat_map(|f| {
            [
                [at(f[0]), at(f[1]), at(f[2])],
                [at(f[0]), at(f[2]), at(f[3])],
            ]
        })
        .collect();
    World::new(
        "box on ground",
        vec![(0, ground), (1, sides)],
        move |object, p| {
            if object == 0 {
                [0.0, 1.0, 0.0]
            } else {
                sub(p, centre)
            }
        },
    )
}

/// A terrain with hills over the ground's square (40 × 40 cells, object 0), in 5 × 5-cell
/// clusters.
fn terrain_world() -> World {
    let cells = 40usize;
    let step = 2.0 * GROUND / cells as f64;
    let height = |x: f64, z: f64| {
        0.5 * (0.8 * x + 0.3).sin() * (0.6 * z).cos() + 0.25 * (1.3 * z - 0.5 * x).sin()
    };
    let at = |i: usize, j: usize| {
        let (x, z) = (-GROUND + step * i as f64, -GROUND + step * j as f64);
        f32p([x, height(x, z), z])
    };
    let mut groups = Vec::new();
    for bi in (0..cells).step_by(5) {
        for bj in (0..cells).step_by(5) {
            let mut block = Vec::new();
            for i in bi..bi + 5 {
                for j in bj..bj + 5 {
                    let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                    block.push([a, b, c]);
                    block.push([a, c, d]);
                }
            }
            groups.push((0u8, block));
        }
    }
    World::new("terrain", groups, |_, _| [0.0, 1.0, 0.0])
}

/// The limit angle asked for at `elevation`: the flat ground's own angle to the light plus 35°
/// (the sphere's upper half, the terrain's slopes), at most 80°.
fn limit_for(elevation: f64) -> f64 {
    (125.0 - elevation).min(80.0)
}

/// The exact answer per camera pixel: `Some(true)` for a judged pixel (module docs), else None.
#[allow(clippy::too_many_arguments)]
fn judged(
    case: &Case,
    light: &Light,
    camera: &M4,
    eye: [f64; 3],
    reach: f64,
    world: &World,
    limit_deg: f64,
    planar: bool,
) -> Vec<Option<bool>> {
    let inverse = invert(camera);
    let light_vp = mul(&light.proj, &light.view);
    let light_inv = invert(&light_vp);
    let n = f64::from(case.resolution);
    let cos_limit = limit_deg.to_radians().cos();
    // A face the promise covers, lit from `p` on it. The limit angle is measured to the light's
    // axis by `shadow_bias` (it knows no positions), to the ray from the light to `p` by
    // `shadow_bias_for_receivers` (`ShadowMap::limit_angle_deg`): they differ under a spot.
    let promised = |i: usize, p: [f64; 3]| -> bool {
        let t = &world.tris[i];
        let (l, t_max) = toward_light(case, light, p);
        let direction = if planar { light.to_light } else { norm(l) };
        dot(t.n, direction) >= cos_limit
            && dot(t.n, l) > 0.0
            && world.first_hit(p, l, 1e-7, t_max, Some(i)).is_none()
    };
    let to_map = |p: [f64; 3]| map_position(&light_vp, n, p);
    // The first face the light sees through map position `uv` (texels).
    let light_ray = |uv: [f64; 2]| -> Option<(usize, [f64; 3])> {
        let (a, d) = map_ray(&light_inv, n, uv);
        let (t, i) = world.first_hit(a, d, 0.0, f64::INFINITY, None)?;
        Some((i, [0, 1, 2].map(|k| a[k] + t * d[k])))
    };
    // The first face a camera ray hits: its distance parameter, index and point.
    let camera_ray = |x: f64, y: f64| -> Option<(f64, usize, [f64; 3])> {
        let far = apply(&inverse, [x, y, 1.0]);
        let d = sub([far[0] / far[3], far[1] / far[3], far[2] / far[3]], eye);
        let (t, i) = world.first_hit(eye, d, 0.0, f64::INFINITY, None)?;
        Some((t, i, [0, 1, 2].map(|k| eye[k] + t * d[k])))
    };
    // Map depth (NDC z of the light) and each face's gradient of it per texel, for the
    // continuity check below.
    let depth = |q: [f64; 3]| {
        let c = apply(&light_vp, q);
        c[2] / c[3]
    };
    let gradients: Vec<[f64; 2]> = world
        .tris
        .iter()
        .map(|t| {
            let corners = t.v.map(|v| {
                let uv = to_map(v);
                [uv[0], uv[1], depth(v)]
            });
            let normal = cross(sub(corners[1], corners[0]), sub(corners[2], corners[0]));
            [-normal[0] / normal[2], -normal[1] / normal[2]]
        })
        .collect();
    let edge = reach + 1.5;
    let pixel = 2.0 / CAMERA as f64;
    let mut out = Vec::with_capacity(CAMERA * CAMERA);
    for py in 0..CAMERA {
        for px in 0..CAMERA {
            let x = (px as f64 + 0.5) * pixel - 1.0;
            let y = (py as f64 + 0.5) * pixel - 1.0;
            out.push((|| {
                let (t, i, p) = camera_ray(x, y)?;
                let object = world.tris[i].object;
                for (dx, dy) in [(-0.6, -0.6), (0.6, -0.6), (-0.6, 0.6), (0.6, 0.6)] {
                    let (ti, j, _) = camera_ray(x + dx * pixel, y + dy * pixel)?;
                    if world.tris[j].object != object || (ti - t).abs() > 0.05 * t {
                        return None;
                    }
                }
                if !promised(i, p) {
                    return None;
                }
                let uv = to_map(p);
                if uv.iter().any(|&c| c < edge + 1.0 || c > n - edge - 1.0) {
                    return None;
                }
                let mut hits = Vec::with_capacity(25);
                for a in -2..=2 {
                    for b in -2..=2 {
                        let at = [uv[0] + edge * a as f64 / 2.0, uv[1] + edge * b as f64 / 2.0];
                        let (j, q) = light_ray(at)?;
                        if world.tris[j].object != object || !promised(j, q) {
                            return None;
                        }
                        if planar && !coplanar(&world.tris[i], &world.tris[j]) {
                            return None;
                        }
                        hits.push((j, q, at));
                    }
                }
                // The surface the lookup reads must be the one through the pixel's point, not
                // a crest of the same object in front of it (its self-shadow edge: a seeded
                // draw judged a lit terrain pixel whose kernel read a hill 9 texels' worth of
                // its slope nearer the light). Within the neighbourhood the map depth may
                // change by at most the steepest sampled face's gradient over the distance
                // (twice, for faces between the samples).
                let g = hits
                    .iter()
                    .map(|h| h.0)
                    .chain([i])
                    .fold([0.0f64; 2], |g, j| {
                        [
                            g[0].max(gradients[j][0].abs()),
                            g[1].max(gradients[j][1].abs()),
                        ]
                    });
                let zp = depth(p);
                let continuous = hits.iter().all(|&(_, q, at)| {
                    let run = g[0] * (at[0] - uv[0]).abs() + g[1] * (at[1] - uv[1]).abs();
                    (depth(q) - zp).abs() <= 2.0 * run + 1e-12 * zp.abs()
                });
                continuous.then_some(true)
            })());
        }
    }
    out
}

/// Whether two triangles lie in one plane (to f32 rounding of their corners).
fn coplanar(a: &Tri, b: &Tri) -> bool {
    let scale = a.v.iter().flatten().fold(1.0f64, |m, c| m.max(c.abs()));
    dot(a.n, b.n) > 1.0 - 1e-9
        && b.v
            .iter()
            .all(|&p| dot(a.n, sub(p, a.v[0])).abs() < 1e-6 * scale)
}

/// The smallest multiple `s` of zshift's bias (factor, units and clamp scaled together) that is
/// acne-free, by geometric bisection over `[2⁻¹⁰, 1]` (`acne_at(s)` counts acne pixels):
/// `Some(0)` when no bias is needed, `None` when even 2⁻¹⁰ of it is acne-free.
fn smallest_scale(gl: &mut Gl, mut acne_at: impl FnMut(&mut Gl, f32) -> usize) -> Option<f64> {
    if acne_at(gl, 0.0) == 0 {
        return Some(0.0);
    }
    let (mut lo, mut hi) = (1.0f64 / 1024.0, 1.0f64);
    if acne_at(gl, lo as f32) == 0 {
        return None;
    }
    for _ in 0..10 {
        let mid = (lo * hi).sqrt();
        if acne_at(gl, mid as f32) > 0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(hi)
}

/// One engine default's tally on one mesh: its asks, those with acne, the worst acne fraction
/// of judged pixels.
struct EngineTally {
    scene: &'static str,
    engine: &'static str,
    asks: usize,
    acne: usize,
    worst: f64,
}

/// zshift's bias (receivers path, probed) over its smallest acne-free multiple on one mesh; asks
/// needing no bias; asks whose every multiple down to 2⁻¹⁰ is acne-free.
struct ScaleTally {
    scene: &'static str,
    ratios: Vec<f64>,
    none: usize,
    tiny: usize,
}

/// The peers' tally on the mesh receivers. Printed, not asserted (docs/shadows.md).
#[derive(Default)]
struct Peers {
    engines: Vec<EngineTally>,
    scales: Vec<ScaleTally>,
}

impl Peers {
    fn engine(&mut self, scene: &'static str, engine: &'static str, got: Count) {
        let i = match self
            .engines
            .iter()
            .position(|t| t.scene == scene && t.engine == engine)
        {
            Some(i) => i,
            None => {
                self.engines.push(EngineTally {
                    scene,
                    engine,
                    asks: 0,
                    acne: 0,
                    worst: 0.0,
                });
                self.engines.len() - 1
            }
        };
        let t = &mut self.engines[i];
        t.asks += 1;
        if got.acne > 0 {
            t.acne += 1;
            t.worst = t.worst.max(got.acne as f64 / got.lit.max(1) as f64);
        }
    }

    fn scale(&mut self, scene: &'static str, smallest: Option<f64>) {
        let i = match self.scales.iter().position(|t| t.scene == scene) {
            Some(i) => i,
            None => {
                self.scales.push(ScaleTally {
                    scene,
                    ratios: Vec::new(),
                    none: 0,
                    tiny: 0,
                });
                self.scales.len() - 1
            }
        };
        let t = &mut self.scales[i];
        match smallest {
            Some(s) if s > 0.0 => t.ratios.push(1.0 / s),
            Some(_) => t.none += 1,
            None => t.tiny += 1,
        }
    }

    fn print(&self) {
        println!("| mesh | engine default | asks with acne | worst acne (% of judged) |");
        println!("|---|---|---|---|");
        for t in &self.engines {
            println!(
                "| {} | {} | {} of {} | {:.2} % |",
                t.scene,
                t.engine,
                t.acne,
                t.asks,
                100.0 * t.worst
            );
        }
        println!("| mesh | zshift (probed, receivers) ÷ its smallest acne-free multiple: median, max | asks needing no bias | asks acne-free at 2^-10 of it |");
        println!("|---|---|---|---|");
        for t in &self.scales {
            let mut r = t.ratios.clone();
            r.sort_by(f64::total_cmp);
            let median = r.get(r.len() / 2).copied().unwrap_or(f64::NAN);
            let max = r.last().copied().unwrap_or(f64::NAN);
            println!(
                "| {} | {median:.2}, {max:.2} | {} | {} |",
                t.scene, t.none, t.tiny
            );
        }
    }
}

/// The sweep's cases for the receiver scenes: both lights at 20°–89°, two lookups per light and
/// elevation in turn (every lookup under `full`), each with one pick of f/n, map size, format and
/// convention (21 picks under `full`); another draw under `ZSHIFT_SHADOW_SEED`.
fn receiver_cases(full: bool) -> Vec<Case> {
    let mut v = Vec::new();
    let mut i = 0usize;
    for (k, kind) in [Kind::Directional, Kind::Spot].into_iter().enumerate() {
        for (e, elevation) in [20.0, 45.0, 70.0, 89.0].into_iter().enumerate() {
            for (l, pcf) in [1, 0, 3, 5].into_iter().enumerate() {
                // The default run: two lookups per light and elevation, in turn.
                let combos: Vec<usize> = if full {
                    (0..81).step_by(4).collect()
                } else if (k + e + l) % 2 == 0 {
                    vec![(i * 31 + 7) % 81]
                } else {
                    Vec::new()
                };
                v.extend(combos.into_iter().map(|c| case_of(kind, elevation, pcf, c)));
                i += 1;
            }
        }
    }
    drawn(v)
}

/// One case's map of every mesh, looked up from the camera.
struct Through<'a> {
    rig: &'a Rig,
    case: &'a Case,
    light: &'a Light,
    camera: &'a M4,
    meshes: &'a [(glow::Buffer, i32)],
}

impl Through<'_> {
    /// Renders the map with `caster`, looks every mesh up through it with `receiver`, and
    /// deletes the map: per pixel (passing taps, taps).
    fn look(&self, gl: &mut Gl, caster: CasterBias, receiver: ReceiverBias) -> Vec<[u8; 2]> {
        let (case, light) = (self.case, self.light);
        // SAFETY: the harness's context is current on this thread.
        unsafe {
            let m = self
                .rig
                .map_of(gl, case, light, caster, self.meshes)
                .unwrap_or_else(|e| panic!("{e}"));
            let px = self
                .rig
                .look_at(gl, case, light, self.camera, m.0, receiver, self.meshes)
                .unwrap_or_else(|e| panic!("{e}"));
            gl.glow().delete_framebuffer(m.1);
            gl.glow().delete_texture(m.0);
            px
        }
    }
}

#[test]
fn spheres_and_terrain_receive_without_acne() {
    let mut gl = Gl::new(Profile::Core)
        .unwrap_or_else(|e| panic!("no GL context for the shadow sweep: {e}"));
    let probed = gl_common::probed(&gl);
    let rig = unsafe { Rig::new(&gl) }.unwrap_or_else(|e| panic!("{e}"));
    let full = std::env::var("ZSHIFT_SHADOW_SCENES").is_ok_and(|v| v == "full");
    // `ZSHIFT_SHADOW_ONLY=<a>&<b>…`: only the asks whose label contains every part.
    let only = std::env::var("ZSHIFT_SHADOW_ONLY").unwrap_or_default();
    // `ZSHIFT_SHADOW_SHARD=<i>/<n>`: every n-th case from the i-th (the full grid in n processes).
    let (shard, shards) = gl_common::shard("ZSHIFT_SHADOW_SHARD");
    let (eye, camera) = camera();
    let mut failures = Vec::new();
    let (mut asked, mut answered, mut refused, mut judged_pixels) = (0, 0, 0, 0usize);
    let mut receiver_side = 0;
    let mut peers = Peers::default();
    let started = std::time::Instant::now();
    for world in [sphere_world(), terrain_world(), box_world()] {
        let buffer =
            unsafe { upload(gl.glow(), &world.vertices()) }.unwrap_or_else(|e| panic!("{e}"));
        let meshes = [(buffer, 3 * world.tris.len() as i32)];
        let points = world.points();
        let cases = receiver_cases(full).into_iter().enumerate();
        for (_, case) in cases.filter(|(index, _)| index % shards == shard) {
            let label = format!("{} {}", world.name, case.label());
            if !only.split('&').all(|part| label.contains(part)) {
                continue;
            }
            let light = light_for(&case, &points, &points);
            let reach = case.kernel_reach();
            let limit = limit_for(case.elevation);
            // `shadow_bias` promises planar receivers (planar across the kernel: every tap on
            // the receiver's own plane); `shadow_bias_for_receivers` every listed face.
            let truths = [false, true]
                .map(|planar| judged(&case, &light, &camera, eye, reach, &world, limit, planar));
            judged_pixels += truths.iter().flatten().flatten().count();
            let faces: Vec<Vec<glam::Vec3>> = world
                .tris
                .iter()
                .map(|t| {
                    t.v.iter()
                        .map(|&p| {
                            let e = apply(&light.view, p);
                            glam::Vec3::new(e[0] as f32, e[1] as f32, e[2] as f32)
                        })
                        .collect()
                })
                .collect();
            let face_refs: Vec<&[glam::Vec3]> = faces.iter().map(|f| f.as_slice()).collect();
            let where_ = format!("{} {} limit {limit}°", world.name, case.label());
            let through = Through {
                rig: &rig,
                case: &case,
                light: &light,
                camera: &camera,
                meshes: &meshes,
            };
            for (pname, profile, listed) in [
                ("worst", RasterizerProfile::worst_case(), false),
                ("probed", probed, false),
                ("worst, receivers", RasterizerProfile::worst_case(), true),
                ("probed, receivers", probed, true),
            ] {
                let map = case.shadow_map(&light, limit, profile, Default::default());
                asked += 1;
                let answer = if listed {
                    shadow_bias_for_receivers(&map, &face_refs)
                } else {
                    shadow_bias(&map)
                };
                match answer {
                    Ok(bias) => {
                        answered += 1;
                        let truth = &truths[usize::from(!listed)];
                        let caster = CasterBias::of(&bias);
                        let px = through.look(&mut gl, caster, ReceiverBias::default());
                        let got = count(&px, truth);
                        if got.acne > 0 {
                            failures.push(format!(
                                "{where_} ({pname}): {} acne pixels of {} judged at {:?}",
                                got.acne, got.lit, bias.gl_polygon_offset
                            ));
                        }
                        // The receiver-side alternative along the light, applied in the lookup
                        // instead (the map drawn without bias), on the same judged pixels.
                        if listed && bias.along_light.is_finite() {
                            let receiver = ReceiverBias {
                                along_light: bias.along_light as f32,
                                ..Default::default()
                            };
                            let got = count(
                                &through.look(&mut gl, CasterBias::default(), receiver),
                                truth,
                            );
                            receiver_side += 1;
                            if got.acne > 0 {
                                failures.push(format!(
                                    "{where_} ({pname}): {} acne pixels of {} judged along the light {}",
                                    got.acne, got.lit, bias.along_light
                                ));
                            }
                        }
                        if pname == "probed, receivers" {
                            let [f, u, c] = bias.gl_polygon_offset;
                            let acne_at = |gl: &mut Gl, s: f32| {
                                let offset = Some((f as f32 * s, u as f32 * s, c as f32 * s));
                                let caster = CasterBias {
                                    offset,
                                    ..Default::default()
                                };
                                count(&through.look(gl, caster, ReceiverBias::default()), truth)
                                    .acne
                            };
                            peers.scale(world.name, smallest_scale(&mut gl, acne_at));
                        }
                    }
                    Err(e) if e.kind() == ErrorKind::Unresolvable => {
                        refused += 1;
                        let nearly_all = ReceiverBias {
                            beta: 0.999,
                            ..Default::default()
                        };
                        let px = through.look(&mut gl, CasterBias::default(), nearly_all);
                        if count(&px, &truths[usize::from(!listed)]).acne == 0 {
                            failures.push(format!(
                                "{where_} ({pname}): refused ({e}) but a lookup bias below 1 is acne-free"
                            ));
                        }
                    }
                    // Every face beyond the limit angle: nothing to promise.
                    Err(e) if listed && e.kind() == ErrorKind::Domain => {}
                    Err(e) => failures.push(format!("{where_} ({pname}): {e}")),
                }
            }
            // The engines' defaults on the same meshes, judged as the receivers path is.
            for engine in engines() {
                let (caster, receiver) = engine.biases(&case, &light);
                let got = count(&through.look(&mut gl, caster, receiver), &truths[0]);
                peers.engine(world.name, engine.name, got);
            }
        }
        unsafe { gl.glow().delete_buffer(buffer) };
    }
    peers.print();
    println!(
        "shadow receivers: {asked} asked, {answered} answered, {refused} refused, {judged_pixels} judged pixels, {receiver_side} looked up with the receiver-side offset along the light instead, {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

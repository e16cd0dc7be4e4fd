//! The meshes the edge scenes draw (eye-space f32 vertices, every triangle edge drawn): a UV
//! sphere, a tilted torus, a terrain with hills wider than the view and a chamfered box, each
//! made at a size `r` and an eye distance `d`.

use std::collections::HashMap;

/// A triangle mesh with its edges: every triangle side once, and the adjacency both ways.
pub struct Mesh {
    /// What the sweep's labels call it.
    pub name: &'static str,
    /// Eye-space vertices.
    pub verts: Vec<[f32; 3]>,
    /// Triangles, as vertex indices.
    pub tris: Vec<[u32; 3]>,
    /// Every triangle side once, as vertex indices (lower first).
    pub edges: Vec<[u32; 2]>,
    /// Triangles of each edge.
    pub edge_tris: Vec<Vec<usize>>,
    /// Edge of each triangle side (0-1, 1-2, 2-0).
    pub tri_edges: Vec<[usize; 3]>,
}

impl Mesh {
    /// The nearest and farthest eye distance of its vertices.
    pub fn depth_range(&self) -> (f64, f64) {
        self.verts.iter().fold((f64::MAX, 0.0f64), |(a, c), v| {
            (a.min(-f64::from(v[2])), c.max(-f64::from(v[2])))
        })
    }
}

/// A mesh of `tris` over `verts`, with its edges and which triangles each borders.
pub fn finish(name: &'static str, verts: Vec<[f32; 3]>, tris: Vec<[u32; 3]>) -> Mesh {
    let mut index: HashMap<[u32; 2], usize> = HashMap::new();
    let (mut edges, mut edge_tris, mut tri_edges) =
        (Vec::new(), Vec::<Vec<usize>>::new(), Vec::new());
    for (t, tri) in tris.iter().enumerate() {
        let mut te = [0; 3];
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = [a.min(b), a.max(b)];
            let e = *index.entry(key).or_insert_with(|| {
                edges.push(key);
                edge_tris.push(Vec::new());
                edges.len() - 1
            });
            edge_tris[e].push(t);
            te[k] = e;
        }
        tri_edges.push(te);
    }
    Mesh {
        name,
        verts,
        tris,
        edges,
        edge_tris,
        tri_edges,
    }
}

/// `rows` rings of `per_ring` vertices, ring by ring: `point(ring, index)`.
fn rings(rows: usize, per_ring: usize, point: impl Fn(usize, usize) -> [f32; 3]) -> Vec<[f32; 3]> {
    (0..rows)
        .flat_map(|j| (0..per_ring).map(move |i| (j, i)))
        .map(|(j, i)| point(j, i))
        .collect()
}

/// The corners of cell `i` between ring `j` and ring `next` of [`rings`]: two on ring `j`, then
/// two on `next`, the second of each one step further round.
fn cell(per_ring: usize, j: usize, next: usize, i: usize) -> [u32; 4] {
    let at = |ring: usize, k: usize| (ring * per_ring + k % per_ring) as u32;
    [at(j, i), at(j, i + 1), at(next, i), at(next, i + 1)]
}

/// A UV sphere of radius `r` centred at eye depth `d`, 24 × 12, poles dropped to rings.
pub fn sphere(r: f64, d: f64) -> Mesh {
    let (nu, nv) = (24, 12);
    let verts = rings(nv + 1, nu, |j, i| {
        let v = std::f64::consts::PI * j as f64 / nv as f64;
        let u = 2.0 * std::f64::consts::PI * i as f64 / nu as f64 + 0.3;
        // Tilted 20° about x so that the poles are not on the axis.
        let (x, y, z) = (r * v.sin() * u.cos(), r * v.cos(), r * v.sin() * u.sin());
        place([x, y, z], 0.35, 0.0, d)
    });
    let mut tris = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let [a, b, c, e] = cell(nu, j, j + 1, i);
            if j > 0 {
                tris.push([a, b, e]);
            }
            if j < nv - 1 {
                tris.push([a, e, c]);
            }
        }
    }
    finish("sphere", verts, tris)
}

/// A torus of major radius `r`, minor `0.35r`, 24 × 12, tilted 55° toward the camera.
pub fn torus(r: f64, d: f64) -> Mesh {
    let (nu, nv) = (24, 12);
    let verts = rings(nv, nu, |j, i| {
        let v = 2.0 * std::f64::consts::PI * j as f64 / nv as f64;
        let u = 2.0 * std::f64::consts::PI * i as f64 / nu as f64;
        let rr = r + 0.35 * r * v.cos();
        let (x, y, z) = (rr * u.cos(), 0.35 * r * v.sin(), rr * u.sin());
        place([x, y, z], 0.96, 0.0, d)
    });
    let mut tris = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let [a, b, c, e] = cell(nu, j, (j + 1) % nv, i);
            tris.push([a, b, e]);
            tris.push([a, e, c]);
        }
    }
    finish("torus", verts, tris)
}

/// Rotates `v` by `tilt` about x, then `yaw` about y, and moves it to eye depth `d`.
pub fn place(v: [f64; 3], tilt: f64, yaw: f64, d: f64) -> [f32; 3] {
    let (ct, st) = (tilt.cos(), tilt.sin());
    let (x, y, z) = (v[0], ct * v[1] - st * v[2], st * v[1] + ct * v[2]);
    let (cy, sy) = (yaw.cos(), yaw.sin());
    let (x, z) = (cy * x + sy * z, -sy * x + cy * z);
    [x as f32, y as f32, (z - d) as f32]
}

/// A 64 × 64 terrain with hills, `1.6r` wide (wider than the view: cells of 5–7 pixels), seen
/// 25° from above.
pub fn terrain(r: f64, d: f64) -> Mesh {
    let n = 64;
    let half = 0.8 * r / 0.3;
    let mut verts = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f64 / n as f64 - 0.5, j as f64 / n as f64 - 0.5);
            let (x, z) = (2.0 * half * u, 2.0 * half * v);
            let hill =
                |cx: f64, cz: f64, s: f64| (-((u - cx).powi(2) + (v - cz).powi(2)) / s).exp();
            let h = 0.05
                * half
                * (hill(-0.2, 0.1, 0.01)
                    + 0.8 * hill(0.15, -0.15, 0.02)
                    + 0.6 * hill(0.25, 0.25, 0.005))
                + 0.01 * half * (7.0 * u).sin() * (5.0 * v).cos();
            verts.push(place([x, h, z], 25f64.to_radians(), 0.2, d));
        }
    }
    let mut tris = Vec::new();
    let w = (n + 1) as u32;
    for j in 0..n as u32 {
        for i in 0..n as u32 {
            let a = j * w + i;
            tris.push([a, a + 1, a + w + 1]);
            tris.push([a, a + w + 1, a + w]);
        }
    }
    finish("terrain", verts, tris)
}

/// A box of half-size `r` with every edge chamfered (`0.3r`), turned 30° and tilted 35°: six
/// square faces, twelve chamfer rectangles, eight corner triangles. Vertex `(i, k)` of corner
/// `i` lies on the face of axis `k`.
pub fn chamfered_box(r: f64, d: f64) -> Mesh {
    let c = 0.3 * r;
    let signs = |i: usize| [0, 1, 2].map(|k| if i >> k & 1 == 1 { 1.0 } else { -1.0 });
    let vid = |i: usize, k: usize| (3 * i + k) as u32;
    let mut raw = Vec::new();
    for i in 0..8 {
        let s: [f64; 3] = signs(i);
        for k in 0..3 {
            let mut p = s.map(|x| x * (r - c));
            p[k] = s[k] * r;
            raw.push(p);
        }
    }
    let mut tris = Vec::new();
    for i in 0..8 {
        tris.push([vid(i, 0), vid(i, 1), vid(i, 2)]);
    }
    for a in 0..3 {
        let (b, cc) = ((a + 1) % 3, (a + 2) % 3);
        for i in 0..8 {
            if signs(i)[a] > 0.0 {
                continue;
            }
            let j = i | 1 << a;
            tris.push([vid(i, b), vid(j, b), vid(j, cc)]);
            tris.push([vid(i, b), vid(j, cc), vid(i, cc)]);
        }
        for sa in [-1.0, 1.0] {
            let mut ring: Vec<u32> = (0..8)
                .filter(|&i| signs(i)[a] == sa)
                .map(|i| vid(i, a))
                .collect();
            ring.sort_by(|&p, &q| {
                let angle = |v: u32| raw[v as usize][cc].atan2(raw[v as usize][b]);
                angle(p).total_cmp(&angle(q))
            });
            tris.push([ring[0], ring[1], ring[2]]);
            tris.push([ring[0], ring[2], ring[3]]);
        }
    }
    let verts = raw
        .iter()
        .map(|&p| place(p, 35f64.to_radians(), 30f64.to_radians(), d))
        .collect();
    finish("chamfered box", verts, tris)
}

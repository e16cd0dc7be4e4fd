//! One scene drawn on GL as an engine draws it ([`Renderer`]: world space, chunks and decal
//! entities through their model matrices, one matrix or piece by piece) and its pixels counted:
//! decal pixels lost, pixels bled over an occluder at the bleed gap, the smallest working offset.

use super::*;

/// Draws one case's passes on `gl` (target already made).
pub(crate) struct Renderer<'a> {
    gl: &'a mut Gl,
    case: Case,
    pub(crate) plain: [f32; 16],
    pub(crate) ground: Vec<[f32; 3]>,
    /// The ground in chunks, each with its model matrix ([`Case::ground_parts`]).
    chunks: Option<Vec<Chunk>>,
    pub(crate) mask: Vec<bool>,
}

/// A chunk of the ground as drawn: its triangles in its local coordinates and its model matrix.
pub(crate) type Chunk = (Vec<[f32; 3]>, [f32; 16]);

/// Where a mesh's vertices are given: world space (`None`), or a model space through the f32
/// model matrix `M`, its model-view multiplied as [`ModelView`] says.
pub(crate) type Placement = Option<([f32; 16], ModelView)>;

/// The identity, the model matrix of world-space vertices.
pub(crate) const IDENTITY: [f32; 16] = [
    1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
];

/// Cells per side of a chunk of the grid ([`Case::ground_chunks`]).
pub(crate) const CHUNK_CELLS: u32 = 8;

/// Chunks per side of the grid.
pub(crate) const CHUNKS: i64 = 64 / CHUNK_CELLS as i64;

/// The model-view `V·M` an engine multiplies for a model drawn `kind` ([`ModelView`]).
pub(crate) fn model_view(v: &[f32; 16], m: &[f32; 16], kind: ModelView) -> [f32; 16] {
    zshift_harness::world::model_view(v, m, kind == ModelView::Float)
}

/// A decal entity's unit quad in its model space (x and z across, y up), in the corner order of
/// [`Case::square`].
pub(crate) const MODEL_QUAD: [[f32; 3]; 4] = [
    [-0.5, 0.0, 0.5],
    [0.5, 0.0, 0.5],
    [0.5, 0.0, -0.5],
    [-0.5, 0.0, -0.5],
];

/// The decal pass's projection: one matrix for the whole decal, or each piece of a decal over
/// several planes with its own plane's matrix (the remedy `recommend_planes` names when the
/// largest plane's offset would move a nearer plane past the near plane).
#[derive(Clone, Copy)]
pub(crate) enum DecalPass<'p> {
    One(&'p [f32; 16]),
    Pieces(&'p [Piece]),
}

/// A piece of a mesh decal (world-space triangles) and the matrix it is drawn with.
pub(crate) type Piece = (Vec<[f32; 3]>, [f32; 16]);

pub(crate) fn quad_triangles(q: &[[f32; 3]; 4]) -> Vec<[f32; 3]> {
    vec![q[0], q[1], q[2], q[0], q[2], q[3]]
}

impl<'a> Renderer<'a> {
    pub(crate) fn new(gl: &'a mut Gl, case: Case) -> Result<Self, String> {
        let [w, h] = case.framebuffer();
        gl.set_target_samples(w, h, case.at.format, case.at.packed, case.samples)?;
        gl.clip_control(if case.at.clip == ClipDepth::NegOneToOne {
            GlClip::NegativeOneToOne
        } else {
            GlClip::ZeroToOne
        })?;
        gl.set_window(&case.window())?;
        let plain = projection(&case.frustum(), case.at.clip).map_err(|e| e.to_string())?;
        let mut r = Renderer {
            gl,
            case,
            plain,
            ground: case.ground(),
            chunks: case.ground_parts(),
            mask: Vec::new(),
        };
        let (decal, placement) = case.decal_draw();
        r.mask = r.coverage_through(&decal, placement)?;
        if case.ground == Ground::Hills {
            let seen = r.unhidden()?;
            r.mask.iter_mut().zip(seen).for_each(|(m, s)| *m &= s);
        }
        Ok(r)
    }

    /// Over hills, the decal's pixels that no other terrain hides: the terrain outside the
    /// decal's square (cut in f32 as the decal is) drawn with the plain matrix, then the decal
    /// moved 1 % of its distance away from the camera (scaled about it); the pixels it still wins
    /// are in front of all the rest of the terrain by more than that. The decal's pixels behind a
    /// crest, the decal's own terrain's included, are the crest's, not the decal's to lose.
    fn unhidden(&mut self) -> Result<Vec<bool>, String> {
        let [x0, x1, z0, z1] = self.case.decal_square(1.0);
        let inf = f32::INFINITY;
        let outside = [
            [-inf, x0, -inf, inf],
            [x1, inf, -inf, inf],
            [x0, x1, -inf, z0],
            [x0, x1, z1, inf],
        ];
        let others: Vec<[f32; 3]> = outside
            .iter()
            .flat_map(|&part| clip_to_square(&self.ground, part))
            .flat_map(|(_, piece)| piece)
            .collect();
        let cam = self.case.camera();
        let away: Vec<[f32; 3]> = self
            .case
            .decal_triangles()
            .iter()
            .map(|p| [0, 1, 2].map(|k| (cam[k] + (f64::from(p[k]) - cam[k]) * 1.01) as f32))
            .collect();
        self.clear()?;
        let (plain, state) = (self.plain, self.state());
        self.draw(&others, None, &plain, BASE, &state)?;
        self.draw(&away, None, &plain, DECAL, &state)?;
        let seen = self.read_viewport()?.mask_of(zshift_harness::rgba8(DECAL));
        // And whose four neighbours are: the terrain outside the square is cut in pieces that
        // meet at T-junctions, where a pixel can fall through (one did, a decal pixel behind its
        // own terrain's crest counted as lost).
        // (Under MSAA the samples' images lie one above the other: y within its own.)
        let [w, h] = viewport().map(|v| v as usize);
        // Over hills, also where the frontmost terrain triangle's own piece is the frontmost
        // piece ([`Renderer::own_piece_in_front`]).
        let own = if self.case.ground == Ground::Hills {
            self.own_piece_in_front()?
        } else {
            vec![true; seen.len()]
        };

        Ok((0..seen.len())
            .map(|i| {
                let (x, y) = (i % w, (i / w) % h);
                seen[i]
                    && own[i]
                    && (x == 0 || seen[i - 1])
                    && (x + 1 == w || seen[i + 1])
                    && (y == 0 || seen[i - w])
                    && (y + 1 == h || seen[i + w])
            })
            .collect())
    }

    /// Per pixel (sample), whether the frontmost of the decal's pieces drawn alone lies on the
    /// frontmost terrain triangle. The pieces are the terrain's triangles cut to the decal's
    /// square in f32, so their edges are off their triangles' by those roundings; where a
    /// crest's triangle covers a pixel centre its own piece does not, the decal shows there the
    /// piece of a triangle behind the crest, which loses to the crest at any offset short of
    /// their depth difference. No offset is to blame for such a pixel (measured: a decal 48
    /// units long over the hills lost one, at the recommendation and at 12 times it, whose
    /// frontmost triangle's piece did not cover it; `long_decals`).
    fn own_piece_in_front(&mut self) -> Result<Vec<bool>, String> {
        let under = clip_to_square(&self.ground, self.case.decal_square(1.0));
        // Piece k (and its triangle) drawn in the colour that encodes k + 1 (blue 0; the base
        // is blue and the clear colour black, neither an id).
        let id_colour = |k: usize| {
            let id = k + 1;
            [
                (id % 256) as f32 / 255.0,
                (id / 256) as f32 / 255.0,
                0.0,
                1.0,
            ]
        };
        let ids = |image: &zshift_harness::Image| -> Vec<Option<usize>> {
            image
                .pixels
                .iter()
                .map(|p| {
                    let id = usize::from(p[0]) + 256 * usize::from(p[1]);
                    (p[2] == 0 && id >= 1).then_some(id)
                })
                .collect()
        };
        let plain = self.plain;
        // The frontmost terrain triangle: the whole ground, then each triangle under the decal
        // again at its own depth (equal passes) in its colour.
        self.clear_and_draw_ground()?;
        let again = DrawState {
            depth_func: if self.case.reversed() {
                glow::GEQUAL
            } else {
                glow::LEQUAL
            },
            depth_write: false,
            ..self.state()
        };
        for (k, (i, _)) in under.iter().enumerate() {
            let triangle = self.ground[3 * i..3 * i + 3].to_vec();
            self.draw(&triangle, None, &plain, id_colour(k), &again)?;
        }
        let terrain = ids(&self.read_viewport()?);
        // The frontmost piece, the pieces drawn alone.
        self.clear()?;
        let state = self.state();
        for (k, (_, piece)) in under.iter().enumerate() {
            self.draw(piece, None, &plain, id_colour(k), &state)?;
        }
        let pieces = ids(&self.read_viewport()?);
        Ok(terrain
            .iter()
            .zip(&pieces)
            .map(|(t, p)| t.is_some() && t == p)
            .collect())
    }

    /// The viewport's pixels (not the rest of the framebuffer).
    fn read_viewport(&mut self) -> Result<zshift_harness::Image, String> {
        let [w, h] = viewport();
        self.gl.read_color_at(self.case.origin, w, h)
    }

    fn clear(&mut self) -> Result<(), String> {
        let depth = if self.case.reversed() { 0.0 } else { 1.0 };
        self.gl.clear(CLEAR, depth)
    }

    fn state(&self) -> DrawState {
        DrawState {
            depth_func: self.case.tests().0,
            ..DrawState::default()
        }
    }

    /// Draws `triangles` placed as `placement`, projected by `proj`, through the case's
    /// pipeline ([`Case::shader_matrices`]).
    fn draw(
        &mut self,
        triangles: &[[f32; 3]],
        placement: Placement,
        proj: &[f32; 16],
        color: [f32; 4],
        state: &DrawState,
    ) -> Result<(), String> {
        let [view, proj] = self.case.shader_matrices(placement, proj);
        self.gl.draw_world(triangles, &view, &proj, color, state)
    }

    /// Draws the decal as `pass` says.
    fn draw_decal(&mut self, pass: DecalPass, state: &DrawState) -> Result<(), String> {
        match pass {
            DecalPass::One(proj) => {
                let (decal, placement) = self.case.decal_draw();
                self.draw(&decal, placement, proj, DECAL, state)
            }
            DecalPass::Pieces(pieces) => {
                for (triangles, proj) in pieces {
                    self.draw(triangles, None, proj, DECAL, state)?;
                }
                Ok(())
            }
        }
    }

    /// The pixels `triangles` placed as `placement` (a decal entity's model) cover, drawn alone.
    pub(crate) fn coverage_through(
        &mut self,
        triangles: &[[f32; 3]],
        placement: Placement,
    ) -> Result<Vec<bool>, String> {
        self.clear()?;
        let always = DrawState {
            depth_func: glow::ALWAYS,
            ..DrawState::default()
        };
        let plain = self.plain;
        self.draw(triangles, placement, &plain, DECAL, &always)?;
        Ok(self.read_viewport()?.mask_of(zshift_harness::rgba8(DECAL)))
    }

    /// Clears and draws the ground with the plain matrix and the scene's depth test.
    fn clear_and_draw_ground(&mut self) -> Result<(), String> {
        self.clear()?;
        let (plain, state) = (self.plain, self.state());
        if let Some(chunks) = self.chunks.take() {
            let kind = self.case.chunked();
            let drawn = chunks.iter().try_for_each(|(triangles, model)| {
                self.draw(triangles, Some((*model, kind)), &plain, BASE, &state)
            });
            self.chunks = Some(chunks);
            return drawn;
        }
        let ground = std::mem::take(&mut self.ground);
        let drawn = self.draw(&ground, None, &plain, BASE, &state);
        self.ground = ground;
        drawn
    }

    /// The ground's own error, drawn alone (`ZSHIFT_ENGINE_SCENES_GROUND_ERROR=1`): per sixth
    /// row of the viewport, the largest |stored − exact| window depth in f32 units (2⁻²⁴) over
    /// the row, the row's mean eye depth `d`, and their product (a clipper error that propagates
    /// from the near-plane vertices falls as `1/d`: the product is then the same on every row).
    pub(crate) fn ground_error(&mut self) -> Result<Vec<String>, String> {
        self.clear_and_draw_ground()?;
        let stored = self.gl.read_depth()?;
        let c = self.case;
        let (l, r, b, t, n, f) = c.frustum().parameters();
        // The ground plane in eye space: normal and offset from three world points.
        let [o, ex, ez] =
            [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]].map(|[x, z]| c.eye([x, c.height(x), z]));
        let (u1, u2) = (
            [0, 1, 2].map(|k| ex[k] - o[k]),
            [0, 1, 2].map(|k| ez[k] - o[k]),
        );
        let normal = [
            u1[1] * u2[2] - u1[2] * u2[1],
            u1[2] * u2[0] - u1[0] * u2[2],
            u1[0] * u2[1] - u1[1] * u2[0],
        ];
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let m = zshift::projection::projection_f64(&c.frustum(), c.at.clip)
            .map_err(|e| e.to_string())?;
        let [w, h] = viewport().map(|v| v as usize);
        let fw = c.framebuffer()[0] as usize;
        let [ox, oy] = c.origin.map(|v| v as usize);
        let mut rows = Vec::new();
        for py in (0..h).step_by(6) {
            let (mut worst, mut depth_sum, mut count) = (0.0f64, 0.0, 0);
            for px in 0..w {
                let xn = 2.0 * (px as f64 + 0.5) / w as f64 - 1.0;
                let yn = 2.0 * (py as f64 + 0.5) / h as f64 - 1.0;
                let ray = [
                    (xn * (r - l) / 2.0 + (r + l) / 2.0) / n,
                    (yn * (t - b) / 2.0 + (t + b) / 2.0) / n,
                    -1.0,
                ];
                let d = dot(normal, o) / dot(normal, ray);
                if !(d > n && d < f) {
                    continue;
                }
                let ndc = (m[14] - m[10] * d) / d;
                let exact = match c.at.clip {
                    ClipDepth::NegOneToOne => 0.5 * ndc + 0.5,
                    _ => ndc,
                };
                let exact = c.depth_range[0] + (c.depth_range[1] - c.depth_range[0]) * exact;
                let got = f64::from(stored[(py + oy) * fw + px + ox]);
                worst = worst.max((got - exact).abs() * 16_777_216.0);
                depth_sum += d;
                count += 1;
            }
            if count > 0 {
                let d = depth_sum / count as f64;
                rows.push(format!(
                    "  row {py:3}: d {d:9.2}, ground error {worst:9.2} u, times d {:10.1}",
                    worst * d
                ));
            }
        }
        Ok(rows)
    }

    pub(crate) fn lost(&mut self, decal_proj: &[f32; 16]) -> Result<Count, String> {
        self.lost_offset(DecalPass::One(decal_proj), None)
    }

    /// [`Renderer::lost`] with the decal pass under `glPolygonOffset(offset)` too.
    pub(crate) fn lost_offset(
        &mut self,
        pass: DecalPass,
        offset: Option<(f32, f32)>,
    ) -> Result<Count, String> {
        let state = DrawState {
            polygon_offset: offset,
            ..self.state()
        };
        // A decal the far plane cuts: the clipper computes its far corners from their depth,
        // so the offset moves them, and with them the edges that end there; a pixel centre on
        // such an edge is covered at one offset and not at the next, whatever the depth test
        // (a grid scene "lost" a pixel on the far line at every offset from 2 to 2²² steps
        // but two, another two at the corners where the far line meets the sides). Judged: the
        // mask's pixels the decal pass covers when drawn alone.
        let mask = if self.case.beyond {
            self.clear()?;
            let always = DrawState {
                depth_func: glow::ALWAYS,
                ..state
            };
            self.draw_decal(pass, &always)?;
            let covered = self.read_viewport()?.mask_of(zshift_harness::rgba8(DECAL));
            self.mask
                .iter()
                .zip(covered)
                .map(|(m, c)| *m && c)
                .collect()
        } else {
            self.mask.clone()
        };
        self.clear_and_draw_ground()?;
        self.draw_decal(pass, &state)?;
        Ok(Count::decal_missing(&self.read_viewport()?, &mask))
    }

    /// Decal pixels shown over an occluder parallel to the ground whose eye depth is `gap` in
    /// front of the ground's at every decal pixel: along a ray from the camera at distance h
    /// from the ground's plane (its normal), `d_occluder/d_ground = (h − δ)/h`, so `δ = gap·h/d₁`
    /// along the normal suffices (`d₁` the decal's nearest eye depth).
    pub(crate) fn bled(
        &mut self,
        pass: DecalPass,
        gap: f64,
        d1: f64,
    ) -> Result<Option<Count>, String> {
        let h = self.case.clearance();
        let lift = gap * h / d1 * (1.0 + 1e-6);
        if lift >= 0.9 * h {
            return Ok(None); // a gap reaching the camera: nothing to check
        }
        let occluder = quad_triangles(
            &self
                .case
                .square(0.75 * self.case.size, lift)
                .map(|p| p.map(|c| c as f32)),
        );
        self.shown_over(&occluder, pass, false).map(Some)
    }

    /// [`Renderer::bled`] over hills: the occluder is the terrain under a square 1.5 times the
    /// decal's, scaled about the camera by `1 − gap/d₁`, so that at every decal pixel its eye
    /// depth is `gap·d/d₁ ≥ gap` in front of the terrain's (`d₁` the decal's nearest eye depth).
    pub(crate) fn bled_scaled(
        &mut self,
        pass: DecalPass,
        gap: f64,
        d1: f64,
    ) -> Result<Option<Count>, String> {
        let s = 1.0 - gap / d1 * (1.0 + 1e-6);
        if s < 0.1 {
            return Ok(None); // a gap reaching the camera: nothing to check
        }
        let cam = self.case.camera();
        let occluder: Vec<[f32; 3]> = clip_to_square(&self.ground, self.case.decal_square(1.5))
            .into_iter()
            .flat_map(|(_, piece)| piece)
            .map(|p| [0, 1, 2].map(|k| (cam[k] + (f64::from(p[k]) - cam[k]) * s) as f32))
            .collect();
        self.shown_over(&occluder, pass, true).map(Some)
    }

    /// Decal pixels drawn as `pass` says over `occluder` (drawn with the plain matrix after the
    /// ground), among the decal's pixels where the occluder shows over the ground and the decal
    /// drawn with the plain matrix does not show over it. Over hills the occluder (the terrain scaled
    /// toward the camera) is in front of the decal's own plane only where that plane is the
    /// terrain the pixel shows: at a crest's silhouette a mesh decal's piece, cut in f32, can
    /// cover a pixel centre its terrain triangle does not (a seeded draw with a jittered frustum
    /// showed one such pixel with the plain matrix over an occluder 4 times the gap in front),
    /// and there no occluder is in front of its plane. With the plain matrix the decal is within
    /// its errors of its plane, less than the gap, so the filter drops only such pixels.
    /// (`silhouettes`: over hills; a flat ground has none.)
    fn shown_over(
        &mut self,
        occluder: &[[f32; 3]],
        pass: DecalPass,
        silhouettes: bool,
    ) -> Result<Count, String> {
        let (plain, state) = (self.plain, self.state());
        // Where the occluder stands in front of the base as drawn: over the ground with the
        // plain matrix and the scene's test. Its coverage alone is not enough: at a silhouette
        // (the terrain folding over itself, seen along it) a sample the base's own triangle
        // covers can fall, by the rounding of the scaled occluder's edges, under the scaled
        // terrain beyond the fold, behind the base; a decal shown there is over its base with
        // no occluder in front (one such sample under 4x MSAA was counted as bled).
        self.clear_and_draw_ground()?;
        self.draw(occluder, None, &plain, OCCLUDER, &state)?;
        let occ_mask = self
            .read_viewport()?
            .mask_of(zshift_harness::rgba8(OCCLUDER));
        let mut overhang = vec![false; occ_mask.len()];
        if silhouettes {
            self.clear_and_draw_ground()?;
            self.draw(occluder, None, &plain, OCCLUDER, &state)?;
            self.draw_decal(DecalPass::One(&plain), &state)?;
            overhang = self.read_viewport()?.mask_of(zshift_harness::rgba8(DECAL));
        }
        let both: Vec<bool> = (0..occ_mask.len())
            .map(|i| occ_mask[i] && self.mask[i] && !overhang[i])
            .collect();
        self.clear_and_draw_ground()?;
        self.draw(occluder, None, &plain, OCCLUDER, &state)?;
        self.draw_decal(pass, &state)?;
        Ok(Count::decal_shown(&self.read_viewport()?, &both))
    }

    /// The smallest number of f32 steps of the offset element toward the camera that loses no
    /// decal pixel, by bisection up to 2²²; `None` if none does.
    pub(crate) fn smallest_working(&mut self) -> Result<Option<u32>, String> {
        let (plain, reversed) = (self.plain, self.case.reversed());
        let hi = 1 << 22;
        if self.lost(&stepped_toward_camera(&plain, reversed, hi))?.hit > 0 {
            return Ok(None);
        }
        if self.lost(&plain)?.hit == 0 {
            return Ok(Some(0));
        }
        bisect_smallest_passing(0, hi, |k| {
            Ok(self.lost(&stepped_toward_camera(&plain, reversed, k))?.hit == 0)
        })
        .map(Some)
    }
}

//! The edges demonstration (`cargo run --release -p zshift-demo -- --edges DIR`): a tessellated
//! mesh, faces filled, its own edges drawn over them five ways, headless, as one labelled
//! picture (`DIR/edges.png`).
//!
//! The edges are `GL_LINES` (`GL_LEQUAL`) over faces drawn `GL_LESS`, NDC depth [−1, 1],
//! 256×256, in each of [`SCENES`] (one row of the picture each): with no offset; with osgFX::Scribe's
//! `glPolygonOffset(1, 1)` on the faces; with VTK's units-only `glPolygonOffset(0, 4)` on the
//! faces; with zshift's (`zshift::lines::recommend`, the worst-case rasterizer profile, faces up
//! to 60° from the view axis) method (a), its `glPolygonOffset` on the faces, and method (b), the
//! edges drawn through its offset matrix.
//!
//! Each render is read back with `glReadPixels` and counted against the exact reference of
//! `zshift_harness::edges` (the one `tests/gl_lines.rs` counts against: an f64 z-buffer of the
//! faces at every pixel centre and two `gl_PrimitiveID` renders of the edges), nothing from
//! zshift but the window gradient of the 60° face-slope limit, beyond which pixels are not
//! counted (as in the sweep): **lost** are visible edge pixels where the faces cover the edge,
//! **shown** are hidden edge pixels (edges behind a front face by any amount, as the sweep counts
//! the peers'; its assertion on zshift counts only those beyond zshift's hidden-line gap) where
//! an edge is drawn. Every panel is counted against the same pixels. In the picture
//! lost pixels are painted red and shown ones yellow. Exits nonzero, with the reason, if either
//! of zshift's panels loses or shows a pixel.

use std::path::Path;

use zshift::lines::{recommend, EdgeMethod, EdgeRecommendation, Edges, FaceSlope, LineKind};
use zshift::precision::DepthFormat as Format;
use zshift::projection::{projection, projection_f64, ClipDepth, Frustum};
use zshift::recommend::{DepthTest, RasterizerProfile};
use zshift_harness::edges::meshes::torus;
use zshift_harness::edges::{
    classify, count_in, edge_ids, project, reference, Classes, Draw, Limit, Mesh, Primitive,
    Renderer, Scene, Variant, EDGE, SIZE,
};
use zshift_harness::{ClipDepth as GlClip, DepthFormat, Gl, Image};

use crate::picture::{compose_panels, count_line, Panel, Picture};
use crate::scene::snapping_of;

/// The near plane; the frustum is `±HALF_WIDTH·n` wide and high.
const NEAR: f64 = 1.0;
const HALF_WIDTH: f64 = 0.5;
/// The mesh's size as a fraction of its distance (the sweep's default).
const RADIUS: f64 = 0.3;
/// The steepest face that matters: 60° from the view axis.
const ANGLE_DEG: f64 = 60.0;
/// Where the picture marks the visible edge pixels lost and the hidden ones shown.
const LOST: [u8; 4] = [255, 40, 40, 255];
const SHOWN: [u8; 4] = [255, 225, 0, 255];

/// One row of the picture: a mesh at a distance, a far plane and a depth format.
pub struct EdgeScene {
    /// The mesh as the title names it.
    pub what: &'static str,
    /// Its maker (`zshift_harness::edges::meshes`), at a size and an eye distance.
    pub mesh: fn(f64, f64) -> Mesh,
    /// The mesh's eye distance.
    pub distance: f64,
    /// The far plane (the near one is 1).
    pub far: f64,
    /// The depth buffer.
    pub format: DepthFormat,
    /// The edges' `glLineWidth`.
    pub width: f32,
}

/// The picture's rows: the same torus, its edges 1 pixel wide in the middle of a D24 depth range
/// (VTK's units lose the edges, Scribe's factor keeps them), 3 pixels wide there (Scribe's
/// factor no longer covers the line's reach), and 3 pixels wide in the middle of a deep D16 one
/// (VTK's units push the faces back past hidden edges).
pub const SCENES: [EdgeScene; 3] = [
    torus_at(31.6, 1e3, DepthFormat::D24, 1.0),
    torus_at(31.6, 1e3, DepthFormat::D24, 3.0),
    torus_at(1000.0, 1e6, DepthFormat::D16, 3.0),
];

/// The sweep's torus at `distance`, far plane `far`, depth `format`, lines `width` pixels wide.
const fn torus_at(distance: f64, far: f64, format: DepthFormat, width: f32) -> EdgeScene {
    EdgeScene {
        what: "TORUS",
        mesh: torus,
        distance,
        far,
        format,
        width,
    }
}

/// How a panel draws: no offset, an offset on the faces (`glPolygonOffset(factor, units)`), or
/// zshift's answer by one of its methods.
#[derive(Clone, Copy)]
enum Offset {
    None,
    Faces(f32, f32),
    Zshift(EdgeMethod),
}

/// A panel's method.
struct Method {
    name: &'static str,
    label: &'static str,
    offset: Offset,
}

/// The methods compared, in the picture's order.
const METHODS: [Method; 5] = [
    Method {
        name: "none",
        label: "NO OFFSET",
        offset: Offset::None,
    },
    Method {
        name: "Scribe (1, 1)",
        label: "OSGFX::SCRIBE",
        offset: Offset::Faces(1.0, 1.0),
    },
    Method {
        name: "VTK (0, 4)",
        label: "VTK",
        offset: Offset::Faces(0.0, 4.0),
    },
    Method {
        name: "zshift (a)",
        label: "ZSHIFT (A)",
        offset: Offset::Zshift(EdgeMethod::PolygonOffset),
    },
    Method {
        name: "zshift (b)",
        label: "ZSHIFT (B)",
        offset: Offset::Zshift(EdgeMethod::Matrix),
    },
];

/// One method's render of a scene and its counts.
struct Render {
    method: &'static Method,
    /// What it did, as the panel's second label line.
    detail: String,
    image: Image,
    lost: usize,
    shown: usize,
}

/// A scene drawn every way, with the reference's pixel totals and zshift's answers.
struct Row {
    scene: &'static EdgeScene,
    visible: usize,
    hidden: usize,
    renders: Vec<Render>,
    /// zshift's (a) and (b).
    recs: [EdgeRecommendation; 2],
}

/// What zshift is told about `mesh`: the engine's view of the scene.
fn edges_of(mesh: &Mesh, s: &EdgeScene, gl: &Gl) -> Result<Edges, String> {
    let format = Format::from_gl_internal_format(s.format.gl_enum()).map_err(|e| e.to_string())?;
    let mut edges = Edges::new([SIZE, SIZE], format, <[f64; 2]>::from(mesh.depth_range()));
    edges.kind = LineKind::Lines;
    edges.line_width = f64::from(s.width);
    edges.profile = RasterizerProfile {
        snapping: snapping_of(gl),
        ..RasterizerProfile::worst_case()
    };
    edges.face_slope = FaceSlope::Angle(ANGLE_DEG.to_radians());
    edges.depth_test = DepthTest::LessEqual;
    Ok(edges)
}

/// The draw of `method` and its panel's detail line.
fn draw_of(method: &Method, m: &[f32; 16], recs: &[EdgeRecommendation; 2]) -> (Draw, String) {
    let faces = |f: f32, u: f32| Draw {
        face_offset: Some((f, u)),
        edge_matrix: *m,
    };
    // The label is rounded to fit the panel; the printed table has the values drawn.
    let label = |f: f32, u: f32| format!("OFFSET ({}, {})", compact(f), compact(u));
    match method.offset {
        Offset::None => (
            Draw {
                face_offset: None,
                edge_matrix: *m,
            },
            "EDGES OVER THE FACES".into(),
        ),
        Offset::Faces(f, u) => (faces(f, u), label(f, u)),
        Offset::Zshift(EdgeMethod::PolygonOffset) => {
            let [f, u] = recs[0].polygon_offset.map(|x| x as f32);
            (faces(f, u), label(f, u))
        }
        Offset::Zshift(EdgeMethod::Matrix) => (
            Draw {
                face_offset: None,
                edge_matrix: recs[1].matrix,
            },
            format!("MATRIX, NDC {:.1E}", recs[1].ndc_offset),
        ),
    }
}

/// `x` with at most two decimals, trailing zeros dropped.
fn compact(x: f32) -> String {
    let s = format!("{x:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `img` as a picture's panel: lost visible edge pixels in [`LOST`], shown hidden ones in
/// [`SHOWN`].
fn marked(mut img: Vec<[u8; 4]>, c: &Classes) -> Image {
    for &i in &c.visible {
        if img[i][..3] != EDGE {
            img[i] = LOST;
        }
    }
    for &i in &c.hidden {
        if img[i][..3] == EDGE {
            img[i] = SHOWN;
        }
    }
    Image {
        width: SIZE as usize,
        height: SIZE as usize,
        pixels: img,
    }
}

/// Draws `s` every way and counts each render against the exact reference.
fn measure(gl: &mut Gl, renderer: &Renderer, s: &'static EdgeScene) -> Result<Row, String> {
    gl.set_target(SIZE, SIZE, s.format)?;
    gl.clip_control(GlClip::NegativeOneToOne)?;
    let mesh = (s.mesh)(RADIUS * s.distance, s.distance);
    let t = HALF_WIDTH * NEAR;
    let frustum = Frustum::new(-t, t, -t, t, NEAR, s.far).map_err(|e| e.to_string())?;
    let clip = ClipDepth::NegOneToOne;
    let m = projection(&frustum, clip).map_err(|e| e.to_string())?;
    let mf = projection_f64(&frustum, clip).map_err(|e| e.to_string())?;
    let edges = edges_of(&mesh, s, gl)?;
    let ask = |method| recommend(&m, clip, &edges, method).map_err(|e| e.to_string());
    let recs = [ask(EdgeMethod::PolygonOffset)?, ask(EdgeMethod::Matrix)?];
    let p = project(&mesh, &mf);
    let rf = reference(&mesh, &p, [0.5, 0.5]);
    renderer.load(gl.glow(), &mesh);
    let variant = Variant {
        kind: Primitive::Lines,
        width: s.width,
        samples: 1,
    };
    let scene = Scene::new(gl, renderer, &mesh, m, false, variant, None);
    let ids = edge_ids(&scene);
    // Every hidden edge pixel, behind its front face by any amount (gap 0), for every panel.
    let b = s.far * NEAR / (s.far - NEAR);
    let g = recs[0].face_gradient;
    // Single-sampled: the faces whose larger gradient component is within the limit.
    let c = classify(
        &scene,
        &p,
        std::slice::from_ref(&rf),
        &ids,
        b,
        Limit::MaxComponent(g),
        0.0,
    );
    Ok(Row {
        scene: s,
        visible: c.visible.len(),
        hidden: c.hidden.len(),
        renders: render_all(&scene, &c, &recs),
        recs,
    })
}

/// Every method's render of `scene`, counted against `c`.
fn render_all(scene: &Scene, c: &Classes, recs: &[EdgeRecommendation; 2]) -> Vec<Render> {
    METHODS
        .iter()
        .map(|method| {
            let (draw, detail) = draw_of(method, &scene.m, recs);
            let img = scene.render(&draw);
            let (lost, shown) = count_in(&img, c);
            Render {
                method,
                detail,
                image: marked(img, c),
                lost,
                shown,
            }
        })
        .collect()
}

/// The title lines over a row.
fn title(r: &Row) -> Vec<String> {
    let s = r.scene;
    vec![
        format!(
            "{}, {} UNITS AWAY, F/N = {:.0E}, {}: {}-PIXEL GL_LINES OVER BLUE FACES, OFFSET = GLPOLYGONOFFSET ON THEM",
            s.what,
            s.distance,
            s.far / NEAR,
            s.format.name(),
            s.width
        ),
        format!(
            "RED: VISIBLE EDGE PIXELS LOST (OF {}). YELLOW: HIDDEN EDGE PIXELS SHOWN (OF {})",
            r.visible, r.hidden
        ),
    ]
}

/// The footer: what zshift answered, and on the last row where the counts come from.
fn footer(gl: &Gl, r: &Row, last: bool) -> Vec<String> {
    let mut lines = vec![format!(
        "ZSHIFT'S HIDDEN-LINE GAP: {:.2} (A), {:.2} (B) EYE UNITS",
        r.recs[0].hidden_gap, r.recs[1].hidden_gap
    )];
    if last {
        lines.push(format!(
            "COUNTED WITH GLREADPIXELS AGAINST AN EXACT F64 Z-BUFFER OF THE FACES ({})",
            gl.renderer().split(" (").next().unwrap_or_default()
        ));
    }
    lines
}

/// The row's picture: every render between its labels and its counts.
fn picture_of(gl: &Gl, r: &Row, last: bool) -> Picture {
    let panels: Vec<Panel> = r
        .renders
        .iter()
        .map(|x| Panel {
            picture: Picture::from_image(&x.image),
            label: [x.method.label.to_string(), x.detail.clone()],
            counts: vec![
                count_line("LOST", x.lost, r.visible, 0),
                count_line("SHOWN", x.shown, r.hidden, 0),
            ],
        })
        .collect();
    compose_panels(&panels, panels.len(), &title(r), &footer(gl, r, last))
}

/// Prints a row's counts.
fn report(r: &Row) {
    let s = r.scene;
    println!(
        "{} at {} units, f/n {:e}, {}, {}-pixel GL_LINES: {} visible edge pixels, {} hidden",
        (s.mesh)(1.0, 1.0).name,
        s.distance,
        s.far / NEAR,
        s.format.name(),
        s.width,
        r.visible,
        r.hidden
    );
    for x in &r.renders {
        println!(
            "  {:<14} {:<28} lost {:>5} ({:>4.1} %)  shown {:>5} ({:>4.1} %)",
            x.method.name,
            x.detail,
            x.lost,
            crate::scene::percent(x.lost, r.visible),
            x.shown,
            crate::scene::percent(x.shown, r.hidden)
        );
    }
    let [a, b] = &r.recs;
    println!(
        "  zshift: (a) glPolygonOffset({}, {}), (b) NDC offset {:.4e}; hidden-line gap (a) {:.3}, (b) {:.3} eye units",
        a.polygon_offset[0] as f32, a.polygon_offset[1] as f32, b.ndc_offset, a.hidden_gap, b.hidden_gap
    );
}

/// zshift's panels that lose or show a pixel, as failures.
fn verdict(r: &Row) -> Vec<String> {
    r.renders
        .iter()
        .filter(|x| matches!(x.method.offset, Offset::Zshift(_)) && x.lost + x.shown > 0)
        .map(|x| {
            format!(
                "{} in the {} row lost {} visible and showed {} hidden edge pixels",
                x.method.name, r.scene.what, x.lost, x.shown
            )
        })
        .collect()
}

/// Draws every scene, prints the counts, writes `edges.png` into `out_dir`. Fails if zshift's
/// panels lose or show a pixel.
pub fn demonstrate(gl: &mut Gl, out_dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(out_dir).map_err(|e| format!("{}: {e}", out_dir.display()))?;
    let renderer = Renderer::new(gl.glow());
    let mut picture: Option<Picture> = None;
    let mut failures = Vec::new();
    for (i, s) in SCENES.iter().enumerate() {
        let row = measure(gl, &renderer, s)?;
        report(&row);
        failures.extend(verdict(&row));
        let p = picture_of(gl, &row, i + 1 == SCENES.len());
        picture = Some(match picture {
            None => p,
            Some(top) => Picture::stacked(&top, &p),
        });
    }
    let png = out_dir.join("edges.png");
    picture.ok_or("no scenes")?.write_png(&png)?;
    println!("picture: {}", png.display());
    match failures.is_empty() {
        true => Ok(()),
        false => Err(failures.join("; ")),
    }
}

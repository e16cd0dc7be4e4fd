//! `--shadows DIR`: the shadow scene of `tests/gl_shadow.rs` (a 12 × 12 ground with a box
//! standing on it, `zshift_harness::shadow_scene`) under one light, looked up six ways: the
//! shadow-bias defaults of Unity URP, Godot 4, Filament, bevy and three.js as the test draws
//! them, and zshift's bias (`zshift::shadow::shadow_bias_for_receivers`, the ground listed, the
//! light's view given, the worst-case rasterizer profile: nothing probed). Each lookup is read
//! back with `glReadPixels` and counted against the test's exact f64 ray-traced reference:
//! **acne** (lit ground the map darkens) and **leak** (shadowed ground the map leaves fully lit:
//! the shadow detached, peter-panning). Writes `DIR/shadows.png`, prints the table, and fails if
//! zshift's lookup shows an acne pixel.

use crate::picture::{compose_panels, count_line, Panel, Picture};
use crate::scene::percent;
use zshift::projection::ClipDepth;
use zshift::recommend::RasterizerProfile;
use zshift::shadow::shadow_bias_for_receivers;
use zshift_harness::shadow_scene::{
    blocked, camera, engines, invert, judge, light_of, pixel_ray, reference, Case, CasterBias,
    Count, Kind, Light, ReceiverBias, Rig, Verdict, AZIMUTH_DEG, CAMERA, RECEIVER_LIMIT_DEG,
};
use zshift_harness::{glow::HasContext, DepthFormat, Gl, Profile};

/// The light and its map.
const SCENE: Case = Case {
    kind: Kind::Spot,
    elevation: 20.0,
    azimuth: AZIMUTH_DEG,
    ratio: 1e3,
    resolution: 1024,
    format: DepthFormat::D16,
    clip: ClipDepth::NegOneToOne,
    pcf: 3,
    radius: 0.0,
    atlas: None,
    shift: [0.0; 3],
};
/// Each camera pixel drawn as `ZOOM × ZOOM` picture pixels, panels three to a row.
const ZOOM: usize = 2;
const COLUMNS: usize = 3;
/// Ground colours: fully lit, fully shadowed; acne and leak marks; the see-through box; sky.
const LIT: [u8; 3] = [226, 214, 182];
const SHADOW: [u8; 3] = [72, 78, 104];
const ACNE: [u8; 3] = [255, 0, 200];
const LEAK: [u8; 3] = [0, 220, 255];
const BOX: [u8; 3] = [150, 150, 160];
const SKY: [u8; 3] = [30, 32, 40];

/// One lookup of the scene: its label, what the camera read back, and its count.
struct Lookup {
    label: [String; 2],
    pixels: Vec<[u8; 2]>,
    count: Count,
}

/// The scene as lit and seen: what every lookup shares.
struct Setting {
    case: Case,
    light: Light,
    eye: [f64; 3],
    camera: [f64; 16],
    truth: Vec<Option<bool>>,
}

impl Setting {
    fn new(case: Case) -> Setting {
        let light = light_of(&case);
        let (eye, camera) = camera();
        let truth = reference(&case, &light, &camera, eye, case.kernel_reach());
        Setting {
            case,
            light,
            eye,
            camera,
            truth,
        }
    }
}

/// Runs `--shadows` into `dir` (default `target/shadows`).
pub fn run(dir: Option<std::ffi::OsString>) -> Result<(), String> {
    let dir = dir.map_or_else(|| "target/shadows".into(), std::path::PathBuf::from);
    let mut gl = Gl::new(Profile::Core).map_err(|e| format!("no headless GL context: {e}"))?;
    // SAFETY: the harness's context is current on this thread from here on.
    let rig = unsafe { Rig::new(&gl) }?;
    let setting = Setting::new(SCENE);
    let lookups = look_all(&mut gl, &rig, &setting)?;
    print_table(&gl, &setting, &lookups);
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let png = dir.join("shadows.png");
    picture(&gl, &setting, &lookups).write_png(&png)?;
    println!("picture: {}", png.display());
    let zshift = &lookups[lookups.len() - 1].count;
    match zshift.acne {
        0 => Ok(()),
        n => Err(format!(
            "zshift's bias leaves {n} acne pixels of {} lit",
            zshift.lit
        )),
    }
}

/// Looks the ground up through every engine's default and then zshift's bias.
fn look_all(gl: &mut Gl, rig: &Rig, s: &Setting) -> Result<Vec<Lookup>, String> {
    // SAFETY (every block below): the harness's context is current on this thread.
    let unbiased = unsafe { rig.map(gl, &s.case, &s.light, CasterBias::default()) }?;
    let mut lookups = Vec::new();
    for engine in engines() {
        let (caster, receiver) = engine.biases(&s.case, &s.light);
        let pixels = unsafe { look(gl, rig, s, unbiased.0, caster, receiver) }?;
        lookups.push(Lookup {
            label: [engine.name.to_uppercase(), engine.short.into()],
            count: zshift_harness::shadow_scene::count(&pixels, &s.truth),
            pixels,
        });
    }
    let (caster, label) = zshift_bias(s)?;
    let pixels = unsafe { look(gl, rig, s, unbiased.0, caster, ReceiverBias::default()) }?;
    lookups.push(Lookup {
        label,
        count: zshift_harness::shadow_scene::count(&pixels, &s.truth),
        pixels,
    });
    unsafe {
        gl.glow().delete_framebuffer(unbiased.1);
        gl.glow().delete_texture(unbiased.0);
    }
    Ok(lookups)
}

/// [`Rig::look_biased`] for the setting.
///
/// # Safety
/// The harness's context is current on this thread.
unsafe fn look(
    gl: &mut Gl,
    rig: &Rig,
    s: &Setting,
    unbiased: zshift_harness::glow::Texture,
    caster: CasterBias,
    receiver: ReceiverBias,
) -> Result<Vec<[u8; 2]>, String> {
    rig.look_biased(gl, &s.case, &s.light, &s.camera, unbiased, caster, receiver)
}

/// zshift's caster bias for the setting (the ground listed as the receiver, the light's view
/// given, the worst-case profile) as `glPolygonOffsetClamp`, and its panel label.
fn zshift_bias(s: &Setting) -> Result<(CasterBias, [String; 2]), String> {
    let map = s.case.shadow_map(
        &s.light,
        RECEIVER_LIMIT_DEG,
        RasterizerProfile::worst_case(),
        s.light.pipeline(),
    );
    let bias = shadow_bias_for_receivers(&map, &[&s.light.ground_quad()])
        .map_err(|e| format!("zshift refused the scene: {e}"))?;
    let caster = CasterBias::of(&bias);
    let [f, u, c] = bias.gl_polygon_offset.map(|x| x as f32);
    println!("zshift: glPolygonOffsetClamp({f}, {u}, {c:e})");
    let label = format!("OFFSET {f:.2}, {u:.0}, {c:.1E}");
    Ok((caster, ["ZSHIFT".into(), label]))
}

/// The table: per lookup, its acne and leak against the reference.
fn print_table(gl: &Gl, s: &Setting, lookups: &[Lookup]) {
    println!("shadows: {} ({})", s.case.label(), gl.renderer());
    println!("| bias | acne (of lit) | leak (of shadowed) |");
    println!("|---|---|---|");
    for l in lookups {
        let c = &l.count;
        println!(
            "| {} ({}) | {} of {} ({:.1} %) | {} of {} ({:.1} %) |",
            l.label[0],
            l.label[1],
            c.acne,
            c.lit,
            percent(c.acne, c.lit),
            c.leak,
            c.shadowed,
            percent(c.leak, c.shadowed)
        );
    }
}

/// The picture: every lookup's panel with its counts, a title naming the light and a footer
/// saying how it was counted.
fn picture(gl: &Gl, s: &Setting, lookups: &[Lookup]) -> Picture {
    let see_through = box_pixels(s);
    let panels: Vec<Panel> = lookups
        .iter()
        .map(|l| {
            let c = &l.count;
            Panel {
                picture: panel(l, s, &see_through),
                label: l.label.clone(),
                counts: vec![
                    count_line("ACNE", c.acne, c.lit, 1),
                    count_line("LEAK", c.leak, c.shadowed, 1),
                ],
            }
        })
        .collect();
    let first = &lookups[0].count;
    let footer = vec![
        format!(
            "COUNTED WITH GLREADPIXELS AGAINST AN EXACT F64 RAY TEST ({}): {} LIT AND",
            gl.renderer().split(" (").next().unwrap_or_default(),
            first.lit
        ),
        format!(
            "{} SHADOWED GROUND PIXELS. ZSHIFT: THE GROUND LISTED, WORST-CASE RASTERIZER",
            first.shadowed
        ),
    ];
    compose_panels(&panels, COLUMNS, &title(&s.case), &footer)
}

/// The title: the light, its map, the lookup, and what the marks mean (the font has capitals
/// only, and no brackets).
fn title(case: &Case) -> Vec<String> {
    let light = match case.kind {
        Kind::Directional => "DIRECTIONAL",
        Kind::Spot => "SPOT",
    };
    let depth = match case.clip {
        ClipDepth::NegOneToOne => "Z -1 TO 1",
        ClipDepth::ZeroToOne => "Z 0 TO 1",
        ClipDepth::ReversedZeroToOne => "REVERSED Z",
    };
    let lookup = match case.pcf {
        1 => "NEAREST".into(),
        0 => "HARDWARE 2X2".into(),
        k => format!("{k}X{k} PCF"),
    };
    let n = case.resolution;
    vec![
        format!(
            "{light} LIGHT AT {} DEG, F/N = {:.0E}, {n}X{n} {} MAP ({depth}), {lookup}",
            case.elevation,
            case.ratio,
            case.format.name()
        ),
        "A 1.2 X 2 X 0.8 BOX (DRAWN SEE-THROUGH) STANDING ON A 12 X 12 GROUND".into(),
        "MAGENTA: ACNE (LIT GROUND THE MAP DARKENS). CYAN: LEAK (SHADOW LOST OR DETACHED)".into(),
    ]
}

/// One lookup as a picture: the ground shaded by its lit taps, acne and leak marked, the box
/// laid over see-through (the ground behind it is counted too), the sky where no ground is.
fn panel(l: &Lookup, s: &Setting, see_through: &[bool]) -> Picture {
    let mut p = Picture::new(CAMERA * ZOOM, CAMERA * ZOOM);
    for (i, (&px, &truth)) in l.pixels.iter().zip(&s.truth).enumerate() {
        let colour = match judge(px, truth) {
            Some(Verdict::Acne) => ACNE,
            Some(Verdict::Leak) => LEAK,
            _ if px[1] == 0 => SKY,
            _ => mix(SHADOW, LIT, f64::from(px[0]) / f64::from(px[1])),
        };
        let colour = if see_through[i] {
            mix(colour, BOX, 0.55)
        } else {
            colour
        };
        // Camera rows run bottom-up, the picture's top-down.
        let (x, y) = (i % CAMERA, CAMERA - 1 - i / CAMERA);
        for (dx, dy) in (0..ZOOM).flat_map(|a| (0..ZOOM).map(move |b| (a, b))) {
            p.pixels[(y * ZOOM + dy) * p.width + x * ZOOM + dx] = colour;
        }
    }
    p
}

/// `a` moved toward `b` by `t` in `[0, 1]`.
fn mix(a: [u8; 3], b: [u8; 3], t: f64) -> [u8; 3] {
    [0, 1, 2].map(|k| (f64::from(a[k]) + (f64::from(b[k]) - f64::from(a[k])) * t).round() as u8)
}

/// Per camera pixel: does its ray meet the box before the ground (or the sky)?
fn box_pixels(s: &Setting) -> Vec<bool> {
    let inverse = invert(&s.camera);
    (0..CAMERA * CAMERA)
        .map(|i| {
            let d = pixel_ray(&inverse, s.eye, i % CAMERA, i / CAMERA);
            let ground = -s.eye[1] / d[1];
            blocked(s.eye, d, if ground > 0.0 { ground } else { f64::INFINITY })
        })
        .collect()
}

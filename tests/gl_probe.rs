//! The rasterizer probe on a real context (Mesa llvmpipe through EGL, core and compatibility
//! profiles): its figures against what is known of llvmpipe and against an independent
//! readback, the caller's state left as it was, and errors that name what failed.
//!
//! Fails, never skips, when no GL context can be made.

use std::ffi::{c_char, c_void, CStr};
use std::sync::atomic::{AtomicUsize, Ordering};

use zshift::ffi::{
    zshift_last_error, zshift_probe, zshift_profile_worst_case, ZshiftGlProc, ZshiftProfile,
    ZSHIFT_ERR_GL, ZSHIFT_ERR_NULL_POINTER, ZSHIFT_NEAR_CLIP_CLIPPED_F32, ZSHIFT_OK,
};
use zshift::probe::{probe, probe_with_figures};
use zshift::profile::{NearClip, RasterizerProfile, Snapping};
use zshift::ErrorKind;
use zshift_harness::glow::{self, HasContext};
use zshift_harness::{ClipDepth, DepthFormat, DrawState, Gl, Profile, Quad};

fn context(profile: Profile) -> Gl {
    Gl::new(profile)
        .unwrap_or_else(|e| panic!("no {profile:?} OpenGL context (EGL surfaceless): {e}"))
}

/// The harness context's loader, as an engine would pass its own.
fn loader(gl: &Gl) -> impl FnMut(&CStr) -> *const c_void + '_ {
    |name| gl.proc_address(name.to_str().unwrap_or(""))
}

fn measured(gl: &Gl) -> RasterizerProfile {
    // SAFETY: the harness's context is current on this thread and EGL returns its entry points.
    unsafe { probe(loader(gl)) }.unwrap_or_else(|e| panic!("probe failed: {e}"))
}

/// The stored offset of `glPolygonOffset(0, units)` on a camera-facing quad, in window depth,
/// read back through the harness (its own shader, its own readback), independent of the probe.
fn offset_of_one_unit(gl: &mut Gl, format: DepthFormat, depth: f32) -> f64 {
    gl.set_target(32, 32, format).unwrap();
    let identity: [f32; 16] = [
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.,
    ];
    let quad = Quad::rect(-1.0, 1.0, -1.0, 1.0, 2.0 * depth - 1.0);
    let always = DrawState {
        depth_func: glow::ALWAYS,
        ..DrawState::default()
    };
    let units = 1024.0;
    let mut read = |offset: Option<(f32, f32)>| {
        gl.clear([0.0; 4], 1.0).unwrap();
        let state = DrawState {
            polygon_offset: offset,
            ..always
        };
        gl.draw_quad(&quad, &identity, [1.0; 4], &state).unwrap();
        let d = gl.read_depth().unwrap();
        d.iter().map(|&v| v as f64).sum::<f64>() / d.len() as f64
    };
    let plain = read(None);
    let offset = read(Some((0.0, units)));
    (offset - plain) / units as f64
}

/// On any rasterizer: the probe's polygon-offset unit `r` equals the harness's own readback of
/// one offset draw. On llvmpipe (CI's): every figure as its source code says it must be. On
/// another rasterizer (a GPU through EGL) the llvmpipe figures are not asserted, and the test
/// says so.
#[test]
fn probe_matches_an_independent_readback_and_llvmpipes_known_figures() {
    for kind in [Profile::Core, Profile::Compatibility] {
        let mut gl = context(kind);
        // SAFETY: as in `measured`.
        let (p, figures) = unsafe { probe_with_figures(loader(&gl)) }.unwrap();
        println!("{kind:?}: {p:?}\n{figures:?}");
        assert!(p.measured);
        assert!(p.probe_seconds > 0.0);
        for (slot, format, depth, quantum) in [
            (0, DepthFormat::D16, 0.5f32, 1.0 / 65535.0),
            (1, DepthFormat::D24, 0.5, 1.0 / 16_777_215.0),
            (3, DepthFormat::D32F, 0.75, 2f64.powi(-24)),
        ] {
            let r = offset_of_one_unit(&mut gl, format, depth) / quantum;
            assert!(
                (p.resolvable[slot] - r).abs() < 0.01,
                "{format:?}: probe {} vs readback {r}",
                p.resolvable[slot]
            );
        }
        if !gl.renderer().contains("llvmpipe") {
            println!(
                "{kind:?} on {}: probe and readback agree on r; llvmpipe's own figures not asserted here",
                gl.renderer()
            );
            continue;
        }
        // llvmpipe snaps coverage to GL_SUBPIXEL_BITS but sets the depth plane up from the float
        // positions (lp_setup_tri.c): unsnapped, and clearly so.
        // A facing decal over its shared-z base: a few f32 steps of element 10 on D24 (one step
        // is about a quantum); D16 is not measured (its quantum is hundreds of steps).
        assert!(p.facing_quanta[0].is_nan(), "{:?}", p.facing_quanta);
        // Under [0, 1] a step of element 10 is two quanta; under reversed Z (D32F) a relative ε
        // of a few 2^-24.
        assert!(
            (2.0..=8.0).contains(&p.facing_quanta_zero_to_one[1]),
            "{:?}",
            p.facing_quanta_zero_to_one
        );
        assert!(
            p.facing_reversed > 0.0 && p.facing_reversed <= 8.0,
            "{}",
            p.facing_reversed
        );
        assert!(
            (1.0..=4.0).contains(&p.facing_quanta[1]),
            "{:?}",
            p.facing_quanta
        );
        assert_eq!(p.snapping, Snapping::Unsnapped);
        // Lines: a 1-pixel line's fragment takes the line's depth at its major-axis coordinate,
        // up to half a pixel across the line (the diamond-exit rule); polygon-mode lines go
        // through the same line set-up. glPolygonOffset's slope term is max(|dz/dx|, |dz/dy|)
        // (lp_setup_tri.c), 1 on the diagonal plane, not sqrt(2). tests/gl_lines.rs checks the
        // reach on meshes against an exact reference.
        assert!(
            (0.5..0.55).contains(&p.line_reach[0]) && (0.5..0.8).contains(&p.line_reach[1]),
            "{:?}",
            p.line_reach
        );
        assert!(
            figures.line_pixels[0] > 2000 && figures.line_pixels[1] > 2000,
            "{figures:?}"
        );
        // Mesa's draw module draws a triangle's outline as lines with their own set-up: beyond a
        // side of constant depth its fragments keep that depth (f32 noise), not the plane's
        // (0.5 pixel of gradient a pixel out), so a neighbour's outline adds no slope term.
        assert!(
            p.outline_neighbour < 1e-3 && figures.outline_neighbour_pixels > 100,
            "{} over {}",
            p.outline_neighbour,
            figures.outline_neighbour_pixels
        );
        // Under 4x MSAA llvmpipe's line sample takes its depth about a pixel from itself along
        // the gradient (1.056), both kinds: less than the worst case's sqrt(2).
        assert!(
            p.line_reach_msaa.iter().all(|r| (1.0..1.1).contains(r))
                && figures.msaa_line_samples.iter().all(|&n| n > 30000)
                && figures.msaa_sample_counts[0] == 4,
            "{:?} over {:?} samples at {:?}",
            p.line_reach_msaa,
            figures.msaa_line_samples,
            figures.msaa_sample_counts
        );
        // Against the whole gradient |∇z| those samples lie within (w + 1)/2 = 1 of their line,
        // as the model takes under a face-slope angle (zshift::lines): 0.87 here, each sample
        // off the plane by less than |∇z|·0.9 whatever the gradient's direction.
        assert!(
            p.line_reach_msaa_whole
                .iter()
                .zip(p.line_reach_msaa)
                .all(|(&whole, reach)| (0.7..0.9).contains(&whole) && whole < reach),
            "{:?} against {:?}",
            p.line_reach_msaa_whole,
            p.line_reach_msaa
        );
        // At glLineWidth(3) (a compatibility context draws it): within the model's (w + 1)/2 = 2
        // of the whole gradient, and at least the line's half width.
        assert!(
            p.line_reach_msaa_wide_whole
                .iter()
                .all(|&whole| (1.4..2.0).contains(&whole))
                && figures.msaa_wide_line_samples.iter().all(|&n| n > 5000),
            "{:?} over {:?}",
            p.line_reach_msaa_wide_whole,
            figures.msaa_wide_line_samples
        );
        // 3-pixel lines and outlines: 1.5 pixels (the wide quad's bound is 2.125 for outlines).
        assert!(
            p.line_reach_wide.iter().all(|r| (1.49..1.6).contains(r))
                && figures.wide_line_pixels.iter().all(|&n| n > 5000),
            "{:?} over {:?}",
            p.line_reach_wide,
            figures.wide_line_pixels
        );
        assert!((p.offset_slope - 1.0).abs() < 1e-3, "{}", p.offset_slope);
        assert!(
            (figures.offset_slope_axis - 1.0).abs() < 1e-3,
            "{figures:?}"
        );
        assert!(
            figures.snapping_residual.0 * 4.0 < figures.snapping_residual.2,
            "{figures:?}"
        );
        // r: lp_state_setup.c scales units by 2·mrd on UNORM (mrd = 1/(2^m − 1)) and by 2^(e−23)
        // on float depth (the readback above agrees with the probe).
        let r = [p.resolvable[0], p.resolvable[1], p.resolvable[3]];
        assert!(
            (r[0] - 2.0).abs() < 0.01 && (r[1] - 2.0).abs() < 0.01 && (r[2] - 1.0).abs() < 0.01,
            "r = {r:?}"
        );
        // The same r by Wine's bisection: the units that separate a coplanar quad are 1/r on
        // D16. On D24 one quantum is one f32 ulp of the depth, and the f32 sum depth + offset
        // needs a little more (1.25 quanta measured): between 1 and 1.5 quanta.
        let units = wine_style_units(&mut gl, DepthFormat::D16);
        let quanta = units * p.resolvable[0];
        assert!((quanta - 1.0).abs() < 0.02, "D16: {units} units separate");
        let units = wine_style_units(&mut gl, DepthFormat::D24);
        let quanta = units * p.resolvable[1];
        assert!((1.0..1.5).contains(&quanta), "D24: {units} units separate");
        // Per-pixel error of a plane: D16 rounds to nearest (½ quantum) plus f32 noise well
        // below a quantum; D24 and D32F carry a few f32 roundings of the plane's terms, whose
        // magnitude grows with a steep plane's distance from the window origin (up to ~25 here),
        // which error_ulps measures: a few roundings, the same on every format.
        assert!(p.plane_error[0] < 1.0, "{:?}", p.plane_error);
        assert!(
            p.plane_error[1] < 64.0 && p.plane_error[3] < 64.0,
            "{:?}",
            p.plane_error
        );
        assert!(p.error_ulps > 0.5 && p.error_ulps < 4.0, "{p:?}");
        assert!(figures.error_ulps[1] <= p.error_ulps, "{figures:?}");
        assert!(p.plane_error_reversed < 64.0, "{p:?}");
        // D16, D24 and D32F are measured; GL_DEPTH_COMPONENT32 keeps the worst case.
        assert!(
            [0, 1, 3].iter().all(|&i| figures.plane_pixels[i] > 20_000),
            "{figures:?}"
        );
        assert_eq!(figures.plane_pixels[2], 0);
        assert_eq!(p.resolvable[2], 1.0);
        assert!(
            p.error_ulps_reversed > 0.5 && p.error_ulps_reversed < 8.0,
            "{p:?}"
        );
        // The probe's error_ulps, measured within 512 pixels of the origin, still bounds a steep
        // plane 2000 pixels away, where plane_error alone would not.
        let (ratio, worst) = far_strip_error(&mut gl);
        println!("{kind:?}: far strip {worst:.1} units of 2^-24, {ratio:.3} u(1+M)");
        assert!(ratio <= p.error_ulps, "{ratio} > {}", p.error_ulps);
        // llvmpipe's facing depth chain: m10·z + m14 in two roundings, w's reciprocal times
        // clip z, ½·ndc + ½ in two roundings, UNORM as round-half-even(fl(w·(2^m − 1))): the
        // probe identified it from every stored depth of its facing planes.
        let chain = p.facing_chain.expect("llvmpipe's depth chain identified");
        assert!(
            !chain.fused_clip && chain.reciprocal && !chain.fused_viewport,
            "{chain:?}"
        );
        assert!(figures.chain_observations > 2000, "{figures:?}");
        // The draw module clips at the near plane in f32 (draw_pipe_clip.c): tens of quanta off.
        assert_eq!(p.near_clip, NearClip::ClippedF32);
        assert!(figures.near_clip_error > 10.0, "{figures:?}");
        // The same planes clipped in f64 before drawing keep their plane: the clipper's f32
        // intersections, not the far-away vertices, move the depth.
        assert!(figures.near_preclipped_error < 4.0, "{figures:?}");
    }
}

/// Wine's wined3d way, independent of the probe: the smallest `units` (by bisection) for which a
/// quad drawn with `glPolygonOffset(0, −units)` under `GL_LESS` wins every pixel over the same
/// quad drawn plainly. Stored values are rounded, so one quantum of offset always suffices and
/// half a quantum never does: the answer is `1/r` to within the bisection's step.
fn wine_style_units(gl: &mut Gl, format: DepthFormat) -> f64 {
    gl.set_target(64, 64, format).unwrap();
    let identity: [f32; 16] = [
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.,
    ];
    // depth varies along x, so the pixels sample every position within a quantum
    let quad = Quad {
        corners: [
            [-1.0, -1.0, -0.2],
            [1.0, -1.0, 0.2],
            [1.0, 1.0, 0.2],
            [-1.0, 1.0, -0.2],
        ],
    };
    let mut lost = |units: f32| {
        gl.clear([0.0; 4], 1.0).unwrap();
        gl.draw_quad(
            &quad,
            &identity,
            [0.0, 0.0, 1.0, 1.0],
            &DrawState::default(),
        )
        .unwrap();
        let decal = DrawState {
            polygon_offset: Some((0.0, -units)),
            ..DrawState::default()
        };
        gl.draw_quad(&quad, &identity, [1.0, 0.0, 0.0, 1.0], &decal)
            .unwrap();
        64 * 64 - gl.read_color().unwrap().count([255, 0, 0, 255], None)
    };
    let (mut low, mut high) = (0.0f32, 4.0f32);
    assert_eq!(lost(high), 0, "{format:?}: 4 units must suffice");
    for _ in 0..10 {
        let middle = 0.5 * (low + high);
        if lost(middle) == 0 {
            high = middle;
        } else {
            low = middle;
        }
    }
    high as f64
}

/// The per-pixel bound `error_ulps·u·(1 + M)` the probe measured within 512 pixels of the
/// window origin, tried 2000 pixels away: a steep strip (depth 0.06 to 0.94 over 88 pixels) at
/// the right end of a 2048-pixel-wide D32F target, drawn with w = 1 so that its exact depth is
/// an affine function of x known in closed form. Returns the worst `|stored − exact| / (u·(1 + M))`
/// and the worst error in units of 2⁻²⁴.
fn far_strip_error(gl: &mut Gl) -> (f64, f64) {
    const WIDTH: usize = 2048;
    gl.set_target(WIDTH as u32, 8, DepthFormat::D32F).unwrap();
    let identity: [f32; 16] = [
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1.,
    ];
    // Dyadic corners: z is exactly affine in x on both triangles of the quad.
    let (x0, x1, z0, z1) = (0.90625f32, 0.9921875f32, -0.875f32, 0.875f32);
    let quad = Quad {
        corners: [[x0, -1.5, z0], [x1, -1.5, z1], [x1, 1.5, z1], [x0, 1.5, z0]],
    };
    let always = DrawState {
        depth_func: glow::ALWAYS,
        ..DrawState::default()
    };
    gl.clear([0.0; 4], 1.0).unwrap();
    gl.draw_quad(&quad, &identity, [1.0; 4], &always).unwrap();
    let depth = gl.read_depth().unwrap();
    let slope = (z1 - z0) as f64 / (x1 - x0) as f64;
    let window = |xw: f64| {
        let xn = 2.0 * xw / WIDTH as f64 - 1.0;
        0.5 * (z0 as f64 + (xn - x0 as f64) * slope) + 0.5
    };
    let (w0, gx) = (window(0.0), window(1.0) - window(0.0));
    let u = 2f64.powi(-24);
    let (mut ratio, mut worst) = (0.0f64, 0.0f64);
    // pixel centres at least a pixel inside the strip
    let first = ((x0 as f64 + 1.0) * WIDTH as f64 / 2.0).ceil() as usize + 1;
    let last = ((x1 as f64 + 1.0) * WIDTH as f64 / 2.0).floor() as usize - 2;
    for x in first..=last {
        let xw = x as f64 + 0.5;
        let error = (depth[4 * WIDTH + x] as f64 - window(xw)).abs();
        let magnitude = w0.abs() + gx.abs() * xw;
        ratio = ratio.max(error / (u * (1.0 + magnitude)));
        worst = worst.max(error / u);
    }
    (ratio, worst)
}

/// Odd values for everything the probe touches, set through glow.
unsafe fn set_odd_state(g: &glow::Context) -> (glow::Framebuffer, glow::VertexArray, glow::Buffer) {
    let fbo = g.create_framebuffer().unwrap();
    let vao = g.create_vertex_array().unwrap();
    let buffer = g.create_buffer().unwrap();
    g.bind_framebuffer(glow::DRAW_FRAMEBUFFER, Some(fbo));
    g.bind_vertex_array(Some(vao));
    g.bind_buffer(glow::ARRAY_BUFFER, Some(buffer));
    g.viewport(3, 5, 17, 19);
    g.depth_range_f64(0.125, 0.875);
    g.depth_func(glow::GREATER);
    g.depth_mask(false);
    g.clear_depth_f64(0.25);
    g.enable(glow::POLYGON_OFFSET_FILL);
    g.polygon_offset(1.5, -2.5);
    g.enable(glow::CULL_FACE);
    g.enable(glow::SCISSOR_TEST);
    g.enable(glow::DEPTH_CLAMP);
    g.enable(glow::CLIP_DISTANCE0 + 3);
    g.enable(glow::POLYGON_SMOOTH);
    g.disable(glow::DEPTH_TEST);
    g.pixel_store_i32(glow::PACK_ALIGNMENT, 1);
    g.pixel_store_i32(glow::PACK_ROW_LENGTH, 7);
    g.pixel_store_i32(glow::PACK_SKIP_ROWS, 2);
    // A multisampled texture on unit 0 with another unit active, multisampling off and the
    // sample mask on: the multisampled line measurement binds unit 0 and turns both its way.
    let texture = g.create_texture().unwrap();
    g.active_texture(glow::TEXTURE0);
    g.bind_texture(glow::TEXTURE_2D_MULTISAMPLE, Some(texture));
    g.active_texture(glow::TEXTURE3);
    g.disable(glow::MULTISAMPLE);
    g.enable(glow::SAMPLE_MASK);
    (fbo, vao, buffer)
}

/// Everything [`set_odd_state`] set, read back.
unsafe fn state(g: &glow::Context) -> Vec<String> {
    let mut viewport = [0; 4];
    g.get_parameter_i32_slice(glow::VIEWPORT, &mut viewport);
    let mut range = [0.0f32; 2];
    g.get_parameter_f32_slice(glow::DEPTH_RANGE, &mut range);
    let enabled = [
        glow::POLYGON_OFFSET_FILL,
        glow::CULL_FACE,
        glow::SCISSOR_TEST,
        glow::DEPTH_CLAMP,
        glow::DEPTH_TEST,
        glow::STENCIL_TEST,
        glow::RASTERIZER_DISCARD,
        glow::CLIP_DISTANCE0 + 3,
        glow::POLYGON_SMOOTH,
        glow::MULTISAMPLE,
        glow::SAMPLE_MASK,
    ]
    .map(|cap| g.is_enabled(cap));
    let active = g.get_parameter_i32(glow::ACTIVE_TEXTURE);
    g.active_texture(glow::TEXTURE0);
    let unit0 = g.get_parameter_i32(glow::TEXTURE_BINDING_2D_MULTISAMPLE);
    g.active_texture(active as u32);
    let ints = [
        glow::DRAW_FRAMEBUFFER_BINDING,
        glow::READ_FRAMEBUFFER_BINDING,
        glow::RENDERBUFFER_BINDING,
        glow::CURRENT_PROGRAM,
        glow::VERTEX_ARRAY_BINDING,
        glow::ARRAY_BUFFER_BINDING,
        glow::PIXEL_PACK_BUFFER_BINDING,
        glow::DEPTH_FUNC,
        glow::PACK_ALIGNMENT,
        glow::PACK_ROW_LENGTH,
        glow::PACK_SKIP_ROWS,
        glow::PACK_SKIP_PIXELS,
        glow::CLIP_ORIGIN,
        glow::CLIP_DEPTH_MODE,
    ]
    .map(|p| g.get_parameter_i32(p));
    let floats = [
        glow::DEPTH_CLEAR_VALUE,
        glow::POLYGON_OFFSET_FACTOR,
        glow::POLYGON_OFFSET_UNITS,
    ]
    .map(|p| g.get_parameter_f32(p));
    let mask = g.get_parameter_bool(glow::DEPTH_WRITEMASK);
    vec![
        format!("viewport {viewport:?} depth range {range:?}"),
        format!("enabled {enabled:?}"),
        format!("ints {ints:?}"),
        format!("floats {floats:?} depth mask {mask}"),
        format!("active texture {active:#x}, unit 0's multisampled texture {unit0}"),
    ]
}

/// The real glEnable, for [`failing_read_pixels`].
static GL_ENABLE: AtomicUsize = AtomicUsize::new(0);

/// A glReadPixels that raises GL_INVALID_ENUM (through glEnable(0xFFFF)) and reads nothing.
extern "system" fn failing_read_pixels(
    _: i32,
    _: i32,
    _: i32,
    _: i32,
    _: u32,
    _: u32,
    _: *mut c_void,
) {
    let enable = GL_ENABLE.load(Ordering::SeqCst);
    // SAFETY: GL_ENABLE holds glEnable's address, stored before the probe runs.
    let enable: extern "system" fn(u32) = unsafe { std::mem::transmute(enable) };
    enable(0xFFFF);
}

/// Compatibility-profile state that would spoil the probe if it were left on: an alpha test
/// that discards everything, and a depth scale and bias applied to every depth readback.
const ODD_FIXED_FUNCTION_STATE: (bool, [f32; 2]) = (true, [0.5, 0.25]);
const GL_ALPHA_TEST: u32 = 0x0BC0;
const GL_NEVER: u32 = 0x0200;
const GL_DEPTH_SCALE: u32 = 0x0D1E;
const GL_DEPTH_BIAS: u32 = 0x0D1F;

fn set_odd_fixed_function_state(gl: &Gl) {
    // SAFETY: compatibility-profile entry points of the current context, by their C types.
    unsafe {
        let alpha_func: extern "system" fn(u32, f32) =
            std::mem::transmute(gl.proc_address("glAlphaFunc"));
        let transfer: extern "system" fn(u32, f32) =
            std::mem::transmute(gl.proc_address("glPixelTransferf"));
        gl.glow().enable(GL_ALPHA_TEST);
        alpha_func(GL_NEVER, 0.0);
        transfer(GL_DEPTH_SCALE, ODD_FIXED_FUNCTION_STATE.1[0]);
        transfer(GL_DEPTH_BIAS, ODD_FIXED_FUNCTION_STATE.1[1]);
    }
}

unsafe fn fixed_function_state(gl: &Gl) -> (bool, [f32; 2]) {
    let g = gl.glow();
    let transfer = [GL_DEPTH_SCALE, GL_DEPTH_BIAS].map(|p| g.get_parameter_f32(p));
    (g.is_enabled(GL_ALPHA_TEST), transfer)
}

#[test]
fn the_callers_state_is_restored() {
    for kind in [Profile::Core, Profile::Compatibility] {
        let mut gl = context(kind);
        gl.clip_control(ClipDepth::ZeroToOne).unwrap();
        let g = gl.glow();
        // SAFETY: the context is current on this thread.
        let clean = measured(&gl);
        let before = unsafe {
            set_odd_state(g);
            if kind == Profile::Compatibility {
                set_odd_fixed_function_state(&gl);
            }
            assert_eq!(g.get_error(), glow::NO_ERROR);
            state(g)
        };
        let odd = measured(&gl);
        let after = unsafe { state(g) };
        assert_eq!(before, after, "{kind:?}");
        if kind == Profile::Compatibility {
            assert_eq!(
                unsafe { fixed_function_state(&gl) },
                ODD_FIXED_FUNCTION_STATE
            );
        }
        // The odd state changes nothing the probe measures.
        assert_eq!(
            (odd.snapping, odd.resolvable, odd.near_clip),
            (clean.snapping, clean.resolvable, clean.near_clip),
            "{kind:?}"
        );
        // Bit for bit (NaN where a format is not measured).
        assert_eq!(
            odd.plane_error.map(f64::to_bits),
            clean.plane_error.map(f64::to_bits),
            "{kind:?}"
        );
        assert_eq!(
            unsafe { g.get_error() },
            glow::NO_ERROR,
            "{kind:?}: the probe left a GL error"
        );
        // The same after a probe that fails halfway: its glReadPixels raises a GL error, after
        // the probe has changed the state and made its objects.
        GL_ENABLE.store(gl.proc_address("glEnable") as usize, Ordering::SeqCst);
        let failing = |name: &CStr| {
            if name == c"glReadPixels" {
                failing_read_pixels as *const c_void
            } else {
                gl.proc_address(name.to_str().unwrap())
            }
        };
        // SAFETY: as above; the replacement has glReadPixels's signature.
        let e = unsafe { probe(failing) }.unwrap_err();
        assert!(e.detail().contains("glReadPixels"), "{}", e.detail());
        assert_eq!(
            unsafe { g.get_error() },
            glow::NO_ERROR,
            "{kind:?}: error left pending"
        );
        assert_eq!(before, unsafe { state(g) }, "{kind:?} after an error");
    }
}

#[test]
fn errors_name_what_failed() {
    let gl = context(Profile::Core);
    for missing in [
        c"glReadPixels",
        c"glPolygonOffset",
        c"glCheckFramebufferStatus",
    ] {
        let without = |name: &CStr| {
            if name == missing {
                std::ptr::null()
            } else {
                gl.proc_address(name.to_str().unwrap())
            }
        };
        // SAFETY: the context is current; NULL is allowed.
        let e = unsafe { probe(without) }.unwrap_err();
        assert_eq!(e.kind(), ErrorKind::Gl);
        assert!(
            e.detail().contains(missing.to_str().unwrap()),
            "{missing:?}: {}",
            e.detail()
        );
    }
    // A GL error the caller left pending is reported, not blamed on a probe step.
    unsafe { gl.glow().enable(0xFFFF) };
    let e = unsafe { probe(loader(&gl)) }.unwrap_err();
    assert!(e.detail().contains("pending"), "{}", e.detail());
    // Optional entry points (glClipControl, viewport arrays) may be missing.
    let without_optional = |name: &CStr| {
        if name == c"glClipControl" || name == c"glViewportIndexedf" {
            std::ptr::null()
        } else {
            gl.proc_address(name.to_str().unwrap())
        }
    };
    assert!(unsafe { probe(without_optional) }.is_ok());
}

unsafe extern "C" fn egl_loader(name: *const c_char, user: *mut c_void) -> ZshiftGlProc {
    let gl = &*(user as *const Gl);
    let address = gl.proc_address(CStr::from_ptr(name).to_str().unwrap());
    // SAFETY: a non-NULL address is a GL entry point; the probe casts it to its real type.
    (!address.is_null())
        .then(|| std::mem::transmute::<*const c_void, unsafe extern "C" fn()>(address))
}

unsafe extern "C" fn null_loader(_: *const c_char, _: *mut c_void) -> ZshiftGlProc {
    None
}

#[test]
fn the_c_entry_point_checks_pointers_and_leaves_out_untouched_on_error() {
    let gl = context(Profile::Core);
    let user = &gl as *const Gl as *mut c_void;
    let mut worst = std::mem::MaybeUninit::<ZshiftProfile>::uninit();
    assert_eq!(zshift_profile_worst_case(worst.as_mut_ptr()), ZSHIFT_OK);
    assert_eq!(
        zshift_profile_worst_case(std::ptr::null_mut()),
        ZSHIFT_ERR_NULL_POINTER
    );
    let worst = unsafe { worst.assume_init() };
    // Debug formatting: NaN entries (not measured) compare equal that way.
    let same = |a: &RasterizerProfile, b: &RasterizerProfile| format!("{a:?}") == format!("{b:?}");
    assert!(same(
        &worst.to_profile().unwrap(),
        &RasterizerProfile::worst_case()
    ));
    // A sentinel byte pattern: on error `out` must keep every byte.
    let mut out: ZshiftProfile =
        unsafe { std::mem::transmute([0xABu8; std::mem::size_of::<ZshiftProfile>()]) };
    let bytes = |p: &ZshiftProfile| format!("{p:?}");
    let sentinel = bytes(&out);
    unsafe {
        assert_eq!(zshift_probe(None, user, &mut out), ZSHIFT_ERR_NULL_POINTER);
        assert_eq!(
            zshift_probe(Some(egl_loader), user, std::ptr::null_mut()),
            ZSHIFT_ERR_NULL_POINTER
        );
        assert_eq!(
            zshift_probe(Some(null_loader), user, &mut out),
            ZSHIFT_ERR_GL
        );
        // The last-error detail names the first entry point the loader lacked.
        let detail = CStr::from_ptr(zshift_last_error()).to_str().unwrap();
        assert!(detail.contains("glGetError"), "{detail}");
        assert_eq!(bytes(&out), sentinel, "out written on error");
        assert_eq!(zshift_probe(Some(egl_loader), user, &mut out), ZSHIFT_OK);
    }
    let rust = measured(&gl);
    let mut c = out.to_profile().unwrap();
    c.probe_seconds = rust.probe_seconds;
    assert!(same(&c, &rust), "{c:?} vs {rust:?}");
    assert_eq!(out.measured, 1);
    // -1 unsnapped (llvmpipe), else the bits the rasterizer snaps to.
    let bits = match rust.snapping {
        Snapping::Unsnapped => -1,
        Snapping::SubpixelBits(b) => b as i32,
    };
    assert_eq!(out.subpixel_bits, bits);
    assert_eq!(out.near_clip, ZSHIFT_NEAR_CLIP_CLIPPED_F32);
    // A zero-filled record is refused, naming the field.
    let zero: ZshiftProfile = unsafe { std::mem::zeroed() };
    let e = zero.to_profile().unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Domain);
    assert!(e.detail().contains("near_clip"), "{}", e.detail());
}

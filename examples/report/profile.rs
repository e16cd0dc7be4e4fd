//! The rasterizer's measured profile (`zshift::probe`) and what it changes in the recommendation
//! on the near-clipped floor, for the report.

use std::ffi::{c_void, CStr};
use std::fmt::Write as _;

use zshift::probe::{probe_with_figures, Figures};
use zshift::projection::{projection, ClipDepth, Frustum};
use zshift::recommend::{
    decal_shape, recommend_clip, Base, DepthFormat, DepthTest, RasterizerProfile, Scene,
};
use zshift_harness::Gl;

/// The probe run in the report's own core context.
pub fn measure(gl: &Gl) -> Result<(RasterizerProfile, Figures), String> {
    let loader = |name: &CStr| -> *const c_void { gl.proc_address(name.to_str().unwrap_or("")) };
    // SAFETY: the harness's context is current on this thread and EGL returns its entry points.
    unsafe { probe_with_figures(loader) }.map_err(|e| format!("probe: {e}"))
}

/// One row of the floor table: convention and format, base, profile, recommended f32 steps of
/// the offset element (or the refusal).
struct Floor {
    kind: &'static str,
    base: &'static str,
    profile: &'static str,
    steps: Result<u32, String>,
}

/// The floor: glFrustum(±0.1, ±0.05625, 0.1, 1000), 256×144, the plane z = −10 − 0.5y,
/// decals 8–13 units away, base corners at ±1000 (clipped by the rasterizer) or cut to the
/// frustum in f64 first (`clip_to_frustum`: the base then lies inside); GL_LESS. `tests/gl_scenes.rs` (`the_issues_near_clipped_ground_holds`)
/// draws it and finds the smallest working offsets (27 steps raw, 2 cut, on `[−1, 1]` D24).
fn floors(probed: &RasterizerProfile) -> Vec<Floor> {
    let frustum = Frustum::new(-0.1, 0.1, -0.05625, 0.05625, 0.1, 1000.0).expect("a frustum");
    let ground: Vec<[f64; 3]> = [(-1e3, -1e3), (1e3, -1e3), (1e3, 1e3), (-1e3, 1e3)]
        .iter()
        .map(|&(x, y)| [x, y, -10.0 - 0.5 * y])
        .collect();
    let reach = ground
        .iter()
        .flat_map(|p| p.iter().map(|c| c.abs()))
        .fold(0.0, f64::max);
    let mut rows = Vec::new();
    for (kind, clip, format) in [
        ("[-1,1] D24", ClipDepth::NegOneToOne, DepthFormat::Unorm24),
        ("[0,1] D32F", ClipDepth::ZeroToOne, DepthFormat::Float32),
    ] {
        for (base_name, base) in [
            ("clipped by the rasterizer", Base::Clipped { reach }),
            ("cut by clip_to_frustum", Base::InsideFrustum),
        ] {
            for (profile_name, profile, corners) in [
                ("worst case", RasterizerProfile::worst_case(), false),
                ("probed", *probed, false),
                ("probed, decal corners", *probed, true),
            ] {
                let mut scene = Scene {
                    pipeline: Default::default(),
                    footprint: None,
                    frustum,
                    viewport: [256, 144],
                    format,
                    depth_range: [8.0, 13.0],
                    slope: 0.5,
                    exact_depth: false,
                    depth_test: DepthTest::Less,
                    base,
                    profile,
                };
                if corners {
                    // The decal of tests/gl_scenes.rs: x from −0.6 to 0.5, y from −4 to 6.
                    let decal = [(-0.6f32, -4.0f32), (0.5, -4.0), (0.5, 6.0), (-0.6, 6.0)]
                        .map(|(x, y)| glam::Vec3::new(x, y, -10.0 - 0.5 * y));
                    let shape = decal_shape(&frustum, clip, scene.viewport, &decal)
                        .expect("the floor's decal");
                    scene.depth_range = shape.depth_range;
                    scene.slope = shape.slope;
                    scene.footprint = Some(shape.footprint);
                }
                let steps = recommend_clip(&scene, clip)
                    .map_err(|e| e.to_string())
                    .and_then(|r| {
                        let plain = projection(&frustum, clip).map_err(|e| e.to_string())?;
                        Ok(r.matrix[10].to_bits().abs_diff(plain[10].to_bits()))
                    });
                rows.push(Floor {
                    kind,
                    base: base_name,
                    profile: profile_name,
                    steps,
                });
            }
        }
    }
    rows
}

/// The report's section: the probed profile and the near-clipped floor.
pub fn section(w: &mut String, profile: &RasterizerProfile, figures: &Figures) {
    let _ = writeln!(w, "## The rasterizer's measured profile (zshift::probe)\n");
    let _ = writeln!(
        w,
        "Measured in the report's own context in {:.1} ms ({}). Snapping: {:?} (GL_SUBPIXEL_BITS \
         {}); near-plane clipping: {:?} ({:.1} D24 quanta off as clipped by GL, {:.1} clipped in \
         f64 first).\n",
        profile.probe_seconds * 1e3,
        figures.renderer,
        profile.snapping,
        figures.subpixel_bits,
        profile.near_clip,
        figures.near_clip_error,
        figures.near_preclipped_error
    );
    let _ = writeln!(
        w,
        "| format | r (quanta) | plane_error (quanta; D32F 2⁻²⁴) | facing decal [−1,1] | facing decal [0,1] |"
    );
    let _ = writeln!(w, "|---|---|---|---|---|");
    for (i, name) in ["D16", "D24", "D32", "D32F"].iter().enumerate() {
        let _ = writeln!(
            w,
            "| {name} | {:.3} | {:.2} | {:.2} | {:.2} |",
            profile.resolvable[i],
            profile.plane_error[i],
            profile.facing_quanta[i],
            profile.facing_quanta_zero_to_one[i]
        );
    }
    let _ = writeln!(
        w,
        "\nerror_ulps {:.3} (reversed Z {:.3}), plane_error_reversed {:.2}, facing decal under \
         reversed Z (D32F, relative ε in 2⁻²⁴) {:.2}; D32 (UNORM) is not measured (NaN: the \
         worst case). The recommendation takes snapping, r, near-plane clipping, error_ulps (its \
         per-quad error) and the facing figures from it (README, \"The rasterizer probe\").\n",
        profile.error_ulps,
        profile.error_ulps_reversed,
        profile.plane_error_reversed,
        profile.facing_reversed
    );
    let _ = writeln!(
        w,
        "### The near-clipped floor\n\nglFrustum(±0.1, ±0.05625, 0.1, 1000), 256×144, floor z = −10 − \
         0.5y with corners at ±1000, decals 8–13 units away, GL_LESS: the recommended offset in f32 \
         steps of element 10 (`tests/gl_scenes.rs` draws it: no pixel lost at any of these; the \
         smallest working offset on `[−1, 1]` D24 is 27 steps raw, 2 cut).\n"
    );
    let _ = writeln!(w, "| convention | base | profile | recommended steps |");
    let _ = writeln!(w, "|---|---|---|---|");
    for row in floors(profile) {
        let steps = match row.steps {
            Ok(k) => k.to_string(),
            Err(e) => format!("refused: {e}"),
        };
        let _ = writeln!(
            w,
            "| {} | {} | {} | {steps} |",
            row.kind, row.base, row.profile
        );
    }
    let _ = writeln!(w);
}

//! How wide GL draws a line asked `w` pixels wide, against the width the model takes
//! (`max(w, ⌊w + ½⌋)`: GL rounds an aliased line's width to the nearest integer, OpenGL 4.6
//! compatibility profile, 14.5.2.1).

use zshift::lines::{recommend, EdgeMethod, Edges, FaceSlope, LineKind};
use zshift::precision::DepthFormat as Format;
use zshift::projection::{projection, ClipDepth, Frustum};
use zshift::recommend::RasterizerProfile;
use zshift_harness::edges::drawn_width;
use zshift_harness::{flat_colour_pipeline, DepthFormat, Gl, Profile};

/// Passes clip coordinates through: the line's ends are given in NDC.
const VERTEX_SHADER: &str = "#version 330 core
layout(location = 0) in vec3 p;
void main() { gl_Position = vec4(p, 1.0); }
";

/// A horizontal `GL_LINES` segment, and a triangle's side in polygon mode, at widths between
/// integers and at four sub-pixel heights,
/// the rows it covers counted in one column of a 64² target: never more than the width the
/// model takes (GL's rule as the harness states it, [`drawn_width`], not read from the
/// library), and the library's
/// worst-case line reach is at least `(rows + 1)/2` (half the drawn width and half a pixel of
/// freedom). Printed: the rows per width (llvmpipe: 1.5, 2.5 and 3.5 draw 2, 3 and 4 rows, 2.4
/// two).
#[test]
fn a_line_is_drawn_no_wider_than_the_model_takes_it() {
    let mut gl =
        Gl::new(Profile::Compatibility).unwrap_or_else(|e| panic!("no OpenGL context: {e}"));
    gl.set_target(64, 64, DepthFormat::D24)
        .unwrap_or_else(|e| panic!("{e}"));
    // SAFETY: the harness's context is current on this thread.
    let (program, vao, vbo) =
        unsafe { flat_colour_pipeline(gl.glow(), VERTEX_SHADER) }.unwrap_or_else(|e| panic!("{e}"));
    let mut failures = Vec::new();
    for (w, outline) in [1.0f32, 1.5, 2.0, 2.4, 2.5, 2.6, 3.0, 3.5, 4.5]
        .into_iter()
        .flat_map(|w| [(w, false), (w, true)])
    {
        let taken = drawn_width(w);
        let mut drawn = Vec::new();
        for y in [20.0f32, 20.25, 20.5, 20.75] {
            gl.clear([0.0; 4], 1.0).unwrap_or_else(|e| panic!("{e}"));
            let ndc = y / 32.0 - 1.0;
            // GL_LINES: the segment; polygon mode: a triangle whose lowest side is that segment
            // (its other sides meet the column far above it).
            let ends: Vec<u8> = [-0.9f32, ndc, 0.0, 0.9, ndc, 0.0, 0.0, 0.9, 0.0]
                .iter()
                .flat_map(|v| v.to_ne_bytes())
                .collect();
            // SAFETY: as above; the pipeline's objects belong to this context.
            unsafe {
                use glow::HasContext;
                let g = gl.glow();
                g.disable(glow::DEPTH_TEST);
                g.use_program(Some(program));
                let at = g.get_uniform_location(program, "color");
                g.uniform_4_f32(at.as_ref(), 1.0, 1.0, 1.0, 1.0);
                g.bind_vertex_array(Some(vao));
                g.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
                g.buffer_data_u8_slice(glow::ARRAY_BUFFER, &ends, glow::STREAM_DRAW);
                g.line_width(w);
                if outline {
                    g.polygon_mode(glow::FRONT_AND_BACK, glow::LINE);
                    g.draw_arrays(glow::TRIANGLES, 0, 3);
                    g.polygon_mode(glow::FRONT_AND_BACK, glow::FILL);
                } else {
                    g.draw_arrays(glow::LINES, 0, 2);
                }
                g.line_width(1.0);
            }
            gl.check("a wide line").unwrap_or_else(|e| panic!("{e}"));
            let image = gl.read_color().unwrap_or_else(|e| panic!("{e}"));
            // Rows of the lowest side only: the triangle's others cross the column near y 60.
            let rows = (0..48).filter(|&r| image.at(32, r)[0] > 0).count();
            if rows as f64 > taken {
                failures.push(format!(
                    "glLineWidth({w}) at y {y}: {rows} rows, the model takes {taken}"
                ));
            }
            drawn.push(rows);
        }
        let mut edges = Edges::new([64, 64], Format::Unorm24, [10.0, 20.0]);
        edges.line_width = f64::from(w);
        if outline {
            edges.kind = LineKind::PolygonMode;
        }
        edges.face_slope = FaceSlope::WindowGradient(1e-4);
        edges.profile = RasterizerProfile::worst_case();
        let clip = ClipDepth::NegOneToOne;
        let m = projection(
            &Frustum::new(-0.5, 0.5, -0.5, 0.5, 1.0, 100.0).unwrap(),
            clip,
        )
        .unwrap();
        let reach = recommend(&m, clip, &edges, EdgeMethod::Matrix)
            .unwrap_or_else(|e| panic!("{e}"))
            .line_reach;
        let widest = *drawn.iter().max().expect("four heights") as f64;
        if reach < (widest + 1.0) / 2.0 {
            failures.push(format!(
                "glLineWidth({w}): {widest} rows drawn, line reach {reach}"
            ));
        }
        let kind = if outline { "polygon mode" } else { "GL_LINES" };
        println!(
            "glLineWidth({w}) {kind}: rows {drawn:?}, the model takes {taken}, line reach {reach}"
        );
        assert!(
            drawn.iter().all(|&r| r > 0),
            "glLineWidth({w}) drew nothing"
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

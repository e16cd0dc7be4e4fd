//! The report's PNG plots (plotters, bitmap backend; text through the system's sans-serif font).

use std::path::Path;

use plotters::prelude::*;

use crate::steps::Curve;

/// One method's point: mean frame time (ms) and error (% of decal pixels wrong).
pub struct MethodPoint {
    pub label: String,
    pub frame_ms: f64,
    pub error_pct: f64,
    /// Lost pixels over visible decal pixels, and bleed over hidden ones, % (all scenes).
    pub lost_pct: f64,
    pub bleed_pct: f64,
    /// Scenes where the method got every counted pixel right.
    pub scenes_clean: usize,
}

fn palette(i: usize) -> RGBColor {
    const C: [RGBColor; 12] = [
        RGBColor(228, 26, 28),
        RGBColor(55, 126, 184),
        RGBColor(77, 175, 74),
        RGBColor(152, 78, 163),
        RGBColor(255, 127, 0),
        RGBColor(166, 86, 40),
        RGBColor(247, 129, 191),
        RGBColor(90, 90, 90),
        RGBColor(23, 190, 207),
        RGBColor(188, 189, 34),
        RGBColor(0, 0, 128),
        RGBColor(128, 0, 0),
    ];
    C[i % C.len()]
}

/// Error against run time, a point per method.
pub fn error_vs_time(path: &Path, points: &[MethodPoint], title: &str) -> Result<(), String> {
    let root = BitMapBackend::new(path, (1100, 700)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let x_max = points.iter().map(|p| p.frame_ms).fold(0.0, f64::max) * 1.05;
    let x_min = points.iter().map(|p| p.frame_ms).fold(f64::MAX, f64::min) * 0.95;
    let y_max = points.iter().map(|p| p.error_pct).fold(1.0, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(x_min..x_max, -0.02 * y_max..y_max)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc("median time per frame, ms (mean over scenes)")
        .y_desc("decal pixels wrong, % (lost + bleed-through)")
        .label_style(("sans-serif", 15))
        .draw()
        .map_err(|e| e.to_string())?;
    for (i, p) in points.iter().enumerate() {
        let color = palette(i);
        let marker = if i % 2 == 0 { 0 } else { 1 };
        chart
            .draw_series(std::iter::once((p.frame_ms, p.error_pct)).map(|xy| {
                if marker == 0 {
                    Circle::new(xy, 7, color.filled()).into_dyn()
                } else {
                    TriangleMarker::new(xy, 8, color.filled()).into_dyn()
                }
            }))
            .map_err(|e| e.to_string())?
            .label(format!(
                "{} ({:.2} ms, {:.1}%)",
                p.label, p.frame_ms, p.error_pct
            ))
            .legend(move |(x, y)| {
                if marker == 0 {
                    Circle::new((x + 8, y), 5, color.filled()).into_dyn()
                } else {
                    TriangleMarker::new((x + 8, y), 6, color.filled()).into_dyn()
                }
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::MiddleRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// Depth step against distance, log-log, a curve per convention.
pub fn depth_steps(path: &Path, curves: &[Curve], title: &str) -> Result<(), String> {
    let root = BitMapBackend::new(path, (1100, 700)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let all = curves.iter().flat_map(|c| c.points.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, 0.0f64, f64::MAX, 0.0f64);
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        if y > 0.0 {
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
    }
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d((x0..x1).log_scale(), (y0 * 0.5..y1 * 2.0).log_scale())
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc("eye distance d")
        .y_desc("depth step at d (eye-space units)")
        .label_style(("sans-serif", 15))
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .x_label_formatter(&|x| format!("{x:.0e}"))
        .draw()
        .map_err(|e| e.to_string())?;
    for (i, c) in curves.iter().enumerate() {
        let color = palette(i);
        // Wide strokes first, so a curve that coincides with a later one still shows.
        let width = if i < 2 { 6 } else { 2 };
        chart
            .draw_series(LineSeries::new(
                c.points.iter().copied().filter(|&(_, y)| y > 0.0),
                color.stroke_width(width),
            ))
            .map_err(|e| e.to_string())?
            .label(c.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(width))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

//! The demonstration's pictures: renders laid side by side with labels and counts in a tiny
//! built-in bitmap font, written as PNG or as the frames of an animated GIF.

use std::path::Path;

use zshift_harness::Image;

use crate::scene::{percent, Comparison, SIZE};

/// An RGB picture, top row first.
pub struct Picture {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<[u8; 3]>,
}

pub const BACKGROUND: [u8; 3] = [52, 52, 60];
const TEXT: [u8; 3] = [235, 235, 235];
const DIM: [u8; 3] = [160, 160, 165];
const GOOD: [u8; 3] = [90, 220, 110];
const BAD: [u8; 3] = [255, 110, 90];
/// The outline drawn around where the decal belongs.
pub const OUTLINE: [u8; 3] = [255, 225, 0];
/// Gap between panels and around them, and the text scale (each font pixel is SCALE² pixels).
const GAP: usize = 16;
const SCALE: usize = 2;
const LINE: usize = 9 * SCALE;

impl Picture {
    pub fn new(width: usize, height: usize) -> Picture {
        Picture {
            width,
            height,
            pixels: vec![BACKGROUND; width * height],
        }
    }

    /// A render (rows bottom-up, as `glReadPixels` gives them) as a picture of its own size.
    pub fn from_image(image: &Image) -> Picture {
        let mut p = Picture::new(image.width, image.height);
        p.blit(image, 0, 0);
        p
    }

    /// `top` above `bottom`, left-aligned, on the background colour.
    pub fn stacked(top: &Picture, bottom: &Picture) -> Picture {
        let mut p = Picture::new(top.width.max(bottom.width), top.height + bottom.height);
        p.paste(top, 0, 0);
        p.paste(bottom, 0, top.height);
        p
    }

    /// Copies `part` with its top-left at `(x, y)` (clipped to this picture).
    pub fn paste(&mut self, part: &Picture, x: usize, y: usize) {
        for row in 0..part.height {
            for col in 0..part.width {
                self.set(x + col, y + row, part.pixels[row * part.width + col]);
            }
        }
    }

    fn set(&mut self, x: usize, y: usize, color: [u8; 3]) {
        if x < self.width && y < self.height {
            self.pixels[y * self.width + x] = color;
        }
    }

    /// Copies a render (rows bottom-up, as `glReadPixels` gives them) with its top-left at `(x, y)`.
    pub fn blit(&mut self, image: &Image, x: usize, y: usize) {
        for row in 0..image.height {
            for col in 0..image.width {
                let [r, g, b, _] = image.at(col, image.height - 1 - row);
                self.set(x + col, y + row, [r, g, b]);
            }
        }
    }

    /// Marks the pixels just outside `mask` (a `side × side` mask, rows bottom-up like a render
    /// placed at `(x, y)`) in [`OUTLINE`]: where the decal belongs, without covering any of its
    /// pixels.
    pub fn outline(&mut self, mask: &[bool], side: usize, x: usize, y: usize) {
        let inside = |c: isize, r: isize| {
            (0..side as isize).contains(&c)
                && (0..side as isize).contains(&r)
                && mask[r as usize * side + c as usize]
        };
        for r in 0..side as isize {
            for c in 0..side as isize {
                let near = [(-1, 0), (1, 0), (0, -1), (0, 1)]
                    .iter()
                    .any(|&(dc, dr)| inside(c + dc, r + dr));
                if !inside(c, r) && near {
                    self.set(x + c as usize, y + side - 1 - r as usize, OUTLINE);
                }
            }
        }
    }

    /// Writes `text` (upper-case letters, digits, a few signs) with its top-left at `(x, y)`.
    pub fn text(&mut self, x: usize, y: usize, text: &str, color: [u8; 3]) {
        for (i, c) in text.chars().enumerate() {
            let rows = glyph(c.to_ascii_uppercase());
            for (dy, bits) in rows.iter().enumerate() {
                for dx in 0..5 {
                    if bits & (0x10 >> dx) != 0 {
                        for (sx, sy) in (0..SCALE).flat_map(|a| (0..SCALE).map(move |b| (a, b))) {
                            self.set(x + (i * 6 + dx) * SCALE + sx, y + dy * SCALE + sy, color);
                        }
                    }
                }
            }
        }
    }

    /// Writes the picture as an RGB PNG.
    pub fn write_png(&self, path: &Path) -> Result<(), String> {
        let file = std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut encoder = png::Encoder::new(
            std::io::BufWriter::new(file),
            self.width as u32,
            self.height as u32,
        );
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let data: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        encoder
            .write_header()
            .and_then(|mut w| w.write_image_data(&data))
            .map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// The width of `text` in pixels.
fn text_width(text: &str) -> usize {
    text.chars().count() * 6 * SCALE
}

/// One labelled render of a picture made by [`compose_panels`].
pub struct Panel {
    /// The render, as it is to appear.
    pub picture: Picture,
    /// Two label lines over it: a head (bright) and a sub-line (dim).
    pub label: [String; 2],
    /// Count lines under it, each with whether it is good (green) or not (red).
    pub counts: Vec<(String, bool)>,
}

/// Lays a comparison out: `title` lines on top, then each method's render between its two label
/// lines and its lost / bled counts (green when 0, red otherwise), then `footer` lines.
pub fn compose(c: &Comparison, title: &[String], footer: &[String]) -> Picture {
    let side = SIZE as usize;
    let panels: Vec<Panel> = c
        .rows
        .iter()
        .map(|row| {
            let mut picture = Picture::from_image(&row.image);
            picture.outline(&c.decal, side, 0, 0);
            Panel {
                picture,
                label: row.method.label.map(String::from),
                counts: vec![
                    count_line("LOST", row.lost, c.visible, 0),
                    count_line("BLED", row.bled, c.covered, 0),
                ],
            }
        })
        .collect();
    compose_panels(&panels, panels.len(), title, footer)
}

/// A panel's count line, `WHAT n (p%)` with `decimals` digits of the percentage of `of`, and
/// whether it is good (`n == 0`, drawn green).
pub fn count_line(what: &str, n: usize, of: usize, decimals: usize) -> (String, bool) {
    (
        format!("{what} {n} ({:.decimals$}%)", percent(n, of)),
        n == 0,
    )
}

/// Lays `panels` (all the same size, the same number of count lines) out `columns` to a row:
/// `title` lines on top, then each panel between its two label lines and its counts, then
/// `footer` lines.
pub fn compose_panels(
    panels: &[Panel],
    columns: usize,
    title: &[String],
    footer: &[String],
) -> Picture {
    let (w, h) = panels
        .first()
        .map_or((0, 0), |p| (p.picture.width, p.picture.height));
    let counts = panels.first().map_or(0, |p| p.counts.len());
    let rows = panels.len().div_ceil(columns.max(1));
    let width = columns * w + (columns + 1) * GAP;
    let top = GAP + title.len() * LINE + GAP;
    // One row: two label lines, the panels, their count lines.
    let block = 2 * LINE + GAP / 2 + h + GAP + counts * LINE + GAP;
    let height = top + rows * block + footer.len() * LINE + GAP;
    let mut p = Picture::new(width, height);
    for (i, line) in title.iter().enumerate() {
        p.text(GAP, GAP + i * LINE, line, TEXT);
    }
    for (i, panel) in panels.iter().enumerate() {
        let x = GAP + (i % columns) * (w + GAP);
        let label_top = top + (i / columns) * block;
        let panel_top = label_top + 2 * LINE + GAP / 2;
        let centre = |t: &str| x + w.saturating_sub(text_width(t)) / 2;
        let [head, sub] = &panel.label;
        p.text(centre(head), label_top, head, TEXT);
        p.text(centre(sub), label_top + LINE, sub, DIM);
        p.paste(&panel.picture, x, panel_top);
        for (j, (text, good)) in panel.counts.iter().enumerate() {
            let color = if *good { GOOD } else { BAD };
            p.text(centre(text), panel_top + h + GAP + j * LINE, text, color);
        }
    }
    for (i, line) in footer.iter().enumerate() {
        p.text(GAP, top + rows * block + i * LINE, line, DIM);
    }
    p
}

/// Writes `frames` (all the same size) as a looping GIF, `delay` hundredths of a second each.
/// The pictures are flat colours, so each frame's palette is its exact colours (at most 256).
pub fn write_gif(path: &Path, frames: &[Picture], delay: u16) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let first = frames.first().ok_or("no frames")?;
    let file = std::fs::File::create(path).map_err(|e| err(&e))?;
    let (w, h) = (first.width as u16, first.height as u16);
    let mut encoder =
        gif::Encoder::new(std::io::BufWriter::new(file), w, h, &[]).map_err(|e| err(&e))?;
    encoder
        .set_repeat(gif::Repeat::Infinite)
        .map_err(|e| err(&e))?;
    for picture in frames {
        let mut palette: Vec<[u8; 3]> = Vec::new();
        let mut indices = Vec::with_capacity(picture.pixels.len());
        for px in &picture.pixels {
            let index = match palette.iter().position(|c| c == px) {
                Some(i) => i,
                None if palette.len() < 256 => {
                    palette.push(*px);
                    palette.len() - 1
                }
                None => return Err(err(&"more than 256 colours in a frame")),
            };
            indices.push(index as u8);
        }
        let flat: Vec<u8> = palette.iter().flatten().copied().collect();
        let mut frame = gif::Frame::from_palette_pixels(w, h, indices, flat, None);
        frame.delay = delay;
        encoder.write_frame(&frame).map_err(|e| err(&e))?;
    }
    Ok(())
}

/// A 5×7 glyph, one byte per row, top row first, bit 4 the leftmost pixel. Characters the font
/// lacks draw as a small box.
fn glyph(c: char) -> [u8; 7] {
    match c {
        ' ' => [0; 7],
        '0' => [0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E],
        '1' => [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E],
        '2' => [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F],
        '3' => [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E],
        '4' => [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02],
        '5' => [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E],
        '6' => [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E],
        '7' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08],
        '8' => [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E],
        '9' => [0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C],
        'A' => [0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11],
        'B' => [0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E],
        'C' => [0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E],
        'D' => [0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C],
        'E' => [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F],
        'F' => [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10],
        'G' => [0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F],
        'H' => [0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11],
        'I' => [0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E],
        'J' => [0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C],
        'K' => [0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11],
        'L' => [0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F],
        'M' => [0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11],
        'N' => [0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11],
        'O' => [0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'P' => [0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10],
        'Q' => [0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D],
        'R' => [0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11],
        'S' => [0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E],
        'T' => [0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04],
        'U' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E],
        'V' => [0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04],
        'W' => [0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A],
        'X' => [0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11],
        'Y' => [0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04],
        'Z' => [0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F],
        '-' => [0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00],
        '+' => [0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00],
        '=' => [0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00],
        '.' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C],
        ',' => [0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08],
        ':' => [0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00],
        ';' => [0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x04, 0x08],
        '(' => [0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02],
        ')' => [0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08],
        '/' => [0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00],
        '%' => [0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03],
        '_' => [0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F],
        '<' => [0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02],
        '>' => [0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08],
        '\'' => [0x04, 0x04, 0x08, 0x00, 0x00, 0x00, 0x00],
        _ => [0x00, 0x1F, 0x11, 0x11, 0x11, 0x1F, 0x00],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two frames with text and flat colours come back from the GIF pixel for pixel.
    #[test]
    fn gif_round_trip() {
        let mut frames = Vec::new();
        for (k, colour) in [[242, 38, 26], [51, 89, 230]].into_iter().enumerate() {
            let mut p = Picture::new(40, 20);
            p.text(1, 1, &format!("LOST {k}"), colour);
            frames.push(p);
        }
        assert_ne!(frames[0].pixels, frames[1].pixels);
        let path = std::env::temp_dir().join(format!("zshift-demo-{}.gif", std::process::id()));
        write_gif(&path, &frames, 10).unwrap();
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options
            .read_info(std::fs::File::open(&path).unwrap())
            .unwrap();
        for picture in &frames {
            let frame = decoder.read_next_frame().unwrap().expect("a frame");
            let rgb: Vec<[u8; 3]> = frame
                .buffer
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2]])
                .collect();
            assert_eq!(rgb, picture.pixels);
        }
        assert!(decoder.read_next_frame().unwrap().is_none());
        std::fs::remove_file(path).unwrap();
    }
}

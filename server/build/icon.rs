//! The home-screen icons, drawn at build time: the page's favicon (a
//! white and a black checker on wood, `web-client/assets/favicon.svg`)
//! rasterised at any size as a PNG, the checkers shrunk into the middle so
//! a launcher that crops the icon to a circle ("maskable") keeps them
//! whole. Each pixel averages 4x4 samples, so the edges are smooth.

/// One shape of the picture, in the favicon's 64-unit square.
enum Shape {
    /// The whole square.
    Fill,
    /// A disc: centre and radius.
    Disc(f32, f32, f32),
    /// A ring: centre, inner and outer radius.
    Ring(f32, f32, f32, f32),
}

/// The picture, painted in order (the favicon's shapes).
const PICTURE: [(Shape, [u8; 3]); 6] = [
    (Shape::Fill, [0x9e, 0x66, 0x38]),
    (Shape::Disc(25.0, 27.0, 17.0), [0x1a, 0x15, 0x12]),
    (Shape::Ring(25.0, 27.0, 9.0, 11.0), [0x55, 0x50, 0x4c]),
    (Shape::Disc(40.0, 40.0, 18.0), [0xc7, 0xb8, 0x9e]),
    (Shape::Disc(40.0, 40.0, 16.0), [0xf5, 0xee, 0xd9]),
    (Shape::Ring(40.0, 40.0, 9.0, 11.0), [0xc7, 0xb8, 0x9e]),
];

/// How much the checkers shrink about the middle (into a maskable
/// icon's safe circle, 80 % of the width).
const SHRINK: f32 = 0.78;

/// The colour at (`x`, `y`) in favicon units.
fn colour_at(x: f32, y: f32) -> [u8; 3] {
    // Undo the shrink about the middle, so the shapes read in their own units.
    let (u, v) = (32.0 + (x - 32.0) / SHRINK, 32.0 + (y - 32.0) / SHRINK);
    let mut c = [0; 3];
    for (shape, colour) in &PICTURE {
        let inside = match *shape {
            Shape::Fill => true,
            Shape::Disc(cx, cy, r) => (u - cx).hypot(v - cy) <= r,
            Shape::Ring(cx, cy, r0, r1) => (r0..=r1).contains(&(u - cx).hypot(v - cy)),
        };
        if inside {
            c = *colour;
        }
    }
    c
}

/// The icon as RGB pixels, `size` x `size`.
pub fn pixels(size: u32) -> Vec<u8> {
    const SAMPLES: u32 = 4;
    let unit = 64.0 / size as f32;
    let mut out = Vec::with_capacity((size * size * 3) as usize);
    for py in 0..size {
        for px in 0..size {
            let mut sum = [0u32; 3];
            for sy in 0..SAMPLES {
                for sx in 0..SAMPLES {
                    let x = (px as f32 + (sx as f32 + 0.5) / SAMPLES as f32) * unit;
                    let y = (py as f32 + (sy as f32 + 0.5) / SAMPLES as f32) * unit;
                    for (s, c) in sum.iter_mut().zip(colour_at(x, y)) {
                        *s += u32::from(c);
                    }
                }
            }
            out.extend(sum.map(|s| (s / (SAMPLES * SAMPLES)) as u8));
        }
    }
    out
}

/// The icon as a PNG file, `size` x `size`.
pub fn png(size: u32) -> Result<Vec<u8>, png::EncodingError> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, size, size);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Best);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(&pixels(size))?;
    writer.finish()?;
    Ok(bytes)
}

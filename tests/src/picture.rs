//! Screenshots as pictures: decoding WebDriver's PNG and telling a drawn
//! scene from a blank page (one flat colour, as when WebGL failed and only
//! the page's background shows).

use crate::{E2eError, Result};

/// What a screenshot holds, in numbers.
#[derive(Debug, Clone)]
pub struct Stats {
    pub width: u32,
    pub height: u32,
    /// Distinct RGB colours.
    pub colours: usize,
    /// The most common colour and the share of pixels it covers (0 to 1).
    pub dominant: [u8; 3],
    pub dominant_share: f64,
}

impl Stats {
    /// Pixels not of the dominant colour, as a share.
    pub fn drawn_share(&self) -> f64 {
        1.0 - self.dominant_share
    }

    /// `Err` unless at least `min_colours` colours show and at least
    /// `min_drawn` of the pixels differ from the dominant colour.
    pub fn check_drawn(&self, what: &str, min_colours: usize, min_drawn: f64) -> Result<()> {
        if self.colours >= min_colours && self.drawn_share() >= min_drawn {
            Ok(())
        } else {
            Err(E2eError::Check(format!(
                "the {what} screenshot looks blank: {self}; wanted at least {min_colours} \
                 colours and {:.2}% of pixels off the dominant colour",
                min_drawn * 100.0
            )))
        }
    }
}

impl std::fmt::Display for Stats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [r, g, b] = self.dominant;
        write!(
            f,
            "{}x{}, {} colours, #{r:02x}{g:02x}{b:02x} covers {:.2}%",
            self.width,
            self.height,
            self.colours,
            self.dominant_share * 100.0
        )
    }
}

/// Decodes a PNG (any bit depth, palette or not) and counts its colours.
pub fn stats(png_bytes: &[u8]) -> Result<Stats> {
    let bad = |e: png::DecodingError| E2eError::Check(format!("screenshot is not a PNG: {e}"));
    let mut decoder = png::Decoder::new(png_bytes);
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(bad)?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).map_err(bad)?;
    let channels = match info.color_type {
        png::ColorType::Rgba => 4,
        png::ColorType::Rgb => 3,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Grayscale => 1,
        png::ColorType::Indexed => {
            return Err(E2eError::Check("palette left unexpanded".into()));
        }
    };
    // One counter per 24-bit colour, zeroed lazily by the allocator (only
    // the pages of colours that occur are touched), and the colour count
    // and the most common colour kept as the pixels go by: this crate is
    // built without optimisation for tests, where hashing each pixel of a
    // 3-megapixel screenshot took seconds.
    let mut counts = vec![0u32; 1 << 24];
    let (mut colours, mut dominant, mut most) = (0usize, [0u8; 3], 0u32);
    let pixels = &buf[..info.buffer_size()];
    for px in pixels.chunks_exact(channels) {
        let rgb = if channels >= 3 {
            [px[0], px[1], px[2]]
        } else {
            [px[0], px[0], px[0]]
        };
        let count =
            &mut counts[usize::from(rgb[0]) << 16 | usize::from(rgb[1]) << 8 | usize::from(rgb[2])];
        *count += 1;
        if *count == 1 {
            colours += 1;
        }
        if *count > most {
            (most, dominant) = (*count, rgb);
        }
    }
    let total = (info.width as usize * info.height as usize).max(1);
    Ok(Stats {
        width: info.width,
        height: info.height,
        colours,
        dominant,
        dominant_share: f64::from(most) / total as f64,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn encode(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut enc = png::Encoder::new(&mut out, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().unwrap();
        w.write_image_data(rgb).unwrap();
        drop(w);
        out
    }

    #[test]
    fn a_flat_picture_is_blank_and_a_drawn_one_is_not() {
        let flat = encode(10, 10, &[40, 30, 24].repeat(100));
        let s = stats(&flat).unwrap();
        assert_eq!((s.colours, s.dominant), (1, [40, 30, 24]));
        assert!(s.check_drawn("flat", 2, 0.001).is_err());

        let mut drawn = [40u8, 30, 24].repeat(100);
        for (i, px) in drawn.chunks_exact_mut(3).take(20).enumerate() {
            px.copy_from_slice(&[i as u8 * 10, 200, 100]);
        }
        let s = stats(&encode(10, 10, &drawn)).unwrap();
        assert_eq!(s.colours, 21);
        assert!((s.drawn_share() - 0.2).abs() < 1e-9);
        s.check_drawn("drawn", 8, 0.1).unwrap();
    }
}

//! The finished picture and PNG encoding.

use std::path::Path;

use crate::{RenderError, Rgba};

/// An 8-bit sRGB RGBA picture with straight alpha, rows top to bottom.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    data: Vec<u8>,
}

impl Image {
    /// A picture from raw RGBA rows; `None` if the length does not match.
    pub fn from_rgba(width: u32, height: u32, data: Vec<u8>) -> Option<Image> {
        let len = (width as usize)
            .checked_mul(height as usize)?
            .checked_mul(4)?;
        (data.len() == len).then_some(Image {
            width,
            height,
            data,
        })
    }

    /// The caller guarantees `data.len() == width · height · 4`.
    pub(crate) fn from_parts(width: u32, height: u32, data: Vec<u8>) -> Image {
        debug_assert_eq!(data.len(), width as usize * height as usize * 4);
        Image {
            width,
            height,
            data,
        }
    }

    /// The picture's width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// The picture's height in pixels (the number of rows).
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The RGBA bytes, row by row from the top.
    pub fn pixels(&self) -> &[u8] {
        &self.data
    }

    /// The RGBA bytes, row by row from the top.
    pub fn into_rgba(self) -> Vec<u8> {
        self.data
    }

    /// The pixel at column `x`, row `y` (from the top), or `None` outside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<Rgba> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 4;
        let p = self.data.get(i..i + 4)?;
        Some([p[0], p[1], p[2], p[3]])
    }

    /// Whether every pixel is opaque.
    pub fn is_opaque(&self) -> bool {
        self.data.chunks_exact(4).all(|p| p[3] == 255)
    }

    /// Encodes the picture as a PNG file (8-bit sRGB; RGB when opaque,
    /// else RGBA). Deterministic: the same picture gives the same bytes.
    pub fn encode_png(&self) -> Result<Vec<u8>, RenderError> {
        let err = |e: png::EncodingError| RenderError::Png(e.to_string());
        let mut out = Vec::new();
        let opaque = self.is_opaque();
        {
            let mut enc = png::Encoder::new(&mut out, self.width, self.height);
            enc.set_color(if opaque {
                png::ColorType::Rgb
            } else {
                png::ColorType::Rgba
            });
            enc.set_depth(png::BitDepth::Eight);
            enc.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
            let mut writer = enc.write_header().map_err(err)?;
            if opaque {
                let rgb: Vec<u8> = self
                    .data
                    .chunks_exact(4)
                    .flat_map(|p| [p[0], p[1], p[2]])
                    .collect();
                writer.write_image_data(&rgb).map_err(err)?;
            } else {
                writer.write_image_data(&self.data).map_err(err)?;
            }
            writer.finish().map_err(err)?;
        }
        Ok(out)
    }

    /// Encodes the picture as PNG and writes it to `path`.
    pub fn write_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let path = path.as_ref();
        let bytes = self.encode_png()?;
        std::fs::write(path, bytes).map_err(|e| RenderError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(bytes: &[u8]) -> (png::OutputInfo, Vec<u8>) {
        let dec = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = dec.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        buf.truncate(info.buffer_size());
        (info, buf)
    }

    #[test]
    fn png_round_trip_opaque_and_transparent() {
        let mut data = Vec::new();
        for i in 0..6u8 {
            data.extend_from_slice(&[i * 40, 255 - i * 40, i, 255]);
        }
        let img = Image::from_rgba(3, 2, data.clone()).unwrap();
        assert_eq!(img.pixel(2, 1), Some([200, 55, 5, 255]));
        assert_eq!(img.pixel(3, 0), None);
        let (info, buf) = decode(&img.encode_png().unwrap());
        assert_eq!((info.width, info.height), (3, 2));
        assert_eq!(info.color_type, png::ColorType::Rgb);
        let rgb: Vec<u8> = data.chunks(4).flat_map(|p| [p[0], p[1], p[2]]).collect();
        assert_eq!(buf, rgb);

        data[3] = 0;
        let img = Image::from_rgba(3, 2, data.clone()).unwrap();
        let (info, buf) = decode(&img.encode_png().unwrap());
        assert_eq!(info.color_type, png::ColorType::Rgba);
        assert_eq!(buf, data);
        assert!(Image::from_rgba(3, 3, data).is_none());
    }

    #[test]
    fn write_png_reports_bad_paths() {
        let img = Image::from_rgba(1, 1, vec![1, 2, 3, 255]).unwrap();
        let e = img
            .write_png("/nonexistent-dir/for/sure/x.png")
            .unwrap_err();
        assert!(matches!(e, RenderError::Io { .. }), "{e}");
    }
}

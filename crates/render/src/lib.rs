//! # holey-render: pictures of meshes
//!
//! A small, deterministic CPU rasterizer that turns a [`PolyMesh`] into an
//! RGBA picture in the style of a modeler's viewport (TopMod's
//! screenshots): faceted flat shading of a pale material, optional black
//! edges along the polygon boundaries, a neutral background.
//!
//! ```
//! use holey_render::{render, RenderOptions, View};
//! let cube = holey_shapes::parse_primitive("@cube").unwrap();
//! let opts = RenderOptions { width: 200, height: 150, edges: true, ..RenderOptions::default() };
//! let image = render(&cube, &opts).unwrap();
//! assert_eq!((image.width(), image.height()), (200, 150));
//! let png = image.encode_png().unwrap();
//! assert_eq!(&png[1..4], b"PNG");
//! assert_eq!(View::parse("1,-1,0.5").unwrap(), View::Direction(glam::DVec3::new(1.0, -1.0, 0.5)));
//! ```
//!
//! ## Pipeline
//!
//! 1. **Preparation** ([`prep`]): the mesh's structure is checked (bad
//!    offsets or vertex indices are a [`RenderError::Mesh`]); vertices
//!    with a non-finite coordinate are unusable and every face touching
//!    one is skipped, as are faces with fewer than three corners. The
//!    remaining vertices are mapped by a similarity transform into the
//!    unit ball around the centre of their bounding box, so every later
//!    tolerance is relative to the model's size and coordinates as large
//!    as `1e308` do not overflow. Each face gets its Newell normal
//!    (Σ (yᵢ − yᵢ₊₁)(zᵢ + zᵢ₊₁), … : twice the vector area, exact for
//!    planar polygons and a good average for non-planar ones).
//! 2. **Camera** ([`camera`]): perspective, looking at the model along the
//!    [`View`] direction with up = +z (or +y, see [`Up`]). The distance
//!    is chosen so the bounding sphere fills [`FILL`] (85 %) of the
//!    shorter image side; [`Framing::Fit`] then zooms and shifts the lens
//!    so the projected vertices themselves fill 85 % of the picture.
//! 3. **Rasterization** ([`raster`]): every polygon is fan-triangulated
//!    from its first corner and scan-converted into a supersampled
//!    buffer (`supersample`² samples per pixel, stored in 32 × 32-sample
//!    tiles for memory locality) with exact integer edge functions on a
//!    1/256-sample grid and a z-buffer of 1/z (screen-linear under
//!    perspective). Faces seen from the front are drawn before faces seen
//!    from behind, so on closed models hidden back faces fail the depth
//!    test before any shading; with interpolated shading and large
//!    triangles a depth pre-pass makes every visible sample shaded once.
//!    Triangles crossing the near plane or far outside the picture are
//!    clipped.
//! 4. **Shading** ([`shade`]): two-sided; a face whose normal points away
//!    from the eye is lit with its normal flipped and drawn in the
//!    [`RenderOptions::back_color`] tint, so inside-out regions and the
//!    inside of holes read at a glance. The tint fades out for faces seen
//!    nearly edge-on (fully tinted from 30° off edge-on), which keeps the
//!    slivers of back faces that every closed polygon mesh shows along its
//!    silhouette from looking like errors. Lights are fixed to the camera
//!    (key light from the upper left, fill light from the lower right,
//!    sky/ground ambient, a faint highlight), computed in linear light.
//! 5. **Edges**: drawn after all faces, along polygon boundaries only
//!    (never along fan diagonals), as lines of
//!    [`RenderOptions::edge_width`] pixels with square caps. A point of an
//!    edge is visible when a sample next to it shows one of the edge's
//!    faces or the background, or failing that when nothing there lies
//!    more than a small tolerance in front of it. Edges shorter than
//!    [`raster::FADE_START`] pixels on screen are not drawn and edges
//!    shorter than [`raster::FADE_FULL`] are drawn partly transparent, so
//!    a dense mesh shows its shape instead of a black blanket (and
//!    foreshortened edges do not pile up along silhouettes).
//! 6. **Resolve** (end of [`raster`]): samples are averaged in linear light
//!    (premultiplied alpha) and converted to 8-bit sRGB; [`Image`] encodes
//!    PNG.
//!
//! Everything runs on one thread in a fixed order, so the same mesh and
//! options give byte-identical pixels and PNG files on every run.
//!
//! ## Limits
//!
//! Sides must be 1..=[`MAX_SIDE`] pixels and the picture at most
//! [`MAX_PIXELS`] pixels; the supersampling factor is lowered
//! automatically so the sample buffers stay below [`MAX_SAMPLES`]
//! samples (8 bytes each, 12 with edges). Fan triangulation fills
//! non-convex polygons incorrectly (it is exact for convex and
//! star-shaped-from-the-first-corner polygons, which covers the meshes
//! holey makes).
//!
//! ## Speed
//!
//! The cost is a per-sample part (buffers, background, resolve: about
//! 2.8 million samples for 640 × 480 at the default 3 × 3 supersampling)
//! plus a per-triangle part. Measured single-threaded, release build, on
//! a shared 2-core machine: a 10k-triangle torus at 640 × 480 in 20–40 ms
//! (7–11 ms with `supersample: 1`, 18–27 ms with 2), a million triangles
//! at 1024 × 768 in 0.2–0.5 s flat and 0.6–0.9 s smooth. For animation
//! frames use `supersample: 2` and freeze the camera with [`frame`] and
//! [`Framing::Fixed`] so the picture does not jump as the model changes.

#![warn(missing_docs)]

pub mod camera;
pub mod image;
pub mod prep;
pub mod raster;
pub mod shade;

#[cfg(test)]
mod tests;

use glam::DVec3;
use holey_mesh::PolyMesh;

pub use camera::{Camera, FILL, Framing, Up, View, frame};
pub use image::Image;

/// An sRGB colour.
pub type Rgb = [u8; 3];
/// An sRGB colour with straight (not premultiplied) alpha.
pub type Rgba = [u8; 4];

/// The largest accepted width or height, in pixels.
pub const MAX_SIDE: u32 = 16_384;
/// The largest accepted picture, in pixels (8192 × 8192).
pub const MAX_PIXELS: u64 = 1 << 26;
/// The most samples (pixels × supersample²) the renderer allocates; above
/// it the supersampling factor is lowered.
pub const MAX_SAMPLES: u64 = 1 << 27;
/// The largest accepted supersampling factor (samples per pixel side).
pub const MAX_SUPERSAMPLE: u32 = 8;

/// Everything that can go wrong while rendering.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// The requested width or height is 0.
    #[error("the picture must be at least 1×1 pixels, not {width}×{height}")]
    ZeroSize {
        /// The requested width in pixels.
        width: u32,
        /// The requested height in pixels.
        height: u32,
    },
    /// A side exceeds [`MAX_SIDE`] or the picture exceeds [`MAX_PIXELS`].
    #[error(
        "a {width}×{height} picture is too large: each side may be at most {max_side} pixels \
         and the picture at most {max_pixels} pixels"
    )]
    TooLarge {
        /// The requested width in pixels.
        width: u32,
        /// The requested height in pixels.
        height: u32,
        /// The largest accepted side in pixels ([`MAX_SIDE`]).
        max_side: u32,
        /// The largest accepted width × height in pixels ([`MAX_PIXELS`]).
        max_pixels: u64,
    },
    /// [`parse_size`] could not read a `WIDTHxHEIGHT` size.
    #[error("bad size {text:?}: {reason} (expected WIDTHxHEIGHT, e.g. 800x600)")]
    Size {
        /// The text as given.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A view is neither a known name nor a usable `x,y,z` direction
    /// ([`View::parse`], [`View::direction`]).
    #[error(
        "bad view {text:?}: {reason} (expected iso, front, back, left, right, top, bottom or a \
         direction x,y,z toward the camera, e.g. 1,-1,0.5)"
    )]
    View {
        /// The text as given, or the direction's components written as `x,y,z`.
        text: String,
        /// What is wrong with it.
        reason: String,
    },
    /// [`Up::parse`] got something other than `z`, `+z`, `y` or `+y`.
    #[error("bad up axis {text:?} (expected z or y)")]
    Up {
        /// The text as given.
        text: String,
    },
    /// A field of [`RenderOptions`] is out of its range.
    #[error("bad option {name}: {reason}")]
    Option {
        /// The field's name, e.g. `"edge_width"`.
        name: &'static str,
        /// The value given and the range it misses.
        reason: String,
    },
    /// No camera can be set up: a fixed [`Camera`] has non-finite or
    /// out-of-range values, or the line of sight is degenerate; the text says which.
    #[error("bad camera: {0}")]
    Camera(String),
    /// The mesh's face offsets or vertex indices are inconsistent; the text
    /// says where.
    #[error("the mesh is malformed: {0}")]
    Mesh(String),
    /// [`render_with_colors`] got a colour list whose length differs from
    /// the mesh's number of faces or vertices.
    #[error("{kind} colours: the mesh has {expected} {kind}s but {got} colours were given")]
    ColorCount {
        /// What the colours are for: `"face"` or `"vertex"`.
        kind: &'static str,
        /// How many faces or vertices the mesh has.
        expected: usize,
        /// How many colours were given.
        got: usize,
    },
    /// The PNG encoder failed; the text is its message.
    #[error("PNG encoding failed: {0}")]
    Png(String),
    /// Writing the PNG file failed.
    #[error("cannot write {path}: {message}")]
    Io {
        /// The file that could not be written.
        path: String,
        /// The operating system's error message.
        message: String,
    },
}

/// The picture's background.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Background {
    /// One colour; `Solid([0, 0, 0, 0])` is transparent.
    Solid(Rgba),
    /// A vertical gradient, opaque.
    Gradient {
        /// Colour of the top row.
        top: Rgb,
        /// Colour of the bottom row; rows in between blend linearly in sRGB.
        bottom: Rgb,
    },
}

impl Background {
    /// A fully transparent background.
    pub const TRANSPARENT: Background = Background::Solid([0, 0, 0, 0]);
    /// The default: a soft neutral grey gradient, lighter at the top.
    pub const DEFAULT: Background = Background::Gradient {
        top: [200, 206, 214],
        bottom: [138, 145, 155],
    };
}

impl Default for Background {
    fn default() -> Self {
        Background::DEFAULT
    }
}

/// Per-face or per-vertex colours for [`render_with_colors`] (parity
/// fields, selection highlights). Back faces show a mix of the given colour
/// and [`RenderOptions::back_color`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Colors<'a> {
    /// One colour per face, in face order.
    PerFace(&'a [Rgb]),
    /// One colour per vertex, interpolated across faces.
    PerVertex(&'a [Rgb]),
}

/// How to draw a picture. [`RenderOptions::default`] is an 800×600 iso
/// view, flat shaded, without edges.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Width in pixels, 1..=[`MAX_SIDE`].
    pub width: u32,
    /// Height in pixels, 1..=[`MAX_SIDE`].
    pub height: u32,
    /// Direction the model is seen from.
    pub view: View,
    /// Which world axis points up on screen.
    pub up: Up,
    /// How the camera is placed.
    pub framing: Framing,
    /// Draw polygon edges.
    pub edges: bool,
    /// Edge line width in pixels, in (0, 16].
    pub edge_width: f64,
    /// Edge colour.
    pub edge_color: Rgb,
    /// Smooth (Phong) shading with angle-weighted vertex normals instead
    /// of flat faceted shading.
    pub smooth: bool,
    /// With `smooth`, faces meeting at more than this angle (degrees,
    /// 0..=180) keep a sharp crease.
    pub crease_angle: f64,
    /// Background.
    pub background: Background,
    /// Material colour of front faces.
    pub color: Rgb,
    /// Material colour of back faces (seen from behind).
    pub back_color: Rgb,
    /// Samples per pixel side for anti-aliasing, 1..=[`MAX_SUPERSAMPLE`]
    /// (lowered automatically for huge pictures).
    pub supersample: u32,
    /// Field of view on the shorter side before framing, in degrees,
    /// (0, 120]; smaller is flatter.
    pub fov: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 800,
            height: 600,
            view: View::Iso,
            up: Up::Z,
            framing: Framing::Fit,
            edges: false,
            edge_width: 1.5,
            edge_color: [24, 24, 28],
            smooth: false,
            crease_angle: 60.0,
            background: Background::DEFAULT,
            color: [206, 208, 212],
            back_color: [232, 168, 104],
            supersample: 3,
            fov: 30.0,
        }
    }
}

impl RenderOptions {
    /// Checks every field and returns the supersampling factor that will
    /// actually be used.
    pub fn validate(&self) -> Result<u32, RenderError> {
        check_size(self.width, self.height)?;
        if !(self.edge_width.is_finite() && self.edge_width > 0.0 && self.edge_width <= 16.0) {
            return Err(RenderError::Option {
                name: "edge_width",
                reason: format!("{} is not in (0, 16] pixels", self.edge_width),
            });
        }
        if !(self.crease_angle.is_finite() && (0.0..=180.0).contains(&self.crease_angle)) {
            return Err(RenderError::Option {
                name: "crease_angle",
                reason: format!("{} is not in [0, 180] degrees", self.crease_angle),
            });
        }
        if !(self.fov.is_finite() && self.fov > 0.0 && self.fov <= 120.0) {
            return Err(RenderError::Option {
                name: "fov",
                reason: format!("{} is not in (0, 120] degrees", self.fov),
            });
        }
        if !(1..=MAX_SUPERSAMPLE).contains(&self.supersample) {
            return Err(RenderError::Option {
                name: "supersample",
                reason: format!("{} is not in 1..={MAX_SUPERSAMPLE}", self.supersample),
            });
        }
        self.view.direction(self.up)?;
        let pixels = u64::from(self.width) * u64::from(self.height);
        let mut ss = self.supersample;
        while ss > 1 && pixels * u64::from(ss * ss) > MAX_SAMPLES {
            ss -= 1;
        }
        Ok(ss)
    }
}

fn check_size(width: u32, height: u32) -> Result<(), RenderError> {
    if width == 0 || height == 0 {
        return Err(RenderError::ZeroSize { width, height });
    }
    if width > MAX_SIDE || height > MAX_SIDE || u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(RenderError::TooLarge {
            width,
            height,
            max_side: MAX_SIDE,
            max_pixels: MAX_PIXELS,
        });
    }
    Ok(())
}

/// Parses a picture size `WIDTHxHEIGHT` (`800x600`; `X` and `×` work
/// too, spaces around the numbers are ignored) and checks it against the
/// limits.
pub fn parse_size(text: &str) -> Result<(u32, u32), RenderError> {
    let bad = |reason: &str| RenderError::Size {
        text: text.to_owned(),
        reason: reason.to_owned(),
    };
    let mut parts = text.split(['x', 'X', '×']);
    let (Some(w), Some(h), None) = (parts.next(), parts.next(), parts.next()) else {
        return Err(bad("it needs exactly one 'x' between width and height"));
    };
    let num = |s: &str| -> Result<u32, RenderError> {
        let s = s.trim();
        if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
            return Err(bad(&format!("{s:?} is not a whole number of pixels")));
        }
        s.parse::<u32>()
            .map_err(|_| bad(&format!("{s} is far too large")))
    };
    let (w, h) = (num(w)?, num(h)?);
    check_size(w, h)?;
    Ok((w, h))
}

/// Renders `mesh` with the default pale material.
///
/// An empty mesh (or one with no drawable face) gives a picture of the
/// background. Errors: options out of range, a malformed mesh (offsets or
/// indices; non-finite positions are skipped instead).
pub fn render(mesh: &PolyMesh, opts: &RenderOptions) -> Result<Image, RenderError> {
    raster::render_impl(mesh, None, opts)
}

/// Renders `mesh` with a colour per face or per vertex instead of the
/// default material. The number of colours must match the mesh.
pub fn render_with_colors(
    mesh: &PolyMesh,
    colors: Colors<'_>,
    opts: &RenderOptions,
) -> Result<Image, RenderError> {
    let (kind, expected, got) = match colors {
        Colors::PerFace(c) => ("face", mesh.face_count(), c.len()),
        Colors::PerVertex(c) => ("vertex", mesh.positions.len(), c.len()),
    };
    if expected != got {
        return Err(RenderError::ColorCount {
            kind,
            expected,
            got,
        });
    }
    raster::render_impl(mesh, Some(colors), opts)
}

/// A unit vector, or `None` for zero, tiny or non-finite input.
pub(crate) fn unit(v: DVec3) -> Option<DVec3> {
    let len = v.length();
    (len.is_finite() && len > 1e-300).then(|| v / len)
}

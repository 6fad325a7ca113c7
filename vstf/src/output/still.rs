//! The file formats of a single image, chosen by the output's extension:
//! PNG and JPEG (8 bits a channel, the linear values quantised as the
//! golden images are), and OpenEXR (the linear radiance in 32-bit floats,
//! with the per-pixel output variables as further channels).

use crate::error::Error;
use std::path::Path;

/// How a single image is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StillFormat {
    /// 8-bit RGB PNG.
    Png,
    /// 8-bit RGB JPEG (lossy, quality [`JPEG_QUALITY`]).
    Jpeg,
    /// OpenEXR: linear radiance as float32 R, G, B, and the output
    /// variables when asked for.
    Exr,
}

/// The JPEG quality vstf writes (1 to 100).
pub const JPEG_QUALITY: u8 = 95;

/// What `--out` of a single image may name.
pub const STILL_EXTENSIONS: &str = ".png, .jpg (or .jpeg) or .exr";

impl StillFormat {
    /// The format named by `path`'s extension; an error naming the path and
    /// the formats vstf writes for any other.
    pub fn of(path: &Path) -> Result<StillFormat, Error> {
        match super::extension(path).as_deref() {
            Some("png") => Ok(StillFormat::Png),
            Some("jpg" | "jpeg") => Ok(StillFormat::Jpeg),
            Some("exr") => Ok(StillFormat::Exr),
            Some(ext @ ("mp4" | "webm" | "gif" | "apng")) => Err(Error::usage(format!(
                "--out {}: .{ext} is an animation (vstf animate writes it); one image is \
                 written as {STILL_EXTENSIONS}",
                path.display()
            ))),
            _ => Err(Error::usage(format!(
                "--out {}: vstf writes one image as {STILL_EXTENSIONS}; name the file so",
                path.display()
            ))),
        }
    }
}

/// Encodes an 8-bit RGB image as JPEG and writes it atomically.
pub fn write_jpeg(path: &Path, img: &image::RgbImage) -> Result<(), Error> {
    let mut bytes = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, JPEG_QUALITY)
        .encode_image(img)
        .map_err(|e| Error::io(path, format!("cannot encode JPEG: {e}")))?;
    super::write_atomic(path, &bytes)
        .map_err(|e| Error::io(path, format!("cannot write {}: {e}", path.display())))
}

/// Writes an 8-bit RGB image as PNG or JPEG, by `format` (an EXR is
/// written from the linear image, [`super::write_exr`]).
pub fn write_8bit(path: &Path, format: StillFormat, img: &image::RgbImage) -> Result<(), Error> {
    match format {
        StillFormat::Png => super::write_png(path, img),
        StillFormat::Jpeg => write_jpeg(path, img),
        StillFormat::Exr => Err(Error::usage(format!(
            "--out {}: an EXR holds the linear radiance of one view, not an 8-bit sheet",
            path.display()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_by_extension_and_clear_refusals() {
        assert_eq!(
            StillFormat::of(Path::new("a.PNG")).unwrap(),
            StillFormat::Png
        );
        assert_eq!(
            StillFormat::of(Path::new("a.jpeg")).unwrap(),
            StillFormat::Jpeg
        );
        assert_eq!(
            StillFormat::of(Path::new("d/a.Jpg")).unwrap(),
            StillFormat::Jpeg
        );
        assert_eq!(
            StillFormat::of(Path::new("a.exr")).unwrap(),
            StillFormat::Exr
        );
        let e = StillFormat::of(Path::new("a.tif")).unwrap_err().to_string();
        assert!(e.contains("--out a.tif") && e.contains(".exr"), "{e}");
        let e = StillFormat::of(Path::new("noext")).unwrap_err().to_string();
        assert!(e.contains("--out noext"), "{e}");
        let e = StillFormat::of(Path::new("a.mp4")).unwrap_err().to_string();
        assert!(e.contains("vstf animate"), "{e}");
    }

    #[test]
    fn a_jpeg_decodes_to_about_the_pixels_written() {
        let dir = std::env::temp_dir().join(format!("vstf-jpeg-{}", std::process::id()));
        let path = dir.join("a.jpg");
        let img = image::RgbImage::from_fn(16, 8, |x, _| image::Rgb([(x * 16) as u8, 128, 40]));
        write_jpeg(&path, &img).unwrap();
        let back = image::open(&path).unwrap().to_rgb8();
        assert_eq!(back.dimensions(), (16, 8));
        let worst = img
            .as_raw()
            .iter()
            .zip(back.as_raw())
            .map(|(a, b)| a.abs_diff(*b))
            .max()
            .unwrap();
        // Quality 95 on a smooth ramp: a few levels at most.
        assert!(worst <= 8, "worst difference {worst}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! OpenEXR output: the rendered image's linear radiance and, when asked
//! for, the per-pixel output variables ([`crate::aov`]) as further
//! channels of the same single-part scan-line image, every channel a
//! 32-bit float (half floats would keep only 3 significant digits of a lab
//! time), ZIP-compressed (lossless).
//!
//! Channels: `R`, `G`, `B`, the radiance, linear, exactly the values the
//! 8-bit PNG quantises (`round(255 * clamp(v, 0, 1))`), rounded to f32;
//! with the output variables: `event_t` (the lab time of the event seen,
//! the retarded time), `proper_time` (the object's own time there),
//! `doppler` (nu_camera / nu_surface), `searchlight` (D^4), `object` (the
//! object's index in the fixture's `objects`), `distance` (lab distance from
//! the camera at the camera time to the event) and `normal.X`, `normal.Y`,
//! `normal.Z` (lab unit normal, turned to the side the camera sees). Where
//! the pixel's ray meets nothing, `object` is -1 and every other output
//! variable is NaN; the radiance there is the background's.
//!
//! The header carries the camera time as a double (`vstfCameraT`, the one
//! custom attribute: the `exr` crate writes custom attributes in a hash
//! map's order, which would change the file's bytes from run to run if there
//! were more), so that lab times stored as f32 can be read relative to it,
//! and in its standard `comments` the fixture's name, the light-speed model
//! and the camera time; `software` is `vstf`.

use crate::aov::PixelAov;
use crate::error::Error;
use ::exr::prelude::{
    AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, Image, Layer, LayerAttributes,
    SmallVec, Text, WritableImage,
};
use std::path::Path;

/// What the header of an EXR says about the render it holds.
#[derive(Clone, Debug)]
pub struct ExrMeta {
    /// The fixture's name.
    pub fixture: String,
    /// The light-speed model, as `vstf render` prints it.
    pub model: String,
    /// The camera's lab time, t.units.
    pub camera_t: f64,
}

/// How one channel's value is read from a pixel's output variables.
pub type AovRead = fn(&PixelAov) -> f64;

/// The output variables' channels, in the order written (EXR sorts them by
/// name in the file), each with how it is read from a pixel's variables.
pub const AOV_CHANNELS: [(&str, AovRead); 9] = [
    ("event_t", |a| a.event_t),
    ("proper_time", |a| a.proper_time),
    ("doppler", |a| a.doppler),
    ("searchlight", |a| a.searchlight),
    ("object", |a| a.object as f64),
    ("distance", |a| a.distance),
    ("normal.X", |a| a.normal.x),
    ("normal.Y", |a| a.normal.y),
    ("normal.Z", |a| a.normal.z),
];

/// Writes `image` (and `aovs`, one per pixel in the same order, if given)
/// to `path` as an OpenEXR file, atomically.
pub fn write_exr(
    path: &Path,
    image: &renderer::Image,
    aovs: Option<&[PixelAov]>,
    meta: &ExrMeta,
) -> Result<(), Error> {
    let bytes = encode(image, aovs, meta).map_err(|e| Error::io(path, e))?;
    super::write_atomic(path, &bytes)
        .map_err(|e| Error::io(path, format!("cannot write {}: {e}", path.display())))
}

/// The EXR file's bytes.
fn encode(
    image: &renderer::Image,
    aovs: Option<&[PixelAov]>,
    meta: &ExrMeta,
) -> Result<Vec<u8>, String> {
    let (w, h) = (image.width as usize, image.height as usize);
    let channel = |name: &str, values: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(values));
    let mut channels: Vec<AnyChannel<FlatSamples>> = ["R", "G", "B"]
        .iter()
        .enumerate()
        .map(|(k, name)| channel(name, image.pixels.iter().map(|p| p[k] as f32).collect()))
        .collect();
    if let Some(aovs) = aovs {
        if aovs.len() != w * h {
            return Err(format!(
                "{} output variables for a {w}x{h} image",
                aovs.len()
            ));
        }
        for (name, read) in AOV_CHANNELS {
            channels.push(channel(name, aovs.iter().map(|a| read(a) as f32).collect()));
        }
    }
    let mut attributes = LayerAttributes::default();
    attributes.other.insert(
        Text::from("vstfCameraT"),
        AttributeValue::F64(meta.camera_t),
    );
    attributes.software_name = Some(Text::from("vstf"));
    attributes.comments = Some(latin1(&format!(
        "fixture {}, {} model, camera time {}",
        meta.fixture, meta.model, meta.camera_t
    )));
    let layer = Layer::new(
        (w, h),
        attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(channels)),
    );
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_layer(layer)
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| format!("cannot encode EXR: {e}"))?;
    Ok(bytes.into_inner())
}

/// `s` as EXR text (Latin-1), other characters as `?`.
fn latin1(s: &str) -> Text {
    let kept: String = s
        .chars()
        .map(|c| if u32::from(c) < 256 { c } else { '?' })
        .collect();
    Text::new_or_none(kept).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use ::exr::prelude::read_all_flat_layers_from_file;
    use glam::DVec3;

    /// A 2x1 image, one pixel hit and one not, written and read back by the
    /// `exr` crate (the independent reading is the command-line tests',
    /// with OpenImageIO).
    #[test]
    fn channels_and_the_header_round_trip() {
        let image = renderer::Image {
            width: 2,
            height: 1,
            pixels: vec![DVec3::new(0.25, 0.5, 1.5), DVec3::new(0.0, 0.0, 0.1)],
        };
        let hit = PixelAov {
            event_t: -9.5,
            proper_time: 1.25,
            doppler: 0.5,
            searchlight: 0.0625,
            object: 3,
            distance: 9.5,
            normal: DVec3::new(0.0, 0.6, 0.8),
        };
        let meta = ExrMeta {
            fixture: "ball ☉".into(),
            model: "relativistic".into(),
            camera_t: 1e9 + 0.125,
        };
        let dir = std::env::temp_dir().join(format!("vstf-exr-{}", std::process::id()));
        let path = dir.join("a.exr");
        write_exr(&path, &image, Some(&[hit, PixelAov::NOTHING]), &meta).unwrap();
        let read = read_all_flat_layers_from_file(&path).unwrap();
        let layer = &read.layer_data[0];
        let value = |name: &str, i: usize| {
            let c = layer
                .channel_data
                .list
                .iter()
                .find(|c| c.name == *name)
                .unwrap_or_else(|| panic!("no channel {name}"));
            match &c.sample_data {
                FlatSamples::F32(v) => v[i],
                other => panic!("{name}: {other:?}"),
            }
        };
        assert_eq!(
            [value("R", 0), value("G", 0), value("B", 0)],
            [0.25, 0.5, 1.5]
        );
        assert_eq!(value("event_t", 0), -9.5);
        assert_eq!(value("object", 0), 3.0);
        assert_eq!(value("object", 1), -1.0);
        assert!(value("event_t", 1).is_nan() && value("normal.Z", 1).is_nan());
        assert_eq!(value("normal.Z", 0), 0.8);
        let other = &layer.attributes.other;
        assert_eq!(
            other.get(&Text::from("vstfCameraT")),
            Some(&AttributeValue::F64(1e9 + 0.125))
        );
        assert_eq!(
            other.len(),
            1,
            "one custom attribute: a hash map's order is not fixed"
        );
        assert_eq!(
            layer.attributes.comments,
            Some(Text::from(
                "fixture ball ?, relativistic model, camera time 1000000000.125"
            ))
        );
        assert_eq!(layer.channel_data.list.len(), 12);
        // Without the output variables: the radiance only.
        write_exr(&path, &image, None, &meta).unwrap();
        let read = read_all_flat_layers_from_file(&path).unwrap();
        assert_eq!(read.layer_data[0].channel_data.list.len(), 3);
        // A count that is not the image's is refused, and nothing is written.
        let e = write_exr(&dir.join("b.exr"), &image, Some(&[hit]), &meta).unwrap_err();
        assert!(
            e.to_string().contains("1 output variables for a 2x1 image"),
            "{e}"
        );
        assert!(!dir.join("b.exr").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! The rendered image: linear RGB pixels, and their 8-bit form.

use glam::DVec3;
use wide::{f64x4, CmpEq, CmpGe};

/// Linear RGB pixels, row-major from the top left.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Image {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Linear RGB, `width * height` of them.
    pub pixels: Vec<DVec3>,
}

impl Image {
    /// 8 bits per channel, three bytes (R, G, B) a pixel, row-major from
    /// the top left; values are stored linearly (no sRGB curve) so that a
    /// pixel's value is proportional to the coverage of an edge.
    pub fn to_rgb8_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(3 * self.pixels.len());
        let mut quads = self.pixels.chunks_exact(4);
        for quad in &mut quads {
            out.extend_from_slice(&quad_bytes(quad));
        }
        for c in quads.remainder() {
            out.extend([c.x, c.y, c.z].map(channel_byte));
        }
        out
    }
}

/// 2^52: added to a double in [0, 2^52), it leaves that double's nearest
/// integer in the sum's low mantissa bits.
const ROUNDING: f64 = 4_503_599_627_370_496.0;

/// A linear channel value as a byte: clamped to [0, 1] (a NaN to 0),
/// scaled to [0, 255] and rounded to the nearest integer, halves up;
/// `(v.clamp(0.0, 1.0) * 255.0).round() as u8` to the bit. The rounding
/// adds 2^52, which rounds to the nearest integer, ties to even, with no
/// branch; a tie rounded down to the even integer below (x exactly a half
/// above it, a difference computed exactly) goes up by one.
#[inline(always)]
fn channel_byte(v: f64) -> u8 {
    let x = if v >= 0.0 { v.min(1.0) } else { 0.0 } * 255.0;
    let sum = x + ROUNDING;
    let nearest = sum.to_bits() as u8;
    nearest + u8::from(x - (sum - ROUNDING) == 0.5)
}

/// [`channel_byte`] of four pixels' twelve channels, in order, four
/// channels a vector: the same operations lane by lane (a comparison and a
/// select where the scalar form branches), so the same bytes.
#[inline(always)]
fn quad_bytes(quad: &[DVec3]) -> [u8; 12] {
    let [a, b, c, d] = [quad[0], quad[1], quad[2], quad[3]];
    let lanes = [
        f64x4::from([a.x, a.y, a.z, b.x]),
        f64x4::from([b.y, b.z, c.x, c.y]),
        f64x4::from([c.z, d.x, d.y, d.z]),
    ];
    let mut bytes = [0u8; 12];
    for (k, v) in lanes.into_iter().enumerate() {
        let (zero, rounding) = (f64x4::ZERO, f64x4::splat(ROUNDING));
        // A NaN fails the comparison and becomes 0, as in the scalar form.
        let x = v.cmp_ge(zero).blend(v.min(f64x4::ONE), zero) * f64x4::splat(255.0);
        let sum = x + rounding;
        let tie = (x - (sum - rounding)).cmp_eq(f64x4::splat(0.5));
        let (sum, tie) = (sum.to_array(), tie.to_array());
        for i in 0..4 {
            bytes[4 * k + i] = (sum[i].to_bits() as u8) + u8::from(tie[i].to_bits() != 0);
        }
    }
    bytes
}

#[cfg(test)]
mod tests {
    use super::{channel_byte, Image};

    /// `f64::round` on the clamped, scaled value: the definition.
    fn rounded(v: f64) -> u8 {
        (v.clamp(0.0, 1.0) * 255.0).round() as u8
    }

    /// The sum's rounding alone, ties to even, without the step up at ties
    /// (the controls' wrong rounding).
    fn ties_to_even(v: f64) -> u8 {
        let x = if v >= 0.0 { v.min(1.0) } else { 0.0 } * 255.0;
        (x + super::ROUNDING).to_bits() as u8
    }

    /// Channel values whose scaled value lies at or beside an integer or a
    /// half (the steps of `to_rgb8_bytes`), a sweep between, and values out
    /// of range or infinite.
    fn awkward_channels() -> Vec<f64> {
        let mut vs = vec![
            0.0,
            -0.0,
            1.0,
            f64::MIN_POSITIVE,
            1e-300,
            -1e-300,
            1.5,
            -3.0,
        ];
        vs.extend([f64::INFINITY, f64::NEG_INFINITY, 1.0f64.next_up()]);
        for k in 0..=510u32 {
            let x = f64::from(k) / 2.0;
            for scaled in [x.next_down(), x, x.next_up()] {
                let v = scaled / 255.0;
                vs.extend([v.next_down(), v, v.next_up()]);
            }
        }
        vs.extend((0..100_000).map(|i| f64::from(i) / 99_999.0));
        vs
    }

    /// Each of them, and NaN, gives the byte of `f64::round`.
    #[test]
    fn a_channel_byte_is_the_rounded_channel_at_every_half_and_integer() {
        for v in awkward_channels() {
            assert_eq!(channel_byte(v), rounded(v), "{v:e}");
        }
        assert_eq!(channel_byte(f64::NAN), 0);
        assert_eq!(channel_byte(-f64::NAN), 0);
    }

    /// Negative control: the sum's rounding alone (ties to even, without
    /// the step up) gives another byte at some of them: the scaled values
    /// that are an even integer and a half, exactly.
    #[test]
    fn ties_to_even_are_not_the_same_rounding() {
        let differ: Vec<f64> = (awkward_channels().into_iter())
            .filter(|&v| ties_to_even(v) != rounded(v))
            .collect();
        assert!(differ.len() > 10, "{}", differ.len());
        assert!(differ.iter().all(|&v| (v * 255.0 - 0.5) % 2.0 == 0.0));
    }

    /// An image of every awkward channel value, and NaNs, each falling in
    /// every lane of the four-pixel vectors in turn, gives each channel's
    /// byte of `f64::round` (0 for a NaN), the pixels past the last four
    /// included; the control: rounding ties to even, which the step up at
    /// ties corrects, would give other bytes for the same image.
    #[test]
    fn an_image_of_awkward_channels_gives_each_rounded_byte() {
        use glam::DVec3;
        let mut values = awkward_channels();
        values.extend([f64::NAN, -f64::NAN, 0.5 / 255.0]);
        for shift in 0..12 {
            let mut channels: Vec<f64> = vec![0.25; shift];
            channels.extend(&values);
            channels.resize(channels.len().div_ceil(3) * 3, 0.75);
            let pixels: Vec<DVec3> = channels.chunks_exact(3).map(DVec3::from_slice).collect();
            let image = Image {
                width: pixels.len() as u32,
                height: 1,
                pixels,
            };
            let round = |v: f64| if v.is_nan() { 0 } else { rounded(v) };
            let bytes = image.to_rgb8_bytes();
            assert_eq!(
                bytes,
                channels.iter().map(|&v| round(v)).collect::<Vec<u8>>(),
                "shift {shift}"
            );
            let even: Vec<u8> = channels.iter().map(|&v| ties_to_even(v)).collect();
            assert_ne!(bytes, even, "shift {shift}");
        }
    }

    /// A whole image: every pixel's three bytes in order, the pixels past
    /// the last four included; the control, one channel changed, differs.
    #[test]
    fn an_image_gives_each_pixels_rounded_bytes_in_order() {
        use glam::DVec3;
        let pixels: Vec<DVec3> = (0..4 * 7 + 3)
            .map(|i| {
                DVec3::new(
                    f64::from(i) / 30.0,
                    1.0 - f64::from(i) / 25.0,
                    f64::from(i % 3) * 0.5,
                )
            })
            .collect();
        let image = Image {
            width: 31,
            height: 1,
            pixels: pixels.clone(),
        };
        let bytes: Vec<u8> = pixels
            .iter()
            .flat_map(|c| c.to_array().map(rounded))
            .collect();
        assert_eq!(image.to_rgb8_bytes(), bytes);
        let mut other = image.clone();
        other.pixels[30].z = 0.2;
        assert_ne!(other.to_rgb8_bytes(), bytes);
    }
}

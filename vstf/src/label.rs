//! Short text labels burned into images (`render --models all`, `animate
//! --label`): a 5 x 7 pixel font for digits, the letters of the model
//! names and a little punctuation, drawn white on a dark box so that it
//! reads on any picture. No font file is needed.

use image::{Rgb, RgbImage};

/// The glyph of `c`, seven rows of five pixels (`#` set), if the font has it.
fn glyph(c: char) -> Option<[&'static str; 7]> {
    Some(match c {
        '0' => [
            " ### ", "#   #", "#  ##", "# # #", "##  #", "#   #", " ### ",
        ],
        '1' => [
            "  #  ", " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        '2' => [
            " ### ", "#   #", "    #", "   # ", "  #  ", " #   ", "#####",
        ],
        '3' => [
            "#####", "   # ", "  #  ", "   # ", "    #", "#   #", " ### ",
        ],
        '4' => [
            "   # ", "  ## ", " # # ", "#  # ", "#####", "   # ", "   # ",
        ],
        '5' => [
            "#####", "#    ", "#### ", "    #", "    #", "#   #", " ### ",
        ],
        '6' => [
            "  ## ", " #   ", "#    ", "#### ", "#   #", "#   #", " ### ",
        ],
        '7' => [
            "#####", "    #", "   # ", "  #  ", " #   ", " #   ", " #   ",
        ],
        '8' => [
            " ### ", "#   #", "#   #", " ### ", "#   #", "#   #", " ### ",
        ],
        '9' => [
            " ### ", "#   #", "#   #", " ####", "    #", "   # ", " ##  ",
        ],
        '.' => [
            "     ", "     ", "     ", "     ", "     ", " ##  ", " ##  ",
        ],
        ',' => [
            "     ", "     ", "     ", "     ", " ##  ", "  #  ", " #   ",
        ],
        '-' => [
            "     ", "     ", "     ", "#####", "     ", "     ", "     ",
        ],
        '=' => [
            "     ", "     ", "#####", "     ", "#####", "     ", "     ",
        ],
        ':' => [
            "     ", " ##  ", " ##  ", "     ", " ##  ", " ##  ", "     ",
        ],
        ' ' => [
            "     ", "     ", "     ", "     ", "     ", "     ", "     ",
        ],
        '+' => [
            "     ", "  #  ", "  #  ", "#####", "  #  ", "  #  ", "     ",
        ],
        'a' => [
            "     ", "     ", " ### ", "    #", " ####", "#   #", " ####",
        ],
        'c' => [
            "     ", "     ", " ### ", "#    ", "#    ", "#   #", " ### ",
        ],
        'e' => [
            "     ", "     ", " ### ", "#   #", "#####", "#    ", " ### ",
        ],
        'f' => [
            "  ## ", " #  #", " #   ", "###  ", " #   ", " #   ", " #   ",
        ],
        'i' => [
            "  #  ", "     ", " ##  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        'l' => [
            " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        'n' => [
            "     ", "     ", "# ## ", "##  #", "#   #", "#   #", "#   #",
        ],
        'o' => [
            "     ", "     ", " ### ", "#   #", "#   #", "#   #", " ### ",
        ],
        'r' => [
            "     ", "     ", "# ## ", "##  #", "#    ", "#    ", "#    ",
        ],
        's' => [
            "     ", "     ", " ####", "#    ", " ### ", "    #", "#### ",
        ],
        't' => [
            " #   ", " #   ", "###  ", " #   ", " #   ", " #  #", "  ## ",
        ],
        'v' => [
            "     ", "     ", "#   #", "#   #", "#   #", " # # ", "  #  ",
        ],
        'z' => [
            "     ", "     ", "#####", "   # ", "  #  ", " #   ", "#####",
        ],
        _ => return None,
    })
}

/// Whether every character of `text` can be drawn.
#[cfg(test)]
fn drawable(text: &str) -> bool {
    text.chars().all(|c| glyph(c).is_some())
}

/// Draws `text` at the top left of `img`, each font pixel `scale` image
/// pixels, white on a dark box; characters the font lacks are skipped.
pub fn draw_label(img: &mut RgbImage, text: &str, scale: u32) {
    draw_at(img, text, (0, 0), scale);
}

/// [`draw`] with the box's top left corner at `(x, y)`.
pub(crate) fn draw_at(img: &mut RgbImage, text: &str, (bx, by): (u32, u32), scale: u32) {
    let (w, h) = img.dimensions();
    let chars: Vec<[&str; 7]> = text.chars().filter_map(glyph).collect();
    let pad = scale * 2;
    let box_w = chars.len() as u32 * 6 * scale + 2 * pad;
    let box_h = 7 * scale + 2 * pad;
    for y in by..(by + box_h).min(h) {
        for x in bx..(bx + box_w).min(w) {
            let p = img.get_pixel_mut(x, y);
            *p = Rgb(p.0.map(|c| c / 4));
        }
    }
    for (k, g) in chars.iter().enumerate() {
        for (row, line) in g.iter().enumerate() {
            for (col, bit) in line.chars().enumerate() {
                if bit != '#' {
                    continue;
                }
                let x0 = bx + pad + (k as u32 * 6 + col as u32) * scale;
                let y0 = by + pad + row as u32 * scale;
                for dy in 0..scale {
                    for dx in 0..scale {
                        if x0 + dx < w && y0 + dy < h {
                            img.put_pixel(x0 + dx, y0 + dy, Rgb([255, 255, 255]));
                        }
                    }
                }
            }
        }
    }
}

/// The font scale for an image `width` pixels wide: 1 up to 320, then 2, 3.
pub fn label_scale(width: u32) -> u32 {
    (width / 320).clamp(1, 3)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A label lights pixels in its box only, and every glyph is 5 x 7.
    #[test]
    fn labels_draw_inside_their_box() {
        let mut img = RgbImage::from_pixel(200, 40, Rgb([0, 0, 200]));
        draw_label(&mut img, "relativistic, t = -12.5", 1);
        let lit = img.pixels().filter(|p| p.0 == [255, 255, 255]).count();
        assert!(lit > 100, "{lit} pixels lit");
        assert_eq!(img.get_pixel(199, 39).0, [0, 0, 200], "outside the box");
        assert!(drawable(
            "infinite+lorentz classical relativistic t = 0123456789.-,:"
        ));
        assert!(!drawable("X"));
        for c in "0123456789.,-=:+ acefilnorstvz".chars() {
            let g = glyph(c).unwrap();
            assert!(g.iter().all(|l| l.chars().count() == 5), "{c}");
        }
    }
}

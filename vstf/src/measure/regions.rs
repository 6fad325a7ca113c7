//! Regions of an image: the pixels of a class (a colour), their connected
//! parts, the area a region encloses, and its centroid. Counting pixels
//! measures the area of a shape on the image plane: every pixel whose
//! centre is inside counts, so the count misses the true area by at most
//! the pixels within half a pixel's diagonal of the outline, and a circle's
//! radius from its area, sqrt(count / pi), is within sqrt(2)/2 pixel.

use glam::DVec3;
use image::RgbImage;
use std::collections::VecDeque;

/// How far a radius from an area counted in pixels can be off, pixels:
/// half a pixel's diagonal (see the module's doc).
pub const RADIUS_FROM_AREA: f64 = std::f64::consts::SQRT_2 / 2.0;

/// A set of pixels of one image.
#[derive(Clone, Debug, PartialEq)]
pub struct Mask {
    width: u32,
    height: u32,
    set: Vec<bool>,
}

impl Mask {
    /// The pixels of `img` whose colour (0 to 1) passes `class`.
    pub fn of(img: &RgbImage, class: impl Fn(DVec3) -> bool) -> Mask {
        let (width, height) = img.dimensions();
        let set = img
            .pixels()
            .map(|p| class(DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])) / 255.0))
            .collect();
        Mask { width, height, set }
    }

    /// How many pixels are in the set.
    pub fn count(&self) -> usize {
        self.set.iter().filter(|&&b| b).count()
    }

    fn at(&self, x: i64, y: i64) -> Option<usize> {
        let inside = x >= 0 && y >= 0 && x < i64::from(self.width) && y < i64::from(self.height);
        inside.then(|| (y * i64::from(self.width) + x) as usize)
    }

    /// The pixels reachable from `seeds` through pixels for which `open`
    /// holds (their indices), stepping to the 4 or 8 neighbours.
    fn flood(&self, seeds: Vec<usize>, open: impl Fn(usize) -> bool, diagonal: bool) -> Vec<bool> {
        let w = i64::from(self.width);
        let mut seen = vec![false; self.set.len()];
        let mut queue: VecDeque<usize> = seeds.into_iter().filter(|&i| open(i)).collect();
        for &i in &queue {
            seen[i] = true;
        }
        while let Some(i) = queue.pop_front() {
            let (x, y) = (i as i64 % w, i as i64 / w);
            for (dx, dy) in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ]
            .into_iter()
            .take(if diagonal { 8 } else { 4 })
            {
                if let Some(j) = self.at(x + dx, y + dy) {
                    if !seen[j] && open(j) {
                        seen[j] = true;
                        queue.push_back(j);
                    }
                }
            }
        }
        seen
    }

    /// The largest 8-connected part of the set (the first in raster order
    /// among equals).
    pub fn largest_part(&self) -> Mask {
        let mut taken = vec![false; self.set.len()];
        let mut best: Vec<bool> = vec![false; self.set.len()];
        let mut best_count = 0;
        for i in 0..self.set.len() {
            if !self.set[i] || taken[i] {
                continue;
            }
            let part = self.flood(vec![i], |j| self.set[j], true);
            let n = part.iter().filter(|&&b| b).count();
            for (t, p) in taken.iter_mut().zip(&part) {
                *t |= *p;
            }
            if n > best_count {
                (best, best_count) = (part, n);
            }
        }
        Mask { set: best, ..*self }
    }

    /// The set and everything it encloses: the pixels not reachable from
    /// the image's border through pixels outside the set (4-connected).
    pub fn enclosed(&self) -> Mask {
        let (w, h) = (self.width as usize, self.height as usize);
        let border: Vec<usize> = (0..self.set.len())
            .filter(|&i| i % w == 0 || i % w == w - 1 || i / w == 0 || i / w == h - 1)
            .collect();
        let outside = self.flood(border, |j| !self.set[j], false);
        Mask {
            set: outside.iter().map(|&o| !o).collect(),
            ..*self
        }
    }

    /// The pixels of `self` not in `other`.
    pub fn without(&self, other: &Mask) -> Mask {
        Mask {
            set: self
                .set
                .iter()
                .zip(&other.set)
                .map(|(&a, &b)| a && !b)
                .collect(),
            ..*self
        }
    }

    /// The centres of the set's pixels (continuous pixel coordinates).
    pub fn centres(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let w = self.width as usize;
        self.set
            .iter()
            .enumerate()
            .filter(|(_, &b)| b)
            .map(move |(i, _)| ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5))
    }

    /// The mean of the set's pixel centres (continuous pixel coordinates,
    /// from the image's top left corner); `None` when it is empty.
    pub fn centroid(&self) -> Option<(f64, f64)> {
        let w = self.width as usize;
        let (mut sx, mut sy, mut n) = (0.0, 0.0, 0.0);
        for (i, _) in self.set.iter().enumerate().filter(|(_, &b)| b) {
            sx += (i % w) as f64 + 0.5;
            sy += (i / w) as f64 + 0.5;
            n += 1.0;
        }
        (n > 0.0).then(|| (sx / n, sy / n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    /// A ring (between radii 10 and 14) on grey, with a black disc (radius 5)
    /// and a lone speck inside it, centred on (40, 30).
    fn picture() -> RgbImage {
        RgbImage::from_fn(80, 60, |x, y| {
            let r = ((f64::from(x) + 0.5 - 40.0).hypot(f64::from(y) + 0.5 - 30.0)) as f32;
            match r {
                r if r < 5.0 => Rgb([0, 0, 0]),
                r if (7.0..7.6).contains(&r) && x == 47 => Rgb([255, 200, 50]),
                r if (10.0..14.0).contains(&r) => Rgb([255, 200, 50]),
                _ => Rgb([80, 100, 150]),
            }
        })
    }

    #[test]
    fn areas_give_radii_within_the_bound() {
        let img = picture();
        let radius = |m: &Mask| (m.count() as f64 / std::f64::consts::PI).sqrt();
        let black = Mask::of(&img, |c| c.max_element() < 0.1);
        assert!((radius(&black) - 5.0).abs() <= RADIUS_FROM_AREA);
        let ring = Mask::of(&img, |c| c.x > 0.9).largest_part();
        let outer = ring.enclosed();
        assert!((radius(&outer) - 14.0).abs() <= RADIUS_FROM_AREA);
        // The speck inside is not the ring: the inner region keeps it.
        let inner = outer.without(&ring);
        assert!((radius(&inner) - 10.0).abs() <= RADIUS_FROM_AREA);
        let (cx, cy) = ring.centroid().unwrap();
        assert!((cx - 40.0).abs() < 0.05 && (cy - 30.0).abs() < 0.05);
        // An arc (the ring's right half) encloses nothing but itself.
        let arc = Mask::of(&img, |c| c.x > 0.9).largest_part();
        let right = Mask {
            set: arc
                .set
                .iter()
                .enumerate()
                .map(|(i, &b)| b && i % 80 >= 40)
                .collect(),
            ..arc.clone()
        };
        assert_eq!(right.enclosed().count(), right.count());
    }
}

use super::*;
use crate::geometry::intersect_prism;
use crate::geometry::Miss;
use crate::rng::SplitMix64;
use glam::DVec4;

/// A triangle at a random place of scale `scale`, of size `size`.
fn triangle(rng: &mut SplitMix64, scale: f64, size: f64) -> [DVec3; 3] {
    let mut at = || DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5;
    let centre = at() * scale;
    [
        centre + at() * size,
        centre + at() * size,
        centre + at() * size,
    ]
}

/// A ray from a random origin (up to 1000 sizes away) aimed at a corner
/// or an edge of `t` or near it, at a random lab time and light speed.
fn aimed(rng: &mut SplitMix64, t: &[DVec3; 3], size: f64) -> (DVec4, DVec4) {
    let (i, j) = ((rng.next_u64() % 3) as usize, (rng.next_u64() % 3) as usize);
    let f = [0.0, 1.0, rng.next_f64()][(rng.next_u64() % 3) as usize];
    let nudge = [0.0, 1e-7, -1e-7, 1e-15][(rng.next_u64() % 4) as usize] * size;
    let target = t[i] + (t[j] - t[i]) * f + DVec3::splat(nudge);
    let from = target
        + (DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5)
            * size
            * crate::math::powf(10.0, 3.0 * rng.next_f64());
    let d = (target - from).extend(-(target - from).length() * rng.next_f64());
    (from.extend(rng.next_f64()), d)
}

/// Counts triangles the filter rejects, and of those the ones the exact
/// test does not reject as outside, with the bound's coefficient E
/// scaled by `slack` (1 in use).
fn rejections(slack: f32, seed: u64) -> (usize, usize) {
    let mut rng = SplitMix64::new(seed);
    let (mut rejected, mut wrong) = (0, 0);
    for scale in [0.05, 1.0, 1e5] {
        for size in [scale * 1e-6, scale * 1e-3, scale] {
            for _ in 0..2000 {
                let tris: Vec<[DVec3; 3]> = (0..LANES)
                    .map(|_| triangle(&mut rng, scale, size))
                    .collect();
                let rows = CornerRows::new(tris.len(), |t| tris[t]);
                let reach = reach(tris.iter().copied());
                let aim = (rng.next_u64() % LANES as u64) as usize;
                let (o, d) = aimed(&mut rng, &tris[aim], size);
                let v = DVec3::new(rng.next_f64() - 0.5, 0.0, 0.0) * 1.8;
                let Some(ray) = ComovingRay::new(o, d, (0.0, DVec3::ZERO), v) else {
                    continue;
                };
                let mut filter = rows.prepare(&ray, reach).expect("filtered");
                filter.e *= slack;
                // Four lanes of SSE2 for the first half, eight for all.
                let four = rows.candidates(SimdLevel::Baseline, &filter, 0, 4);
                let eight = rows.candidates(SimdLevel::best(), &filter, 0, LANES);
                let mask = four | (eight & !0b1111);
                for (i, t) in tris.iter().enumerate() {
                    if mask & (1 << i) == 0 {
                        rejected += 1;
                        let exact = intersect_prism(t, &ray, (-1e300, 1e300), (-1e300, 1e300));
                        if !matches!(exact, Err(Miss::Outside { .. })) {
                            wrong += 1;
                        }
                    }
                }
            }
        }
    }
    (rejected, wrong)
}

/// Every triangle the filter rejects, the exact test rejects as
/// outside, for rays aimed at corners and edges at every scale; and the
/// filter does reject most triangles a ray misses.
#[test]
fn the_filter_rejects_only_what_the_exact_test_rejects() {
    let (rejected, wrong) = rejections(1.0, 7);
    assert_eq!(wrong, 0, "of {rejected} rejected");
    assert!(rejected > 40_000, "{rejected}");
}

/// Negative control: with no allowance for rounding the same rays find
/// triangles rejected that the exact test does not reject.
#[test]
fn without_its_bound_the_filter_rejects_wrongly() {
    let (_, wrong) = rejections(0.0, 7);
    assert!(wrong > 0);
}

/// Every width and vector level this machine runs lets the same
/// triangles through as eight lanes at the baseline, at every scale,
/// leaves of fewer than [`LANES`] triangles included (their lanes past
/// the rows' end read the padding): four or fewer triangles in four SSE2
/// lanes, more in eight at each level, and eight lanes at each level
/// whatever the count. The control: the same rays with no allowance for
/// rounding let other triangles through, so the masks compared are ones
/// the arithmetic decides.
#[test]
fn every_width_and_level_lets_the_same_triangles_through() {
    let mut rng = SplitMix64::new(11);
    let (mut compared, mut decided) = (0, 0);
    for scale in [0.05, 1.0, 1e5] {
        for size in [scale * 1e-3, scale] {
            for _ in 0..500 {
                let count = 1 + (rng.next_u64() % (2 * LANES as u64)) as usize;
                let tris: Vec<[DVec3; 3]> = (0..count)
                    .map(|_| triangle(&mut rng, scale, size))
                    .collect();
                let rows = CornerRows::new(count, |t| tris[t]);
                let aim = (rng.next_u64() % count as u64) as usize;
                let (o, d) = aimed(&mut rng, &tris[aim], size);
                let Some(ray) = ComovingRay::new(o, d, (0.0, DVec3::ZERO), DVec3::ZERO) else {
                    continue;
                };
                let filter = rows.prepare(&ray, reach(tris.iter().copied()));
                let filter = filter.expect("filtered");
                let loose = FilterRay { e: 0.0, ..filter };
                for first in 0..count as u32 {
                    let n = (count - first as usize).min(LANES);
                    let mask = |level, f: &FilterRay, n| rows.candidates(level, f, first, n);
                    let reference = mask(SimdLevel::Baseline, &filter, LANES) & ((1 << n) - 1);
                    for level in SimdLevel::supported() {
                        assert_eq!(mask(level, &filter, n), reference, "{level}, {n}");
                        let eight = mask(level, &filter, LANES) & ((1 << n) - 1);
                        assert_eq!(eight, reference, "{level}, eight lanes");
                        compared += 2;
                    }
                    let loosened = mask(SimdLevel::Baseline, &loose, LANES) & ((1 << n) - 1);
                    decided += usize::from(loosened != reference);
                }
            }
        }
    }
    assert!(compared > 20_000, "{compared}");
    assert!(decided > 0, "the control");
}

/// Rows filled on two threads hold, at row 3 c + a and column t,
/// coordinate a of corner c of triangle t rounded to f32, as rows
/// filled on one thread do; the control, one triangle moved, changes
/// them.
#[test]
fn rows_hold_each_corner_whatever_the_threads() {
    let mut rng = SplitMix64::new(3);
    let tris: Vec<[DVec3; 3]> = (0..3 * FILL_CHUNK + 5)
        .map(|_| triangle(&mut rng, 1.0, 0.1))
        .collect();
    let on = |threads: usize, tris: &[[DVec3; 3]]| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
        pool.unwrap()
            .install(|| CornerRows::new(tris.len(), |t| tris[t]))
    };
    let (one, two) = (on(1, &tris), on(2, &tris));
    assert_eq!(one.rows, two.rows);
    for (t, corners) in tris.iter().enumerate() {
        for (c, corner) in corners.iter().enumerate() {
            for a in 0..3 {
                assert_eq!(two.rows[(3 * c + a) * two.stride + t], corner[a] as f32);
            }
        }
    }
    let mut moved = tris.clone();
    moved[2 * FILL_CHUNK + 1][2].y += 1.0;
    assert_ne!(on(2, &moved).rows, two.rows);
}

/// A ray or stretch too far out for f32 is not filtered.
#[test]
fn far_rays_are_not_filtered() {
    let rows = CornerRows::new(1, |_| [DVec3::X, DVec3::Y, DVec3::Z]);
    let ray = |o: DVec4| {
        ComovingRay::new(
            o,
            DVec4::new(0.0, 0.0, -1.0, -1.0),
            (0.0, DVec3::ZERO),
            DVec3::ZERO,
        )
        .unwrap()
    };
    assert!(rows
        .prepare(&ray(DVec4::new(0.0, 0.0, 5.0, 0.0)), 1.0)
        .is_some());
    assert!(rows
        .prepare(&ray(DVec4::new(0.0, 0.0, 2e15, 0.0)), 1.0)
        .is_none());
    assert!(rows
        .prepare(&ray(DVec4::new(0.0, 0.0, 5.0, 0.0)), f64::NAN)
        .is_none());
}

/// A large mesh's reach, found on both threads, is the one found
/// triangle by triangle on one, and on one thread the same; the
/// control: one corner moved farther out than any changes it. A
/// vertex no triangle uses does not count.
#[test]
fn a_large_meshs_reach_is_that_of_its_triangles_in_order() {
    let mut rng = SplitMix64::new(41);
    let n = 3 * PARALLEL_REACH;
    let mut vertices: Vec<DVec3> = (0..n + 2)
        .map(|_| (DVec3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) - 0.5) * 40.0)
        .collect();
    vertices[n + 1] = DVec3::splat(-1e9); // used by no triangle
    let triangles = (0..n as u32)
        .map(|i| [i, i + 1, (i * 7919) % n as u32])
        .collect();
    let mut mesh = Mesh {
        vertices,
        triangles,
        materials: Vec::new(),
    };
    let in_order = |m: &Mesh| reach((0..m.triangles.len()).map(|t| m.corners(t)));
    let on = |threads: usize, m: &Mesh| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| mesh_reach(m))
    };
    let expected = in_order(&mesh);
    assert!(expected > 19.0 && expected <= 20.0, "{expected}");
    assert_eq!(on(2, &mesh).to_bits(), expected.to_bits());
    assert_eq!(on(1, &mesh).to_bits(), expected.to_bits());
    mesh.vertices[n / 2].y = -75.5;
    assert_eq!(on(2, &mesh), 75.5);
}

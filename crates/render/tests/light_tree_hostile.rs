//! The light tree under hostile emitters (an adversarial review): black and vanishing emitters, huge
//! powers, emitters all at one point or all in one plane, far and close-packed clusters, shading
//! points at a centre or on a cluster's bounds, behind every one-sided panel, cones of opposed
//! normals, and the sizes where the choice changes hands (16/17 emitters, the index from 64).
//!
//! For every case and point: each `pmf` is a finite probability of at least the uniform share; the
//! emitter `choose_with_pmf` picks comes with `pmf`'s number to the bit; the stratified choices
//! land on each emitter as often as `pmf` says (each emitter's values of `u` are at most two
//! intervals, so a count is within 2 of `M pmf`); `sum pmf` plus the share of `u` whose descent
//! stops is 1; and a sample's density is the mixture `pdf` gives its direction, the same to the bit
//! through the index and without it.

use glam::{DVec2, DVec3};
use rtl_pdf::{QuadTarget, ShapeSampler, SphereTarget};
use rtl_render::light_tree::LightTree;
use rtl_render::lights::{EmitterWeight, LightTarget, UNIFORM_SHARE};
use rtl_render::target_index::TargetIndex;

fn sphere(c: DVec3, r: f64) -> LightTarget {
    LightTarget::Sphere(SphereTarget::new(c, r))
}

fn quad(q: DVec3, u: DVec3, v: DVec3, one_sided: bool) -> LightTarget {
    LightTarget::Quad {
        quad: QuadTarget::new(q, u, v),
        one_sided,
    }
}

fn weights(emitters: &[LightTarget], radiance: impl Fn(usize) -> f64) -> Vec<EmitterWeight> {
    emitters
        .iter()
        .enumerate()
        .map(|(i, t)| EmitterWeight::new(t, radiance(i)))
        .collect()
}

/// What [`check`] saw at one point.
#[derive(Debug, Default)]
struct Seen {
    /// The share of the `u` whose descent stopped.
    stopped: f64,
    /// How many emitters the tree part chose at least once.
    chosen_by_tree: usize,
}

/// Strata of `u` per point.
const M: usize = 1 << 14;

/// The checks of the module's documentation at `x`, without a shading normal and with two opposite
/// slanted ones (what is seen without one is returned).
fn check(tree: &LightTree, emitters: &[LightTarget], x: DVec3, label: &str) -> Seen {
    let n = DVec3::new(0.48, 0.6, -0.64);
    for normal in [n, -n] {
        check_choice(tree, emitters, x, Some(normal), label);
    }
    check_choice(tree, emitters, x, None, label)
}

/// [`check`] for one normal (or none): the choice's probabilities, and the densities of samples.
fn check_choice(
    tree: &LightTree,
    emitters: &[LightTarget],
    x: DVec3,
    normal: Option<DVec3>,
    label: &str,
) -> Seen {
    let n = tree.len();
    let floor = UNIFORM_SHARE / n as f64;
    let pmf: Vec<f64> = (0..n).map(|i| tree.pmf(x, normal, i)).collect();
    for (i, &p) in pmf.iter().enumerate() {
        assert!(
            p.is_finite() && p >= floor && p <= 1.0 + 1e-12,
            "{label}: pmf({x}, {i}) = {p}"
        );
    }
    let mut count = vec![0usize; n];
    let mut tree_count = vec![0usize; n];
    let mut stops = 0usize;
    let us: Vec<f64> = (0..M).map(|k| (k as f64 + 0.5) / M as f64).collect();
    // the edges: 0, the largest number below 1, just around the uniform share, and outside [0, 1)
    let edges = [
        0.0,
        1.0 - f64::EPSILON / 2.0,
        UNIFORM_SHARE,
        UNIFORM_SHARE * (1.0 - f64::EPSILON),
        1.0,
        -0.5,
        2.0,
        f64::NAN,
    ];
    for &u in us.iter().chain(&edges) {
        match tree.choose_with_pmf(x, normal, u) {
            Some((i, v, p)) => {
                assert!(i < n, "{label}: chose {i} of {n}");
                assert!((0.0..1.0).contains(&v), "{label}: u {u} remapped to {v}");
                assert_eq!(
                    p.to_bits(),
                    pmf[i].to_bits(),
                    "{label}: at {x}, u = {u}: chose {i} with {p}, pmf says {}",
                    pmf[i]
                );
            }
            None => assert!(
                u >= UNIFORM_SHARE,
                "{label}: the uniform share failed at u = {u}"
            ),
        }
    }
    for &u in &us {
        match tree.choose_with_pmf(x, normal, u) {
            Some((i, ..)) => {
                count[i] += 1;
                if u >= UNIFORM_SHARE {
                    tree_count[i] += 1;
                }
            }
            None => stops += 1,
        }
    }
    for i in 0..n {
        let expected = pmf[i] * M as f64;
        assert!(
            (count[i] as f64 - expected).abs() <= 2.5,
            "{label}: at {x} {normal:?} emitter {i} chosen {} times of {M}, pmf {} expects {expected}",
            count[i],
            pmf[i]
        );
    }
    let stopped = stops as f64 / M as f64;
    let sum: f64 = pmf.iter().sum();
    assert!(
        (sum + stopped - 1.0).abs() <= (n as f64 + 2.0) / M as f64,
        "{label}: at {x} {normal:?} sum pmf {sum} + stopped {stopped} != 1"
    );
    if stops == 0 {
        assert!(
            (sum - 1.0).abs() < 1e-12,
            "{label}: at {x} {normal:?} sum pmf {sum}"
        );
    }
    // A sample's density is the mixture's, through the index or without it.
    let index = TargetIndex::new(emitters);
    for k in 0..64 {
        let u = DVec2::new(
            (k as f64 + 0.5) / 64.0,
            ((k * 37) % 64) as f64 / 64.0 + 0.007,
        );
        let Some(s) = tree.sample(x, normal, u, emitters, None) else {
            continue;
        };
        assert!(
            s.direction.is_finite() && s.pdf.is_finite() && s.pdf > 0.0,
            "{label}: {s:?}"
        );
        let p = tree.pdf(x, normal, s.direction, emitters, None, None);
        assert!(
            (s.pdf - p).abs() <= 1e-9 * p,
            "{label}: at {x} {normal:?} sampled with {} but pdf {p}",
            s.pdf
        );
        let q = tree.pdf(x, normal, s.direction, emitters, Some(&index), None);
        assert_eq!(
            p.to_bits(),
            q.to_bits(),
            "{label}: at {x} {normal:?} pdf {p} without the index, {q} through it"
        );
        let via = tree.sample(x, normal, u, emitters, Some(&index)).unwrap();
        assert_eq!(via.direction, s.direction);
        assert!((via.pdf - s.pdf).abs() <= 1e-12 * s.pdf, "{label}");
    }
    Seen {
        stopped,
        chosen_by_tree: tree_count.iter().filter(|&&c| c > 0).count(),
    }
}

/// Points around and inside the emitters' box `[lo, hi]`: its centre, its corners, the middles of
/// its faces, a little outside and far away.
fn points(lo: DVec3, hi: DVec3) -> Vec<DVec3> {
    let c = 0.5 * (lo + hi);
    let size = (hi - lo).max_element().max(1e-300);
    let mut p = vec![c, lo, hi, DVec3::new(lo.x, hi.y, lo.z)];
    for axis in 0..3 {
        for side in [lo, hi] {
            let mut q = c;
            q[axis] = side[axis];
            p.push(q);
            q[axis] += (side[axis] - c[axis]).signum() * 0.3 * size;
            p.push(q);
        }
    }
    p.push(c + DVec3::new(0.31, 0.77, -0.55) * 40.0 * size);
    p.push(c - DVec3::new(0.31, 0.77, -0.55) * 1e6 * size);
    p.retain(|q| q.is_finite());
    p
}

fn tree(emitters: &[LightTarget], w: &[EmitterWeight]) -> LightTree {
    LightTree::new(emitters, w).expect("a tree")
}

fn check_all(
    emitters: &[LightTarget],
    w: &[EmitterWeight],
    at: &[DVec3],
    label: &str,
) -> Vec<Seen> {
    let t = tree(emitters, w);
    at.iter().map(|&x| check(&t, emitters, x, label)).collect()
}

/// A row of `n` small spheres along x, radius 0.1, at y = 2.
fn row(n: usize) -> Vec<LightTarget> {
    (0..n)
        .map(|i| sphere(DVec3::new(i as f64 * 0.5, 2.0, (i % 3) as f64 * 0.2), 0.1))
        .collect()
}

#[test]
fn ordinary_rows_at_the_thresholds() {
    for n in [17, 18, 33, 63, 64, 65, 100] {
        let e = row(n);
        let w = weights(&e, |i| 1.0 + (i % 5) as f64);
        let at = points(
            DVec3::new(0.0, 1.9, 0.0),
            DVec3::new(n as f64 * 0.5, 2.1, 0.5),
        );
        for s in check_all(&e, &w, &at, &format!("row of {n}")) {
            assert_eq!(s.stopped, 0.0);
        }
        // a shading point that is not a number (a ray gone wrong upstream): every importance is
        // NaN, the descent stops at the root, and each emitter keeps its uniform share
        let t = tree(&e, &w);
        let s = check(&t, &e, DVec3::splat(f64::NAN), "NaN point");
        assert!((s.stopped - (1.0 - UNIFORM_SHARE)).abs() < 1e-3, "{s:?}");
    }
}

#[test]
fn black_and_vanishing_emitters_among_lit_ones() {
    // radiance 0, radius 1e-300 (its r^2 and power are 0), radius 1e-160 (r^2 subnormal)
    // and quads of no area (an edge of length 0, two parallel edges), one- and two-sided
    let mut e = row(40);
    e[3] = sphere(DVec3::new(1.5, 2.0, 0.0), 1e-300);
    e[4] = sphere(DVec3::new(2.0, 2.0, 0.2), 1e-160);
    e[7] = quad(DVec3::new(3.5, 2.0, 0.0), DVec3::ZERO, DVec3::Z, true);
    e[8] = quad(DVec3::new(4.0, 2.0, 0.0), DVec3::X, DVec3::X * 2.0, false);
    e[9] = quad(DVec3::new(4.5, 2.0, 0.0), DVec3::X, DVec3::X * 2.0, true);
    let w = weights(&e, |i| if i % 4 == 0 { 0.0 } else { 1.0 });
    let mut at = points(DVec3::new(0.0, 1.9, 0.0), DVec3::new(20.0, 2.1, 0.5));
    // exactly at the vanishing spheres' centres
    at.push(DVec3::new(1.5, 2.0, 0.0));
    at.push(DVec3::new(2.0, 2.0, 0.2));
    at.push(DVec3::new(3.5, 2.0, 0.0));
    at.push(DVec3::new(4.0, 2.0, 0.0));
    for s in check_all(&e, &w, &at, "black and vanishing") {
        assert_eq!(s.stopped, 0.0);
    }
    // Every emitter black but one
    let w = weights(&e, |i| if i == 17 { 1.0 } else { 0.0 });
    for s in check_all(&e, &w, &at, "one lit") {
        assert_eq!(s.chosen_by_tree, 1);
    }
    // Every emitter black: no tree (the choice is uniform)
    let w = weights(&e, |_| 0.0);
    assert!(LightTree::new(&e, &w).is_none());
}

#[test]
fn many_vanishing_spheres_at_one_point() {
    // Forty spheres of radius 1e-300 at the origin and one ordinary lamp: the cluster of the
    // vanishing ones has power 0 and a sphere of radius 0.
    let mut e: Vec<LightTarget> = (0..40).map(|_| sphere(DVec3::ZERO, 1e-300)).collect();
    e.push(sphere(DVec3::new(3.0, 0.0, 0.0), 0.5));
    let w = weights(&e, |_| 1.0);
    let at = [
        DVec3::ZERO,
        DVec3::new(1e-300, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(3.0, 0.0, 0.0),
    ];
    for s in check_all(&e, &w, &at, "vanishing at a point") {
        assert_eq!(s.stopped, 0.0, "{s:?}");
    }
}

#[test]
fn huge_powers() {
    for radiance in [1e300, 1e307, f64::MAX / 1e3] {
        // (in coincident pairs: from inside a bright pair both leaves' importances are near
        // 4 pi L, whose sum may overflow)
        let e: Vec<LightTarget> = (0..40)
            .map(|i| sphere(DVec3::new((i / 2) as f64 * 0.5, 2.0, 0.0), 0.1))
            .collect();
        let w = weights(&e, |i| if (i / 2) % 2 == 0 { radiance } else { 1.0 });
        if LightTree::new(&e, &w).is_none() {
            // (the powers add up to infinity: a uniform choice, which is allowed)
            assert!(radiance > 1e307, "{radiance}");
            continue;
        }
        let mut at = points(DVec3::new(0.0, 1.9, 0.0), DVec3::new(20.0, 2.1, 0.5));
        at.push(DVec3::new(0.0, 2.0, 0.0)); // at a bright pair's centre
        at.push(DVec3::new(0.0, 2.0, 0.1)); // on its surface
        at.push(DVec3::new(0.5, 2.0, 0.05)); // inside a dim pair
        for (x, s) in at
            .iter()
            .zip(check_all(&e, &w, &at, &format!("radiance {radiance}")))
        {
            assert_eq!(s.stopped, 0.0, "radiance {radiance} at {x}: {s:?}");
        }
    }
}

#[test]
fn every_emitter_at_one_point() {
    let c = DVec3::new(1.0, 2.0, 3.0);
    let e: Vec<LightTarget> = (0..100).map(|_| sphere(c, 0.25)).collect();
    let w = weights(&e, |i| 1.0 + i as f64);
    let at = [
        c,
        c + DVec3::X * 0.25,
        c + DVec3::Y * 5.0,
        c + DVec3::splat(1e3),
    ];
    for s in check_all(&e, &w, &at, "coincident spheres") {
        assert_eq!(s.stopped, 0.0);
    }
    // the same one-sided quad a hundred times, from the front, in its plane and from behind
    let e: Vec<LightTarget> = (0..100)
        .map(|_| quad(DVec3::ZERO, DVec3::X, DVec3::Z, true)) // u x v = -y: shines down
        .collect();
    let w = weights(&e, |_| 1.0);
    let at = [
        DVec3::new(0.5, -1.0, 0.5),
        DVec3::new(0.5, 0.0, 0.5),
        DVec3::new(0.5, 1.0, 0.5),
        DVec3::new(0.5, -1e-300, 0.5),
    ];
    let seen = check_all(&e, &w, &at, "coincident quads");
    assert_eq!(seen[0].stopped, 0.0);
    // in the plane and behind, every importance is 0: the descent stops at the root
    for s in &seen[1..3] {
        assert!((s.stopped - (1.0 - UNIFORM_SHARE)).abs() < 1e-3, "{s:?}");
    }
}

#[test]
fn emitters_in_one_plane() {
    // a 9 x 9 grid of quads in the plane y = 0, alternately facing up and down, and of spheres
    // centred in it: the bounds have no extent in y beyond the padding
    let mut e = Vec::new();
    for i in 0..81 {
        let (a, b) = ((i % 9) as f64, (i / 9) as f64);
        let q = DVec3::new(a, 0.0, b);
        e.push(if i % 3 == 2 {
            sphere(q, 0.2)
        } else if i % 2 == 0 {
            quad(q, DVec3::X * 0.5, DVec3::Z * 0.5, true) // faces down
        } else {
            quad(q, DVec3::Z * 0.5, DVec3::X * 0.5, true) // faces up
        });
    }
    let w = weights(&e, |_| 1.0);
    let mut at = points(DVec3::new(0.0, 0.0, 0.0), DVec3::new(8.5, 0.0, 8.5));
    at.push(DVec3::new(4.25, 0.0, 4.25)); // in the plane, on a quad
    at.push(DVec3::new(100.0, 0.0, 4.0)); // in the plane, far
    check_all(&e, &w, &at, "one plane");
    // only quads facing down, in one plane: from above everything is behind
    let e: Vec<LightTarget> = (0..81)
        .map(|i| {
            let q = DVec3::new((i % 9) as f64, 0.0, (i / 9) as f64);
            quad(q, DVec3::X * 0.5, DVec3::Z * 0.5, true)
        })
        .collect();
    let w = weights(&e, |_| 1.0);
    let at = [
        DVec3::new(4.0, 1.0, 4.0),
        DVec3::new(4.0, 0.0, 4.0),
        DVec3::new(4.0, -1.0, 4.0),
        DVec3::new(4.2, 1e-12, 4.2),
        DVec3::new(4.2, -1e-12, 4.2),
    ];
    let seen = check_all(&e, &w, &at, "one plane facing down");
    assert!(
        (seen[0].stopped - (1.0 - UNIFORM_SHARE)).abs() < 1e-3,
        "{seen:?}"
    );
    assert_eq!(seen[2].stopped, 0.0);
    assert_eq!(seen[4].stopped, 0.0);
}

#[test]
fn far_and_close_packed() {
    // forty lamps 1e-10 apart, 1e15 from the origin, seen from near them and from the origin
    let base = DVec3::new(1e15, -3e14, 2e14);
    let e: Vec<LightTarget> = (0..40)
        .map(|i| sphere(base + DVec3::new(i as f64 * 1e-10, 0.0, 0.0), 1e-11))
        .collect();
    let w = weights(&e, |i| 1.0 + i as f64);
    let t = tree(&e, &w);
    // (at 1e15 the spacing of f64 is 0.125: the forty are one point there)
    for x in [base + DVec3::Y, base] {
        check(&t, &e, x, "far and close-packed");
    }
    for x in [DVec3::ZERO, DVec3::splat(-1e15)] {
        check_choice(&t, &e, x, None, "far and close-packed, from afar");
    }
    // the same forty at ordinary coordinates, so that they are forty points
    let base = DVec3::new(1.0, 2.0, 3.0);
    let e: Vec<LightTarget> = (0..40)
        .map(|i| sphere(base + DVec3::new(i as f64 * 1e-10, 0.0, 0.0), 1e-11))
        .collect();
    let t = tree(&e, &w);
    for x in [base + DVec3::Y, base, base + DVec3::new(2e-10, 1e-11, 0.0)] {
        check(&t, &e, x, "close-packed");
    }
    check_choice(&t, &e, DVec3::splat(-1e15), None, "close-packed, from afar");
    // forty lamps 1e15 apart, seen from the origin and from near one
    let e: Vec<LightTarget> = (0..40)
        .map(|i| sphere(DVec3::new((i as f64 - 20.0) * 1e15, 1.0, 0.0), 1.0))
        .collect();
    let w = weights(&e, |_| 1.0);
    let at = [
        DVec3::ZERO,
        DVec3::new(5e15, 0.0, 0.0),
        DVec3::new(1e15, 1.0, 3.0),
    ];
    for s in check_all(&e, &w, &at, "far apart") {
        assert_eq!(s.stopped, 0.0);
    }
}

#[test]
fn two_sided_and_one_sided_panels_facing_each_other() {
    // Two walls of panels facing each other (opposed normals under the root), a third of them
    // two-sided; one cluster of panels whose normals spread over more than a hemisphere.
    let mut e = Vec::new();
    for i in 0..24 {
        let (a, b) = ((i % 6) as f64, (i / 6) as f64);
        // x = 0 facing +x, x = 4 facing -x
        e.push(quad(
            DVec3::new(0.0, a, b),
            DVec3::Y * 0.8,
            DVec3::Z * 0.8,
            i % 3 != 0,
        ));
        e.push(quad(
            DVec3::new(4.0, a, b),
            DVec3::Z * 0.8,
            DVec3::Y * 0.8,
            i % 3 != 1,
        ));
    }
    for k in 0..8 {
        let t = k as f64 * std::f64::consts::TAU / 8.0;
        let n = DVec3::new(t.cos(), 0.0, t.sin());
        let u = n.cross(DVec3::Y);
        e.push(quad(
            DVec3::new(2.0, -3.0, 2.0) + n,
            u * 0.3,
            DVec3::Y * 0.3,
            true,
        ));
    }
    let w = weights(&e, |i| 1.0 + (i % 7) as f64);
    let mut at = points(DVec3::new(0.0, -3.5, 0.0), DVec3::new(4.0, 6.0, 4.0));
    at.extend([
        DVec3::new(-1.0, 2.0, 2.0), // behind the wall at x = 0
        DVec3::new(5.0, 2.0, 2.0),  // behind the wall at x = 4
        DVec3::new(2.0, -3.0, 2.0), // in the ring's middle
        DVec3::new(0.0, 0.4, 0.4),  // on a panel
    ]);
    check_all(&e, &w, &at, "facing walls");
}

#[test]
fn behind_every_one_sided_panel() {
    // forty panels on a sphere of radius 10, each facing outwards: from the centre every one is
    // seen from behind; the descent stops at the root and the uniform share picks a panel whose
    // sample fails
    let mut e = Vec::new();
    for i in 0..40 {
        let z = 1.0 - (2 * i + 1) as f64 / 40.0;
        let phi = i as f64 * 2.399_963;
        let r = (1.0 - z * z).sqrt();
        let n = DVec3::new(r * phi.cos(), r * phi.sin(), z);
        let (t, b) = {
            let a = if n.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
            let t = n.cross(a).normalize();
            (t, n.cross(t))
        };
        // u x v = t x b = n: faces outwards
        e.push(quad(10.0 * n - 0.5 * (t + b), t, b, true));
    }
    let w = weights(&e, |_| 1.0);
    let t = tree(&e, &w);
    let x = DVec3::new(0.1, -0.2, 0.3);
    let s = check(&t, &e, x, "inside a shell of outward panels");
    // every leaf's importance is 0, so the descent stops wherever it gets
    assert!((s.stopped - (1.0 - UNIFORM_SHARE)).abs() < 1e-3, "{s:?}");
    for u in [0.0, 0.05, 0.5, 0.999] {
        assert!(t.sample(x, None, DVec2::new(u, 0.5), &e, None).is_none());
    }
    assert_eq!(t.pdf(x, None, DVec3::X, &e, None, None), 0.0);
    // from outside, in front of a few
    check(&t, &e, DVec3::new(0.0, 0.0, 30.0), "outside the shell");
}

#[test]
fn ten_thousand_emitters_at_one_point_build_and_choose() {
    let n = 10_000;
    let e: Vec<LightTarget> = (0..n).map(|_| sphere(DVec3::ONE, 0.5)).collect();
    let w = weights(&e, |i| 1.0 + (i % 3) as f64);
    let t = tree(&e, &w);
    // median splits whatever the emitters' boxes: 14 levels for 10,000, so that building is
    // O(n log n) and a trail 14 steps (a split that kept all of them on one side would give 9,999)
    assert_eq!(t.depth(), 14);
    for x in [DVec3::ONE, DVec3::new(1.0, 5.0, 1.0)] {
        for k in 0..1000 {
            let u = (k as f64 + 0.5) / 1000.0;
            // (normals that face the pile, or see it straddle their horizon)
            for normal in [None, Some(-DVec3::Y), Some(DVec3::X)] {
                let (i, _, p) = t.choose_with_pmf(x, normal, u).unwrap();
                assert_eq!(p.to_bits(), t.pmf(x, normal, i).to_bits());
            }
        }
    }
}

#[test]
fn weights_that_are_not_powers_make_no_tree() {
    // A negative or NaN radiance (the renderer's own weights are never either: a scene's radiance
    // that is not a positive number weighs 0) would make negative or NaN probabilities.
    let e = row(40);
    for bad in [-1.0, f64::NAN, f64::NEG_INFINITY] {
        let w = weights(&e, |i| if i == 5 { bad } else { 1.0 });
        assert!(LightTree::new(&e, &w).is_none(), "radiance {bad}");
    }
    let w = weights(&e, |i| if i == 5 { f64::INFINITY } else { 1.0 });
    assert!(LightTree::new(&e, &w).is_none());
}

/// A sphere whose cone is far narrower than the spacing of `f64` unit vectors (radius 1e-11 seen
/// from 1e15: 1e-26 rad) drew directions that, rounded, lay outside its cone, where its own `pdf`
/// is 0. Below rtl-pdf's `MIN_CONE_SIN2` such a sphere is too small to see: no sample, density 0,
/// through the tree as on its own; among ordinary lamps it takes its share of choices and gives no
/// direction, and the others' samples keep their densities.
#[test]
fn a_sphere_below_the_resolution_of_directions_gives_no_sample() {
    let far = sphere(DVec3::new(1e15, -3e14, 2e14), 1e-11);
    let LightTarget::Sphere(s) = far else {
        unreachable!()
    };
    let axis = s.center().normalize();
    for k in 0..64 {
        let u = DVec2::new((k as f64 + 0.5) / 64.0, 0.3);
        assert!(s.sample(DVec3::ZERO, u).is_none());
    }
    assert_eq!(s.pdf(DVec3::ZERO, axis), 0.0);
    // with a lamp at an ordinary distance: the far one keeps its share of the choices (the `u`s
    // are stratified, so the count is that share of 200, to one) and gives nothing; every sample
    // drawn is the near lamp's, with its density
    let e = vec![far, sphere(DVec3::new(0.0, 3.0, 0.0), 0.5)];
    let w = weights(&e, |_| 1.0);
    let t = tree(&e, &w);
    let mut drawn = 0;
    for k in 0..200 {
        let u = DVec2::new((k as f64 + 0.5) / 200.0, 0.41);
        let Some(d) = t.sample(DVec3::ZERO, None, u, &e, None) else {
            continue;
        };
        drawn += 1;
        assert!(d.direction.y > 0.9, "{:?}", d.direction);
        let p = t.pdf(DVec3::ZERO, None, d.direction, &e, None, None);
        assert!((d.pdf - p).abs() <= 1e-12 * p, "{} vs {p}", d.pdf);
    }
    let want = 200.0 * (1.0 - t.pmf(DVec3::ZERO, None, 0));
    assert!(
        (drawn as f64 - want).abs() <= 1.0,
        "{drawn} of 200, not {want}"
    );
    assert!(drawn < 200);
    assert_eq!(t.pdf(DVec3::ZERO, None, axis, &e, None, None), 0.0);
}

/// A direction that meets more emitters than the index names (here every one of ten thousand
/// at one point) sums their terms over one walk of the tree, `O(n)`, not one trail each: the
/// same density as the trails', in the list's order, to rounding; a stop on the way (from behind
/// a pile of panels) gives the emitters under it their uniform share.
#[test]
fn a_direction_through_a_pile_of_emitters_walks_the_tree_once() {
    let reference = |t: &LightTree, e: &[LightTarget], x: DVec3, d: DVec3| -> f64 {
        (0..e.len())
            .map(|j| {
                let p = e[j].pdf(x, d);
                if p > 0.0 { t.pmf(x, None, j) * p } else { 0.0 }
            })
            .sum()
    };
    let n = 10_000;
    let c = DVec3::new(0.0, 3.0, 0.0);
    let e: Vec<LightTarget> = (0..n)
        .map(|i| sphere(c + DVec3::X * (i % 7) as f64 * 1e-3, 0.3))
        .collect();
    let w = weights(&e, |i| 1.0 + (i % 3) as f64);
    let t = tree(&e, &w);
    let index = TargetIndex::new(&e);
    let x = DVec3::ZERO;
    // (the walk adds in the tree's order, a trail for each emitter in the list's: the sums of ten
    // thousand terms differ in their last bits, so bit-equality with the walk says it was taken)
    let mut list_order_differs = 0;
    for k in 0..200 {
        let u = DVec2::new((k as f64 + 0.5) / 200.0, 0.37);
        let s = t.sample(x, None, u, &e, Some(&index)).unwrap();
        let p = t.pdf(x, None, s.direction, &e, Some(&index), None);
        assert!((s.pdf - p).abs() <= 1e-9 * p, "{} vs {p}", s.pdf);
        let walk = t.pdf_by_walk(x, None, s.direction, &e, None);
        assert_eq!(p.to_bits(), walk.to_bits(), "not one walk");
        if k % 20 == 0 {
            let want = reference(&t, &e, x, s.direction);
            assert!((p - want).abs() <= 1e-12 * want, "{p} vs {want}");
            list_order_differs += (want.to_bits() != walk.to_bits()) as usize;
        }
    }
    // the check can tell: the sums in the list's order (a trail each) differ from the walk's
    assert!(list_order_differs > 0);
    // a pile of one-sided panels with a few facing the other way: from the side most face, stops
    // happen nowhere; from behind most of them, under every cluster of only those
    let e: Vec<LightTarget> = (0..200)
        .map(|i| {
            let q = DVec3::new(-1.0, 3.0 + 1e-3 * (i % 5) as f64, -1.0);
            if i % 10 == 0 {
                quad(q, DVec3::X * 2.0, DVec3::Z * 2.0, true) // faces down
            } else {
                quad(q, DVec3::Z * 2.0, DVec3::X * 2.0, true) // faces up
            }
        })
        .collect();
    let w = weights(&e, |_| 1.0);
    let t = tree(&e, &w);
    for x in [DVec3::new(0.1, 0.0, 0.2), DVec3::new(0.1, 6.0, 0.2)] {
        let mut hits = 0;
        for k in 0..64 {
            let u = DVec2::new((k as f64 + 0.5) / 64.0, 0.61);
            let Some(s) = t.sample(x, None, u, &e, None) else {
                continue;
            };
            hits += 1;
            let p = t.pdf(x, None, s.direction, &e, None, None);
            assert!((s.pdf - p).abs() <= 1e-9 * p, "{} vs {p}", s.pdf);
            let want = reference(&t, &e, x, s.direction);
            assert!((p - want).abs() <= 1e-12 * want, "at {x}: {p} vs {want}");
        }
        assert!(hits > 0);
    }
}

/// Around the sizes where the choice changes hands (one per point up to 16 emitters, the tree from
/// 17; the index from 64), with panels facing both ways and two-sided ones: the density a light
/// sample comes with is the one the MIS weight gives its direction, and from behind every panel
/// there is no sample and no density.
#[test]
fn the_light_sample_and_the_mis_weight_agree_at_the_thresholds() {
    use rtl_render::Color;
    use rtl_render::lights::Lights;
    use rtl_render::material::{Albedo, Material};
    use rtl_render::scene::SceneBuilder;
    for n in [16, 17, 63, 64, 65] {
        for all_up in [false, true] {
            let mut b = SceneBuilder::new();
            let w = b.world();
            let lamp = |b: &mut SceneBuilder, two_sided| {
                b.material(Material::DiffuseLight {
                    emit: Albedo::Constant(Color::new(1.0, 2.0, 3.0)),
                    two_sided,
                })
            };
            let (one, two) = (lamp(&mut b, false), lamp(&mut b, true));
            for i in 0..n {
                let q = DVec3::new((i % 8) as f64, 3.0 + 0.1 * (i % 3) as f64, (i / 8) as f64);
                let (u, v) = if all_up || i % 2 == 0 {
                    (DVec3::Z * 0.5, DVec3::X * 0.5) // faces up
                } else {
                    (DVec3::X * 0.5, DVec3::Z * 0.5) // faces down
                };
                let m = if !all_up && i % 5 == 0 { two } else { one };
                b.quad(w, q, u, v, m).unwrap();
            }
            let lights = Lights::new(&b.build().unwrap(), false);
            assert_eq!(lights.emitters.len(), n);
            assert_eq!(lights.emitter_tree.is_some(), n > 16, "{n}");
            assert_eq!(lights.emitter_index.is_some(), n >= 64, "{n}");
            let mut sampled = 0;
            for k in 0..400 {
                let x = DVec3::new(
                    (k % 20) as f64 * 0.45 - 0.5,
                    if k % 2 == 0 { 0.0 } else { 6.0 },
                    (k / 20) as f64 * 0.45 - 0.5,
                );
                let u = DVec2::new(
                    ((k * 7919) % 400) as f64 / 400.0,
                    0.3 + (k % 3) as f64 * 0.2,
                );
                // without a normal, and with normals facing the panels and away from them
                let normal = match k % 3 {
                    0 => None,
                    1 => Some(DVec3::Y),
                    _ => Some(-DVec3::Y),
                };
                let Some(s) = lights.sample_emitters(x, normal, u) else {
                    continue;
                };
                assert!(
                    !(all_up && x.y == 0.0),
                    "{n}: a sample from behind every panel"
                );
                sampled += 1;
                let p = lights.emitters_pdf(x, normal, s.direction);
                assert!(
                    s.pdf.is_finite() && (s.pdf - p).abs() <= 1e-9 * p,
                    "{n} at {x}: sampled with {} but weighted by {p}",
                    s.pdf
                );
            }
            assert!(sampled > 100, "{n}: {sampled}");
            if all_up {
                assert_eq!(
                    lights.emitters_pdf(DVec3::new(1.0, 0.0, 1.0), None, DVec3::Y),
                    0.0
                );
            }
        }
    }
}

/// The cosine at the shading point: a cluster entirely below the horizon of the normal gets only
/// the uniform share (its emitters' trails stop at the root), the probabilities still add up to 1
/// with the share of the descents that stop; an emitter that pokes above the horizon keeps more;
/// without a normal the choice is the one without the cosine, to the bit.
#[test]
fn a_cluster_below_the_horizon_gets_only_the_uniform_share() {
    // twenty spheres 5 below the shading point, twenty 5 above (the split is along y, the longest
    // axis of the centres: one cluster each)
    let mut e = Vec::new();
    for side in [-5.0, 5.0] {
        for k in 0..20 {
            let c = DVec3::new((k % 5) as f64 * 0.3, side, (k / 5) as f64 * 0.3);
            e.push(sphere(c, 0.1));
        }
    }
    let w = weights(&e, |i| 1.0 + (i % 3) as f64);
    let t = tree(&e, &w);
    let x = DVec3::new(0.6, 0.0, 0.45);
    let floor = UNIFORM_SHARE / 40.0;
    for (normal, below) in [(DVec3::Y, 0..20), (-DVec3::Y, 20..40)] {
        for i in below.clone() {
            assert_eq!(t.pmf(x, Some(normal), i), floor, "{normal} {i}");
        }
        let s = check_choice(&t, &e, x, Some(normal), "half below the horizon");
        assert_eq!(s.stopped, 0.0);
        assert_eq!(s.chosen_by_tree, 20, "{normal}: only the cluster above");
        let sum: f64 = (0..40).map(|i| t.pmf(x, Some(normal), i)).sum();
        assert!((sum - 1.0).abs() < 1e-12, "{sum}");
    }
    // just above the lower cluster's box, inside the sphere around it: the box is below the
    // horizon all the same
    let on_top = DVec3::new(0.6, -4.85, 0.45);
    for i in 0..20 {
        assert_eq!(t.pmf(on_top, Some(DVec3::Y), i), floor, "{i}");
    }
    check_choice(&t, &e, on_top, Some(DVec3::Y), "on top of a cluster");
    // a normal along the floor: both clusters straddle its horizon
    let beside = DVec3::new(-1.0, 0.0, 0.45);
    let s = check_choice(&t, &e, beside, Some(DVec3::X), "both at the horizon");
    assert_eq!(s.chosen_by_tree, 40);
    // without a normal: the old importance
    for i in 0..40 {
        assert!(t.pmf(x, None, i) > floor);
    }
    // Every emitter below the horizon: the descent stops at the root (90% of the choices come
    // back empty), each emitter keeps its uniform share.
    let low: Vec<LightTarget> = e[..20].to_vec();
    let t = tree(&low, &w[..20]);
    let s = check_choice(&t, &low, x, Some(DVec3::Y), "all below the horizon");
    assert!((s.stopped - (1.0 - UNIFORM_SHARE)).abs() < 1e-3, "{s:?}");
    for i in 0..20 {
        assert_eq!(t.pmf(x, Some(DVec3::Y), i), UNIFORM_SHARE / 20.0);
    }
    // A sphere whose centre is below the horizon but which pokes above it keeps its leaf's
    // importance: of two spheres side by side, one entirely below (chosen by its share alone).
    let pair = vec![
        sphere(DVec3::new(3.0, -0.5, 0.0), 1.0),
        sphere(DVec3::new(-3.0, -1.5, 0.0), 1.0),
    ];
    let w2 = weights(&pair, |_| 1.0);
    let t = tree(&pair, &w2);
    let origin = DVec3::ZERO;
    assert_eq!(t.pmf(origin, Some(DVec3::Y), 1), UNIFORM_SHARE / 2.0);
    let p = t.pmf(origin, Some(DVec3::Y), 0);
    assert!((p - (1.0 - UNIFORM_SHARE / 2.0)).abs() < 1e-15, "{p}");
}

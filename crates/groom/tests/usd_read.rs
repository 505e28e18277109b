//! USD grooms written by Pixar's own library (scripts/make-usd-fixtures.py): each basis
//! against its curve evaluated another way, each widths interpolation, each appearance primvar,
//! composed transforms, and units and up axes.

use cuticle_fiber::optics::absorption::{COLOUR_BETA_N, mu_a_from_color};
use cuticle_groom::usd::basis::STEPS;
use cuticle_groom::{Absorption, Groom};
use glam::{DVec3, Vec3};

fn fixture(name: &str) -> Groom {
    let path = format!("{}/tests/data/usd/{name}", env!("CARGO_MANIFEST_DIR"));
    Groom::read(&path).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The control points of every curve in bases.usda.
const WIGGLE: [[f64; 3]; 7] = [
    [0., 0., 0.],
    [1., 0., 1.],
    [0., 1., 2.],
    [2., 0., 3.],
    [1., 1., 4.],
    [0., 0., 5.],
    [1., 0., 6.],
];

fn wiggle() -> Vec<DVec3> {
    WIGGLE.iter().map(|p| DVec3::from_array(*p)).collect()
}

/// De Casteljau's construction of a cubic Bézier segment.
fn de_casteljau(p: &[DVec3], u: f64) -> DVec3 {
    let mut q = p.to_vec();
    while q.len() > 1 {
        q = q.windows(2).map(|w| w[0].lerp(w[1], u)).collect();
    }
    q[0]
}

/// Cox–de Boor's recursion for the uniform B-spline basis of degree `k` on integer knots.
fn cox_de_boor(i: i64, k: u32, t: f64) -> f64 {
    let i = i as f64;
    if k == 0 {
        return if (i..i + 1.0).contains(&t) { 1.0 } else { 0.0 };
    }
    let k_f = k as f64;
    (t - i) / k_f * cox_de_boor(i as i64, k - 1, t)
        + (i + k_f + 1.0 - t) / k_f * cox_de_boor(i as i64 + 1, k - 1, t)
}

/// A uniform cubic B-spline at knot parameter `t` (segment s spans t ∈ [s + 3, s + 4]).
fn bspline(p: &[DVec3], t: f64) -> DVec3 {
    // The last sample sits on the domain's end, where the half-open basis is zero: step back.
    let t = t.min(p.len() as f64 - 1e-12);
    p.iter()
        .enumerate()
        .map(|(i, q)| *q * cox_de_boor(i as i64, 3, t))
        .sum()
}

/// A Catmull–Rom segment as a cubic Hermite curve with tangents (P₂ − P₀)/2, (P₃ − P₁)/2.
fn catmull_rom(p: &[DVec3], u: f64) -> DVec3 {
    let (m1, m2) = ((p[2] - p[0]) / 2.0, (p[3] - p[1]) / 2.0);
    let (u2, u3) = (u * u, u * u * u);
    p[1] * (2.0 * u3 - 3.0 * u2 + 1.0)
        + m1 * (u3 - 2.0 * u2 + u)
        + p[2] * (-2.0 * u3 + 3.0 * u2)
        + m2 * (u3 - u2)
}

fn with_phantoms(p: &[DVec3]) -> Vec<DVec3> {
    let n = p.len();
    let mut e = vec![2.0 * p[0] - p[1]];
    e.extend_from_slice(p);
    e.push(2.0 * p[n - 1] - p[n - 2]);
    e
}

/// `strand` of `g` against `curve(segment, u)` at every polyline point.
fn assert_strand(g: &Groom, strand: usize, segments: usize, curve: impl Fn(usize, f64) -> DVec3) {
    let s = g.strand(strand);
    assert_eq!(s.positions.len(), segments * STEPS + 1, "strand {strand}");
    for (i, p) in s.positions.iter().enumerate() {
        let (seg, k) = if i == segments * STEPS {
            (segments - 1, STEPS)
        } else {
            (i / STEPS, i % STEPS)
        };
        let want = curve(seg, k as f64 / STEPS as f64).as_vec3();
        assert!(
            (*p - want).length() < 1e-5,
            "strand {strand} point {i}: {p} vs {want}"
        );
    }
}

/// Strands of bases.usda, in order: Linear (2), Bspline, CatmullRom (2), Bezier,
/// BsplinePinned, CatmullRomPinned.
#[test]
fn every_basis_follows_its_curve() {
    let g = fixture("bases.usda");
    assert_eq!(g.strand_count(), 8);
    let p = wiggle();
    // linear: the points themselves.
    assert_eq!(
        g.strand(0).positions,
        &[
            Vec3::new(0., 0., 0.),
            Vec3::new(1., 0., 1.),
            Vec3::new(0., 1., 2.)
        ]
    );
    assert_eq!(g.strand(1).positions.len(), 4);
    assert_strand(&g, 2, 4, |s, u| bspline(&p, 3.0 + s as f64 + u));
    assert_strand(&g, 3, 4, |s, u| catmull_rom(&p[s..s + 4], u));
    let shifted: Vec<DVec3> = p.iter().map(|q| *q + DVec3::X * 10.0).collect();
    assert_strand(&g, 4, 4, |s, u| catmull_rom(&shifted[s..s + 4], u));
    assert_strand(&g, 5, 2, |s, u| de_casteljau(&p[3 * s..3 * s + 4], u));
    let e = with_phantoms(&p);
    assert_strand(&g, 6, 6, |s, u| bspline(&e, 3.0 + s as f64 + u));
    assert_strand(&g, 7, 6, |s, u| catmull_rom(&e[s..s + 4], u));
    // pinned curves and Bézier pass through their end points; a plain B-spline does not.
    for strand in [5, 6, 7] {
        let s = g.strand(strand);
        assert!((s.positions[0] - Vec3::ZERO).length() < 1e-6);
        assert!((*s.positions.last().unwrap() - Vec3::new(1., 0., 6.)).length() < 1e-5);
    }
    assert!(g.strand(2).positions[0].length() > 0.1);
}

#[test]
fn widths_follow_each_interpolation() {
    let g = fixture("bases.usda");
    let close = |a: f32, b: f64| (f64::from(a) - b).abs() < 1e-6;
    // vertex, linear: one per point.
    assert_eq!(g.strand(0).thickness, &[0.1, 0.2, 0.3]);
    assert_eq!(g.strand(1).thickness, &[0.4, 0.5, 0.6, 0.7]);
    // varying, bspline: linear between segment ends 0.1, 0.2, … 0.5.
    let t = g.strand(2).thickness;
    for (i, w) in t.iter().enumerate() {
        assert!(close(*w, 0.1 + 0.1 * i as f64 / STEPS as f64), "{i}: {w}");
    }
    // uniform: one per curve.
    assert!(g.strand(3).thickness.iter().all(|&w| w == 0.25));
    assert!(g.strand(4).thickness.iter().all(|&w| w == 0.5));
    // constant.
    assert!(g.strand(5).thickness.iter().all(|&w| w == 0.3));
    // vertex, pinned bspline: the widths follow the basis like the points.
    let w: Vec<f64> = (1..=7).map(|i| 0.1 * i as f64).collect();
    let e = {
        let mut e = vec![2.0 * w[0] - w[1]];
        e.extend_from_slice(&w);
        e.push(2.0 * w[6] - w[5]);
        e
    };
    let as_points: Vec<DVec3> = e.iter().map(|&x| DVec3::splat(x)).collect();
    for (i, got) in g.strand(6).thickness.iter().enumerate() {
        let (s, k) = if i == 6 * STEPS {
            (5, STEPS)
        } else {
            (i / STEPS, i % STEPS)
        };
        let want = bspline(&as_points, 3.0 + s as f64 + k as f64 / STEPS as f64).x;
        assert!(close(*got, want), "{i}: {got} vs {want}");
    }
    // none authored: a human hair's 70 µm.
    assert!(g.strand(7).thickness.iter().all(|&w| w == 0.007));
}

fn absorption(g: &Groom) -> Vec<Absorption> {
    g.appearance()
        .iter()
        .map(|a| a.absorption.expect("every strand has one"))
        .collect()
}

fn mu_a_of_colour(c: [f64; 3]) -> Absorption {
    let m = mu_a_from_color(DVec3::from_array(c), COLOUR_BETA_N);
    Absorption::MuA(m.as_vec3().to_array())
}

#[test]
fn primvars_give_each_strand_its_absorption() {
    let a = absorption(&fixture("primvars.usda"));
    assert_eq!(a.len(), 10);
    let melanin = |eumelanin: f64, pheomelanin: f64| Absorption::Melanin {
        eumelanin: eumelanin as f32,
        pheomelanin: pheomelanin as f32,
    };
    // Blender: amount 0.5 and 0.9 (redness 0, 0.25) → −ln(1 − amount) split by redness.
    let c = -(0.1f64.ln());
    let blender = [melanin(2f64.ln(), 0.0), melanin(c * 0.75, c * 0.25)];
    for (got, want) in a[..2].iter().zip(blender) {
        let (
            Absorption::Melanin {
                eumelanin: e,
                pheomelanin: p,
            },
            Absorption::Melanin {
                eumelanin: we,
                pheomelanin: wp,
            },
        ) = (*got, want)
        else {
            panic!("{got:?}")
        };
        assert!(
            (e - we).abs() < 1e-5 && (p - wp).abs() < 1e-5,
            "{got:?} vs {want:?}"
        );
    }
    assert_eq!(a[2..4], [melanin(1.5, 0.0), melanin(0.25, 2.0)]);
    assert_eq!(
        a[4],
        mu_a_of_colour([0.800000011920929, 0.5, 0.20000000298023224])
    );
    assert_eq!(
        a[5],
        mu_a_of_colour([
            0.20000000298023224,
            0.10000000149011612,
            0.05000000074505806
        ])
    );
    // a per-point colour: the strand's mean.
    let Absorption::MuA(grey) = a[6] else {
        panic!()
    };
    let Absorption::MuA(want) = mu_a_of_colour([0.5; 3]) else {
        panic!()
    };
    assert_eq!(grey, want);
    let Absorption::MuA(mean) = a[7] else {
        panic!()
    };
    let Absorption::MuA(want) = mu_a_of_colour([0.2, 0.3, 0.4]) else {
        panic!()
    };
    assert!(
        (0..3).all(|i| (mean[i] - want[i]).abs() < 1e-5),
        "{mean:?} vs {want:?}"
    );
    // constant primvars: both strands.
    assert_eq!(a[8..], [melanin(3.0, 0.5), melanin(3.0, 0.5)]);
}

#[test]
fn prims_move_by_their_composed_transforms_into_centimetres_z_up() {
    // Y-up metres: Left is translated −0.1 m in x; Right is translate · rotateZ(90°) · scale 2.
    let g = fixture("transforms.usdc");
    let near = |a: Vec3, b: [f32; 3]| (a - Vec3::from_array(b)).length() < 1e-4;
    let left = g.strand(0).positions;
    assert!(
        near(left[0], [-10., 0., 0.]) && near(left[1], [-10., 0., 10.]),
        "{left:?}"
    );
    let right = g.strand(1).positions;
    assert!(
        near(right[0], [20., 0., 5.]) && near(right[1], [0., 0., 5.]),
        "{right:?}"
    );
    // widths scale with the units (0.01 cm) and the transform's scale (2).
    assert!((g.strand(0).thickness[0] - 0.01).abs() < 1e-7);
    assert!((g.strand(1).thickness[0] - 0.02).abs() < 1e-7);
}

#[test]
fn a_y_up_centimetre_groom_and_a_z_up_metre_groom_arrive_alike_and_upright() {
    let y = fixture("upright_y_cm.usda");
    let z = fixture("upright_z_m.usdc");
    let packaged = fixture("upright_z_m.usdz");
    let want = [[0., 0., 10.], [0., 1., 20.], [3., 0., 10.], [3., 1., 20.]];
    for g in [&y, &z, &packaged] {
        for (p, w) in g.positions().iter().zip(want) {
            assert!((*p - Vec3::from_array(w)).length() < 1e-5, "{p} vs {w:?}");
        }
        assert!(g.thickness().iter().all(|t| (t - 0.007).abs() < 1e-8));
        // upright: the strands rise along +z, and the bounds are a head's, not a ribbon's.
        let b = g.bounds();
        assert!(b.max.z - b.min.z > 9.0 && b.max.y - b.min.y < 2.0);
    }
}

/// An indexed primvar (`NAME:indices`) gives each curve the value its index picks.
#[test]
fn indexed_primvars_are_expanded() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("indexed.usda");
    std::fs::write(
        &path,
        "#usda 1.0\n(\n    upAxis = \"Z\"\n)\ndef BasisCurves \"H\"\n{\n    uniform token type = \"linear\"\n    int[] curveVertexCounts = [2, 2, 2]\n    point3f[] points = [(0,0,0), (0,0,1), (1,0,0), (1,0,1), (2,0,0), (2,0,1)]\n    color3f[] primvars:displayColor = [(0.5, 0.5, 0.5), (0.25, 0.25, 0.25)] (\n        interpolation = \"uniform\"\n    )\n    int[] primvars:displayColor:indices = [1, 0, 1]\n}\n",
    )
    .unwrap();
    let a = absorption(&Groom::read(&path).unwrap());
    let (dark, light) = (mu_a_of_colour([0.25; 3]), mu_a_of_colour([0.5; 3]));
    assert_eq!(a, [dark, light, dark]);
    let bad = std::fs::read_to_string(&path)
        .unwrap()
        .replace("[1, 0, 1]", "[1, 0, 2]");
    std::fs::write(&path, bad).unwrap();
    let e = Groom::read(&path).unwrap_err().to_string();
    assert!(e.contains("index 2, outside its 2 values"), "{e}");
}

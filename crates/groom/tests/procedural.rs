//! Procedural grooms: deterministic for a seed, the counts asked for, and each control doing
//! what it says.

use cuticle_groom::procedural::{GroomParams, Head, Preset, default_groom, generate};
use cuticle_groom::{Absorption, Groom};
use glam::Vec3;

fn small(preset: Preset, strands: usize, seed: u64) -> GroomParams {
    GroomParams {
        strands,
        seed,
        ..preset.params()
    }
}

/// Mean turning of the tangent per centimetre along the strands.
fn mean_curvature(groom: &Groom) -> f32 {
    let (mut turn, mut length) = (0.0, 0.0);
    for s in groom.strands() {
        for w in s.tangents.windows(2) {
            turn += w[0].angle_between(w[1]);
        }
        length += s.length;
    }
    turn / length
}

fn mean_tip_z(groom: &Groom) -> f32 {
    groom.strands().map(|s| s.tip().z).sum::<f32>() / groom.strand_count() as f32
}

#[test]
fn same_seed_gives_the_same_groom() {
    for preset in Preset::ALL {
        let params = small(preset, 600, 11);
        let (a, b) = (generate(&params).unwrap(), generate(&params).unwrap());
        assert_eq!(a, b, "{preset}");
    }
}

#[test]
fn different_seeds_give_different_grooms() {
    for preset in Preset::ALL {
        let a = generate(&small(preset, 300, 1)).unwrap();
        let b = generate(&small(preset, 300, 2)).unwrap();
        let moved = a
            .strands()
            .zip(b.strands())
            .filter(|(s, t)| s.root() != t.root())
            .count();
        assert!(moved > 290, "{preset}: only {moved} of 300 roots moved");
    }
}

#[test]
fn the_result_does_not_depend_on_the_thread_count() {
    let params = small(Preset::Wavy, 800, 5);
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| generate(&params).unwrap())
    };
    assert_eq!(on(1), on(3));
}

#[test]
fn grooms_have_the_counts_asked_for() {
    for (preset, strands) in [
        (Preset::Straight, 0),
        (Preset::Wavy, 1),
        (Preset::Curly, 7),
        (Preset::Straight, 1234),
    ] {
        let params = small(preset, strands, 3);
        let groom = generate(&params).unwrap();
        assert_eq!(groom.strand_count(), strands);
        assert_eq!(groom.appearance().len(), strands);
        let counts: Vec<usize> = groom.strands().map(|s| s.point_count()).collect();
        assert_eq!(counts.iter().sum::<usize>(), groom.point_count());
        assert!(
            counts
                .iter()
                .all(|n| (params.min_points..=params.max_points).contains(n))
        );
        if strands > 1000 {
            assert_eq!(counts.iter().min(), Some(&params.min_points));
            assert_eq!(counts.iter().max(), Some(&params.max_points));
        }
    }
}

#[test]
fn the_default_groom_is_ten_thousand_strands_of_20_to_30_points() {
    let groom = default_groom();
    assert_eq!(groom.strand_count(), 10_000);
    assert!(
        groom
            .strands()
            .all(|s| (20..=30).contains(&s.point_count()))
    );
    assert!(groom.positions().iter().all(|p| p.is_finite()));
    assert_eq!(groom, generate(&Preset::default().params()).unwrap());
}

#[test]
fn the_default_groom_looks_like_hair_on_a_head() {
    let groom = default_groom();
    let head = Head::default();
    let r = Vec3::from_array(head.radii);
    for s in groom.strands() {
        let root = s.root() / r;
        assert!((root.length() - 1.0).abs() < 1e-4, "roots on the scalp");
        assert!(root.z > -0.6, "no roots below the nape: {root}");
        assert!(
            s.positions.iter().all(|p| (*p / r).length() > 0.999),
            "outside the skull"
        );
    }
    let below_roots = groom.strands().filter(|s| s.tip().z < s.root().z).count();
    assert!(below_roots > 9_500, "hair falls toward −z: {below_roots}");
    let face = |p: &Vec3| p.y > 0.5 * r.y && p.x.abs() < 3.5 && (-6.0..2.0).contains(&p.z);
    let on_face = groom.positions().iter().filter(|p| face(p)).count();
    assert!(
        on_face < 20,
        "the face stays clear: {on_face} points in front of it"
    );
    let b = groom.bounds();
    assert!(
        b.max.z > r.z && b.min.z < -r.z,
        "hair reaches from the crown past the jaw"
    );
}

#[test]
fn strand_length_follows_the_length_control() {
    for length in [10.0, 30.0] {
        let params = GroomParams {
            length,
            ..small(Preset::Straight, 400, 9)
        };
        let groom = generate(&params).unwrap();
        let mean = groom.strand_lengths().iter().sum::<f32>() / 400.0;
        assert!(
            (mean / length - 1.0).abs() < 0.1,
            "asked {length}, got {mean}"
        );
    }
}

#[test]
fn gravity_pulls_tips_down() {
    let base = small(Preset::Straight, 400, 4);
    let light = generate(&GroomParams {
        gravity: 0.02,
        ..base.clone()
    })
    .unwrap();
    let heavy = generate(&GroomParams {
        gravity: 0.4,
        ..base
    })
    .unwrap();
    assert!(mean_tip_z(&heavy) < mean_tip_z(&light) - 3.0);
}

#[test]
fn waves_and_curls_bend_the_strands() {
    let curvature = |preset| mean_curvature(&generate(&small(preset, 400, 6)).unwrap());
    let (straight, wavy, curly) = (
        curvature(Preset::Straight),
        curvature(Preset::Wavy),
        curvature(Preset::Curly),
    );
    assert!(straight < wavy && wavy < curly, "{straight} {wavy} {curly}");
    let curled = GroomParams {
        curl_radius: 0.7,
        ..small(Preset::Straight, 400, 6)
    };
    assert!(mean_curvature(&generate(&curled).unwrap()) > 2.0 * straight);
}

#[test]
fn clumping_gathers_the_tips_of_a_clump() {
    let base = GroomParams {
        clump_size: 20,
        ..small(Preset::Straight, 400, 8)
    };
    let clumps = 20;
    let spread = |clumping| {
        let groom = generate(&GroomParams {
            clumping,
            ..base.clone()
        })
        .unwrap();
        let pairs = (0..400 - clumps).map(|i| {
            groom
                .strand(i)
                .tip()
                .distance(groom.strand(i + clumps).tip())
        });
        pairs.sum::<f32>() / (400 - clumps) as f32
    };
    assert!(spread(0.9) < 0.5 * spread(0.0));
}

#[test]
fn appearance_varies_between_strands_around_the_preset() {
    let params = small(Preset::Straight, 2000, 2);
    let groom = generate(&params).unwrap();
    let Some(Absorption::Melanin {
        eumelanin: base, ..
    }) = params.appearance.absorption
    else {
        panic!("the straight preset is melanin-based")
    };
    let values: Vec<f32> = groom
        .appearance()
        .iter()
        .map(|a| match a.absorption {
            Some(Absorption::Melanin { eumelanin, .. }) => eumelanin,
            other => panic!("unexpected absorption {other:?}"),
        })
        .collect();
    let mean = values.iter().sum::<f32>() / values.len() as f32;
    assert!((mean / base - 1.0).abs() < 0.1, "{mean} vs {base}");
    assert!(values.iter().any(|&v| v < 0.95 * base) && values.iter().any(|&v| v > 1.05 * base));
    assert!(
        groom
            .appearance()
            .iter()
            .all(|a| a.is_physical() && a.beta == params.appearance.beta)
    );
}

#[test]
fn a_painter_can_change_a_strand() {
    let mut groom = generate(&small(Preset::Straight, 10, 1)).unwrap();
    groom.appearance_mut()[3] = groom.appearance()[3].with_mu_a([0.1, 0.2, 0.3]);
    assert_eq!(
        groom.strand(3).appearance.absorption,
        Some(Absorption::MuA([0.1, 0.2, 0.3]))
    );
    assert_ne!(
        groom.strand(4).appearance.absorption,
        Some(Absorption::MuA([0.1, 0.2, 0.3]))
    );
}

#[test]
fn thickness_tapers_toward_the_tip() {
    let params = small(Preset::Straight, 50, 1);
    let groom = generate(&params).unwrap();
    for s in groom.strands() {
        assert_eq!(s.thickness[0], params.root_thickness);
        assert!((s.thickness[s.point_count() - 1] - params.tip_thickness).abs() < 1e-6);
        assert!(s.thickness.windows(2).all(|w| w[1] <= w[0]));
    }
}

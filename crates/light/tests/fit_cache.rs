//! The fit cache: a second fit of the same map and options is read back whole, and anything
//! else (another option, a turned map, another pixel, a spoiled entry) is fitted anew.

use cuticle_light::{
    EnvMap, FitCache, FitOptions, FitSource, SrbfLight, direction_from_angles, evaluate_lights,
    fit_srbf_cached,
};
use glam::Vec3;

fn map() -> EnvMap {
    let lights = [
        SrbfLight::new(
            direction_from_angles(0.5, 0.3).as_vec3(),
            0.3,
            Vec3::new(8.0, 7.0, 6.0),
        ),
        SrbfLight::new(
            direction_from_angles(-0.7, 2.0).as_vec3(),
            0.8,
            Vec3::new(0.3, 0.5, 0.9),
        ),
    ];
    EnvMap::from_fn(64, 32, |d| evaluate_lights(&lights, d).as_vec3())
}

fn options() -> FitOptions {
    FitOptions {
        lights: 3,
        fit_width: 64,
        refine_samples: 0,
        max_iterations: 20,
        ..FitOptions::default()
    }
}

fn fit(map: &EnvMap, options: &FitOptions, cache: &FitCache) -> (Vec<SrbfLight>, FitSource) {
    let (report, source) = fit_srbf_cached(map, options, Some(cache), &mut |_| {}).unwrap();
    (report.lights, source)
}

#[test]
fn the_same_fit_is_read_back_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    let cache = FitCache::at(dir.path());
    let (first, source) = fit(&map(), &options(), &cache);
    assert_eq!(source, FitSource::Fitted);
    let (again, source) = fit(&map(), &options(), &cache);
    assert_eq!(source, FitSource::Cached);
    assert_eq!(again, first, "f32 lights survive the JSON entry exactly");
}

#[test]
fn another_option_rotation_or_pixel_misses() {
    let dir = tempfile::tempdir().unwrap();
    let cache = FitCache::at(dir.path());
    fit(&map(), &options(), &cache);
    let more = FitOptions {
        lights: 4,
        ..options()
    };
    assert_eq!(fit(&map(), &more, &cache).1, FitSource::Fitted);
    assert_eq!(
        fit(&map().with_rotation(0.5), &options(), &cache).1,
        FitSource::Fitted
    );
    let mut pixels = map().pixels().to_vec();
    pixels[100].x += 1.0;
    let edited = EnvMap::new(64, 32, pixels);
    assert_eq!(fit(&edited, &options(), &cache).1, FitSource::Fitted);
    assert_eq!(fit(&map(), &options(), &cache).1, FitSource::Cached);
}

/// A truncated entry, one holding an invalid light, and one copied under another key are each
/// fitted anew (and the entry rewritten, so the next read hits).
#[test]
fn a_spoiled_entry_is_fitted_anew() {
    let dir = tempfile::tempdir().unwrap();
    let cache = FitCache::at(dir.path());
    let key = cuticle_light::fit_cache_key(&map(), &options());
    let entry = dir.path().join("fits").join(format!("{key}.json"));
    let (first, _) = fit(&map(), &options(), &cache);
    let good = std::fs::read_to_string(&entry).unwrap();
    let spoil: [&dyn Fn(&str) -> String; 3] = [
        &|s| s[..s.len() / 2].to_owned(),
        &|s| s.replacen("\"bandwidth\":", "\"bandwidth\":-", 1),
        &|s| s.replace(&key, "0123456789abcdef0123456789abcdef"),
    ];
    for (i, spoil) in spoil.iter().enumerate() {
        std::fs::write(&entry, spoil(&good)).unwrap();
        let (lights, source) = fit(&map(), &options(), &cache);
        assert_eq!(source, FitSource::Fitted, "spoil {i}");
        assert_eq!(lights, first, "spoil {i}: the fit is deterministic");
        assert_eq!(fit(&map(), &options(), &cache).1, FitSource::Cached);
    }
}

/// A cache folder that cannot be written is skipped, never an error.
#[test]
fn an_unwritable_cache_only_skips_storing() {
    let dir = tempfile::tempdir().unwrap();
    let blocked = dir.path().join("file");
    std::fs::write(&blocked, "not a folder").unwrap();
    let cache = FitCache::at(&blocked);
    assert_eq!(fit(&map(), &options(), &cache).1, FitSource::Fitted);
    assert_eq!(fit(&map(), &options(), &cache).1, FitSource::Fitted);
}

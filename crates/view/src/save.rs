//! Saving a look as a set of files that reopens it exactly (`cuticle view --scene` or
//! `cuticle render --scene` on the `scene.toml`):
//!
//! - `groom.hair`: the groom's geometry (cyHair), with the points it is shaded at (the scene
//!   says `shading_points = false`, so that reopening adds none);
//! - `groom.absorption.json`: every strand's absorption as the renderer reads it, paint
//!   included ([`cuticle_groom::strand_absorption`]);
//! - `groom.usda`: the same groom as USD `BasisCurves` for other tools (Houdini, Blender), each
//!   strand's absorption as per-curve primvars: `sigma_a` for every strand (the μ_a it is
//!   shaded with, the scene's default where it has none of its own), and `eumelanin` /
//!   `pheomelanin` (and Blender's `melanin` / `melanin_redness`) where it came with melanin
//!   ([`cuticle_groom::usd::write`]);
//! - `scene.toml`: the scene's settings, naming the two files above by absolute path, the
//!   camera as it stands, the environment map and its rotation (the lights are fitted again on
//!   opening, deterministically, as they were for this view).
//!
//! The set is written whole (docs/conventions.md §9): staged in a folder beside the target, then
//! swapped in; a target that holds anything but an earlier set is refused.

use crate::look::Look;
use std::path::{Path, PathBuf};

pub const SCENE: &str = "scene.toml";
pub const GROOM: &str = "groom.hair";
pub const ABSORPTION: &str = "groom.absorption.json";
pub const GROOM_USD: &str = "groom.usda";

/// The files of a saved look, as (name, bytes).
pub fn look_files(look: &Look, dir: &Path) -> Result<Vec<(&'static str, Vec<u8>)>, String> {
    let scene = look.scene();
    let groom = scene
        .groom
        .to_hair_bytes("cuticle view: painted groom")
        .map_err(|e| format!("cannot encode the groom: {e}"))?;
    let absorption = cuticle_groom::strand_absorption::to_bytes(&scene.groom);
    let usd = usd_bytes(&scene.groom, scene.spec.hair.default_mu_a)?;
    let mut spec = scene.spec.clone();
    spec.groom = dir.join(GROOM).display().to_string();
    // groom.hair holds the points the view shades: reopened, it keeps them.
    spec.shading_points = false;
    spec.strand_absorption = Some(dir.join(ABSORPTION).display().to_string());
    spec.camera = Some(scene.camera);
    if Path::new(&spec.env).exists() {
        spec.env = absolute(Path::new(&spec.env)).display().to_string();
    }
    let toml = toml::to_string(&spec).map_err(|e| format!("cannot write the scene: {e}"))?;
    let text = format!(
        "# Saved by cuticle view: reopen with `cuticle view --scene {}`.\n{toml}",
        dir.join(SCENE).display()
    );
    Ok(vec![
        (GROOM, groom),
        (ABSORPTION, absorption),
        (GROOM_USD, usd),
        (SCENE, text.into_bytes()),
    ])
}

/// The groom as USD, every strand with the absorption it is shaded with: its own, else the
/// scene's default μ_a.
fn usd_bytes(groom: &cuticle_groom::Groom, default_mu_a: [f64; 3]) -> Result<Vec<u8>, String> {
    let mut groom = groom.clone();
    let fallback = cuticle_groom::Absorption::MuA(default_mu_a.map(|c| c as f32));
    for a in groom.appearance_mut() {
        a.absorption = a.absorption.or(Some(fallback));
    }
    cuticle_groom::usd::to_usd_bytes(&groom, cuticle_groom::usd::UsdFormat::Usda)
        .map_err(|e| format!("cannot encode the groom as USD: {e}"))
}

/// Saves `look` into the folder `dir` (made absolute); returns the scene file's path.
pub fn save_look(look: &Look, dir: &Path) -> Result<PathBuf, String> {
    let dir = absolute(dir);
    let files = look_files(look, &dir)?;
    write_set(&dir, &files)?;
    Ok(dir.join(SCENE))
}

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// Writes `files` as the whole content of `dir`, replacing an earlier set.
fn write_set(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<(), String> {
    let names: Vec<&str> = files.iter().map(|f| f.0).collect();
    if dir.exists() {
        let entries =
            std::fs::read_dir(dir).map_err(|e| format!("cannot read {}: {e}", dir.display()))?;
        for entry in entries.flatten() {
            let name = entry.file_name();
            if !names.iter().any(|n| name == std::ffi::OsStr::new(n)) {
                return Err(format!(
                    "{} holds {} which a saved look does not: choose an empty folder",
                    dir.display(),
                    name.to_string_lossy()
                ));
            }
        }
    }
    let parent = dir.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent)
        .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    let leaf = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let stage = parent.join(format!(".{leaf}.saving-{}", std::process::id()));
    let old = parent.join(format!(".{leaf}.old-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&stage);
    let staged = std::fs::create_dir(&stage)
        .map_err(|e| e.to_string())
        .and_then(|_| {
            files.iter().try_for_each(|(name, bytes)| {
                std::fs::write(stage.join(name), bytes)
                    .map_err(|e| format!("cannot write {name}: {e}"))
            })
        });
    if let Err(e) = staged {
        let _ = std::fs::remove_dir_all(&stage);
        return Err(format!("cannot save into {}: {e}", dir.display()));
    }
    let had_old = dir.exists();
    if had_old {
        std::fs::rename(dir, &old).map_err(|e| format!("cannot replace {}: {e}", dir.display()))?;
    }
    if let Err(e) = std::fs::rename(&stage, dir) {
        if had_old {
            let _ = std::fs::rename(&old, dir);
        }
        let _ = std::fs::remove_dir_all(&stage);
        return Err(format!("cannot save into {}: {e}", dir.display()));
    }
    if had_old {
        let _ = std::fs::remove_dir_all(&old);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_groom::procedural::{GroomParams, Preset, generate};
    use cuticle_groom::{Absorption, Groom};
    use cuticle_light::EnvMap;
    use cuticle_render::scene::{Scene, SceneSpec};

    /// A saved look's groom.usda holds each strand's absorption: painted μ_a, the groom's own
    /// melanin, or the scene's default μ_a; and the set is written whole with it.
    #[test]
    fn the_saved_set_holds_the_painted_groom_as_usd() {
        let mut groom = generate(&GroomParams {
            strands: 12,
            ..Preset::Straight.params()
        })
        .unwrap();
        for (s, a) in groom.appearance_mut().iter_mut().enumerate() {
            a.absorption = (s % 2 == 0).then_some(Absorption::Melanin {
                eumelanin: 1.25,
                pheomelanin: 0.5,
            });
        }
        let env = EnvMap::new(16, 8, vec![glam::Vec3::ONE; 16 * 8]);
        let spec = SceneSpec::default();
        let default_mu_a = spec.hair.default_mu_a.map(|c| c as f32);
        let mut look = Look::from_scene(Scene::from_parts(spec, groom, env, Vec::new()));
        let painted = Absorption::MuA([0.5, 0.25, 0.125]);
        look.paint[3] = Some(painted);
        look.paint[4] = Some(painted);
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path().join("look");
        save_look(&look, &dir).unwrap();
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, [ABSORPTION, GROOM, GROOM_USD, SCENE]);
        let usd = Groom::read(dir.join(GROOM_USD)).unwrap();
        let hair = Groom::read(dir.join(GROOM)).unwrap();
        assert_eq!(usd.positions(), hair.positions());
        assert_eq!(usd.thickness(), hair.thickness());
        for (s, a) in usd.appearance().iter().enumerate() {
            let want = match s {
                3 | 4 => painted,
                s if s % 2 == 0 => Absorption::Melanin {
                    eumelanin: 1.25,
                    pheomelanin: 0.5,
                },
                _ => Absorption::MuA(default_mu_a),
            };
            assert_eq!(a.absorption, Some(want), "strand {s}");
        }
    }
}

//! The look being developed: everything the window edits, from which each frame's [`Scene`] is
//! built. Absorption comes in three layers, the first set of which a strand shows:
//! its paint ([`Look::paint`]), the absorption set for all strands ([`Look::all_strands`]), and
//! the groom's own (melanin per strand for the procedural grooms). The scene handed to the
//! renderer carries the result in each strand's appearance, and no global μ_a override.

use cuticle_groom::{Absorption, Groom};
use cuticle_light::{EnvMap, SrbfLight};
use cuticle_render::scene::hair::mu_a_of;
use cuticle_render::{Scene, SceneSpec};
use glam::DVec3;
use std::sync::Arc;

/// Counters bumped when what a preparation depends on is replaced (a camera move is seen in
/// the spec itself).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Revisions {
    pub groom: u64,
    pub lights: u64,
}

/// The edited scene.
#[derive(Clone, Debug)]
pub struct Look {
    /// The scene's settings; its camera is always set and its `hair.mu_a` always `None`.
    pub spec: SceneSpec,
    /// Geometry and each strand's own appearance, as loaded.
    pub groom: Arc<Groom>,
    pub env: Arc<EnvMap>,
    pub lights: Arc<Vec<SrbfLight>>,
    /// Relative L2 error of the SRBF fit, when fitted.
    pub fit_error: Option<f64>,
    /// Absorption of every strand, over the groom's own; `None` shows the groom's own.
    pub all_strands: Option<Absorption>,
    /// Painted absorption per strand, over everything else.
    pub paint: Vec<Option<Absorption>>,
    pub revisions: Revisions,
}

impl Look {
    /// The look of a loaded scene: its global μ_a override, if any, becomes the absorption of
    /// all strands, and nothing is painted.
    pub fn from_scene(mut scene: Scene) -> Self {
        let all_strands = scene
            .spec
            .hair
            .mu_a
            .take()
            .map(|m| Absorption::MuA([m[0] as f32, m[1] as f32, m[2] as f32]));
        scene.spec.camera = Some(scene.camera);
        let paint = vec![None; scene.groom.strand_count()];
        Self {
            spec: scene.spec,
            groom: Arc::new(scene.groom),
            env: Arc::new(scene.env),
            lights: Arc::new(scene.lights),
            fit_error: scene.fit_error,
            all_strands,
            paint,
            revisions: Revisions::default(),
        }
    }

    /// The absorption strand `s` shows, before paint.
    pub fn base_absorption(&self, s: usize) -> Option<Absorption> {
        self.all_strands
            .or_else(|| self.groom.appearance().get(s).and_then(|a| a.absorption))
    }

    /// μ_a per unit radius of strand `s` as the renderer reads it.
    pub fn mu_a(&self, s: usize) -> DVec3 {
        let a = self
            .paint
            .get(s)
            .copied()
            .flatten()
            .or(self.base_absorption(s));
        match a {
            Some(a) => mu_a_of(a),
            None => DVec3::from_array(self.spec.hair.default_mu_a),
        }
    }

    /// The scene of this look: the groom's appearance carries each strand's absorption.
    pub fn scene(&self) -> Scene {
        let mut groom = (*self.groom).clone();
        let strands = groom.strand_count();
        let absorption: Vec<_> = (0..strands)
            .map(|s| {
                self.paint
                    .get(s)
                    .copied()
                    .flatten()
                    .or(self.base_absorption(s))
            })
            .collect();
        for (appearance, a) in groom.appearance_mut().iter_mut().zip(absorption) {
            appearance.absorption = a;
        }
        let mut spec = self.spec.clone();
        spec.hair.mu_a = None;
        Scene::from_parts(spec, groom, (*self.env).clone(), (*self.lights).clone())
    }
}

/// An absorption given as μ_a.
pub fn mu_a(s: DVec3) -> Absorption {
    Absorption::MuA([s.x as f32, s.y as f32, s.z as f32])
}

/// μ_a of what an absorption editor shows (the default μ_a for the strands' own).
pub fn mu_a_of_edit(edit: &crate::app::AbsorptionEdit) -> DVec3 {
    edit.absorption().map(mu_a_of).unwrap_or(DVec3::from_array(
        cuticle_render::HairParams::default().default_mu_a,
    ))
}

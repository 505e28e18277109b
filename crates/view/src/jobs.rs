//! Background loads the window waits for without blocking: the first scene (groom, map, SRBF
//! fit), a groom chosen later, an environment map or light count re-fitted. One job runs at a
//! time per kind; a newer job of a kind makes the older one's result stale (it is dropped).

use crate::look::Look;
use cuticle_groom::Groom;
use cuticle_light::{EnvMap, FitCache, FitOptions, FitProgress, SrbfLight, fit_srbf_cached};
use cuticle_render::{Scene, SceneSpec};
use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, channel};

/// What a finished job hands back.
pub enum Loaded {
    /// The first scene.
    Scene(Box<Look>),
    /// A groom, with the name it was loaded by.
    Groom { name: String, groom: Box<Groom> },
    /// An environment and its fitted lights.
    Lights {
        env: Box<EnvMap>,
        lights: Vec<SrbfLight>,
        fit_error: f64,
    },
}

/// A job in flight: its result and its progress in [0, 1] (as f32 bits).
pub struct Job {
    pub what: String,
    result: Receiver<Result<Loaded, String>>,
    progress: Arc<AtomicU32>,
}

impl Job {
    fn spawn(
        what: String,
        notify: impl Fn() + Send + 'static,
        work: impl FnOnce(&dyn Fn(f32)) -> Result<Loaded, String> + Send + 'static,
    ) -> Self {
        let (tx, result) = channel();
        let progress = Arc::new(AtomicU32::new(0));
        let p = progress.clone();
        let spawned = std::thread::Builder::new()
            .name("cuticle-view load".into())
            .spawn(move || {
                let report = |f: f32| p.store(f.clamp(0.0, 1.0).to_bits(), Ordering::Relaxed);
                let outcome =
                    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| work(&report)))
                        .unwrap_or_else(|_| Err("the load failed unexpectedly".into()));
                let _ = tx.send(outcome);
                notify();
            });
        if let Err(e) = spawned {
            let (tx, rx) = channel();
            let _ = tx.send(Err(format!("cannot start a thread: {e}")));
            return Self {
                what,
                result: rx,
                progress,
            };
        }
        Self {
            what,
            result,
            progress,
        }
    }

    /// Progress in [0, 1].
    pub fn progress(&self) -> f32 {
        f32::from_bits(self.progress.load(Ordering::Relaxed))
    }

    /// The result, once there is one.
    pub fn poll(&self) -> Option<Result<Loaded, String>> {
        self.result.try_recv().ok()
    }
}

/// Loads a whole scene as `cuticle render` would (groom, map, fit unless `lights` are given).
pub fn load_scene(
    spec: SceneSpec,
    lights: Option<Vec<SrbfLight>>,
    notify: impl Fn() + Send + 'static,
) -> Job {
    Job::spawn("loading the scene".into(), notify, move |_| {
        let scene = Scene::load(spec, lights).map_err(|e| e.to_string())?;
        Ok(Loaded::Scene(Box::new(Look::from_scene(scene))))
    })
}

/// Loads a groom preset or `.hair` file.
pub fn load_groom(name: String, strands: usize, notify: impl Fn() + Send + 'static) -> Job {
    Job::spawn(format!("loading groom {name}"), notify, move |_| {
        let groom = cuticle_render::scene::load_groom(&name, strands).map_err(|e| e.to_string())?;
        // As Scene::load does, so that the window shades the points a render shades.
        let groom = cuticle_render::scene::resample::shading_points(groom);
        if groom.strand_count() == 0 {
            return Err(format!("groom {name} has no strands"));
        }
        Ok(Loaded::Groom {
            name,
            groom: Box::new(groom),
        })
    })
}

/// Loads `env` (unless `current` is that map already), rotates it by `rotate_deg` and fits
/// `lights` SRBF lights, as [`Scene::load`] does, reporting the fit's iterations.
pub fn fit_lights(
    env: String,
    current: Option<Arc<EnvMap>>,
    rotate_deg: f64,
    lights: usize,
    notify: impl Fn() + Send + 'static,
) -> Job {
    Job::spawn(
        format!("fitting {lights} SRBF lights"),
        notify,
        move |report| {
            let map = match current {
                Some(map) => (*map).clone(),
                None => cuticle_render::scene::load_env(&env).map_err(|e| format!("{env}: {e}"))?,
            }
            .with_rotation(rotate_deg.to_radians());
            let options = FitOptions {
                lights,
                ..FitOptions::default()
            };
            let mut progress = |p: FitProgress| {
                if let FitProgress::Iteration {
                    iteration,
                    max_iterations,
                    ..
                } = p
                {
                    report(iteration as f32 / max_iterations.max(1) as f32);
                }
            };
            let cache = FitCache::from_env();
            let (fit, _) = fit_srbf_cached(&map, &options, cache.as_ref(), &mut progress)
                .map_err(|e| format!("fit: {e}"))?;
            Ok(Loaded::Lights {
                env: Box::new(map),
                lights: fit.lights,
                fit_error: fit.relative_l2,
            })
        },
    )
}

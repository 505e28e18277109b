//! The fiber model of each strand: Marschner 2003 from the scene's hair parameters and each
//! strand's absorption (exactly what `--method srbf|brute` shade with, through
//! [`HairParams::fiber`]), or one model of the fiber crate for the whole groom.

use cuticle_fiber::models::marschner2003::MarschnerError;
use cuticle_fiber::{FiberModel, Marschner2003};
use cuticle_render::{HairParams, Scene};
use std::collections::HashMap;

/// One model per distinct parameter set, and which one each strand uses.
pub struct StrandModels {
    models: Vec<Box<dyn FiberModel>>,
    of_strand: Vec<u32>,
}

impl StrandModels {
    /// One model for every strand.
    pub fn uniform(model: Box<dyn FiberModel>, strands: usize) -> Self {
        Self {
            models: vec![model],
            of_strand: vec![0; strands],
        }
    }

    /// Marschner 2003 with the scene's hair parameters, per strand as the SRBF renderer reads
    /// them (its absorption from the groom's appearance unless the scene sets one for all).
    pub fn marschner(scene: &Scene) -> Result<Self, MarschnerError> {
        Self::marschner_with(&scene.spec.hair, scene)
    }

    fn marschner_with(hair: &HairParams, scene: &Scene) -> Result<Self, MarschnerError> {
        let mut index: HashMap<String, u32> = HashMap::new();
        let mut models: Vec<Box<dyn FiberModel>> = Vec::new();
        let mut of_strand = Vec::with_capacity(scene.groom.strand_count());
        for s in 0..scene.groom.strand_count() {
            let params = hair.fiber(scene.groom.appearance().get(s));
            let key = format!("{params:?}");
            let k = match index.get(&key) {
                Some(&k) => k,
                None => {
                    models.push(Box::new(Marschner2003::new(params)?));
                    index.insert(key, models.len() as u32 - 1);
                    models.len() as u32 - 1
                }
            };
            of_strand.push(k);
        }
        if models.is_empty() {
            models.push(Box::new(Marschner2003::new(hair.fiber(None))?));
        }
        Ok(Self { models, of_strand })
    }

    /// The model of strand `s`.
    pub fn of(&self, strand: u32) -> &dyn FiberModel {
        let k = self.of_strand.get(strand as usize).copied().unwrap_or(0);
        self.models[k as usize].as_ref()
    }

    /// Distinct models (parameter sets).
    pub fn count(&self) -> usize {
        self.models.len()
    }

    /// The name of the (first) model, as the command line spells it.
    pub fn name(&self) -> &'static str {
        self.models[0].name()
    }
}

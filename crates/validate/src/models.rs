//! The models a validation compares (the fiber crate's [`ModelId`]s), built from a
//! simulated configuration's parameters (α in radians, with the simulator's sign: positive α
//! tilts the scales toward +u, `cuticle_sim` crate docs).

use crate::error::ValidateError;
use cuticle_fiber::{BuildOptions, FiberModel, FiberParams, ModelId};

/// The model `id` for `params`, on its tabulated azimuthal fast path.
pub fn build_model(
    id: ModelId,
    params: &FiberParams,
) -> Result<Box<dyn FiberModel>, ValidateError> {
    id.build(params, &BuildOptions::default())
        .map_err(|e| ValidateError::Model {
            model: id.name(),
            message: e.to_string(),
        })
}

/// A comma-separated list of the fiber crate's model names, such as `nonseparable,deon2011`.
pub fn parse_models(list: &str) -> Result<Vec<ModelId>, ValidateError> {
    let mut out = Vec::new();
    for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let id = name
            .parse()
            .map_err(|_| ValidateError::UnknownModel(name.to_string()))?;
        if !out.contains(&id) {
            out.push(id);
        }
    }
    if out.is_empty() {
        return Err(ValidateError::UnknownModel(list.to_string()));
    }
    Ok(out)
}

/// The models of one fiber, each built on first use and kept while the configurations that
/// follow share that fiber: a validation visits its configurations grouped by fiber
/// ([`crate::sweep_dir::fiber_order`]), so each model is tabulated once per fiber instead of
/// once per inclination θ_i (the tables, not the comparison, were most of a validation's
/// time).
#[derive(Default)]
pub struct FiberModels {
    params: Option<FiberParams>,
    built: Vec<(ModelId, Box<dyn FiberModel>)>,
    builds: usize,
}

impl FiberModels {
    /// `kind` for `params`: the one built before if the fiber is the same, else a new one (and
    /// the previous fiber's models are dropped).
    pub fn get(
        &mut self,
        kind: ModelId,
        params: &FiberParams,
    ) -> Result<&dyn FiberModel, ValidateError> {
        if self.params.as_ref() != Some(params) {
            self.built.clear();
            self.params = Some(*params);
        }
        let at = match self.built.iter().position(|(k, _)| *k == kind) {
            Some(at) => at,
            None => {
                self.built.push((kind, build_model(kind, params)?));
                self.builds += 1;
                self.built.len() - 1
            }
        };
        Ok(self.built[at].1.as_ref())
    }

    /// How many models have been built so far.
    pub fn builds(&self) -> usize {
        self.builds
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_fiber::FiberAngles;

    /// A model is built once per fiber and kind, and is the model `build` makes.
    #[test]
    fn fiber_models_build_each_model_once_per_fiber() {
        let fiber = FiberParams::default();
        let other = FiberParams {
            beta: 0.08,
            ..fiber
        };
        let (wi, wo) = (FiberAngles::new(0.3, 0.0), FiberAngles::new(-0.5, 2.0));
        let fresh = build_model(ModelId::Marschner, &fiber)
            .unwrap()
            .eval(wi, wo);
        let mut models = FiberModels::default();
        for _ in 0..3 {
            let kept = models.get(ModelId::Marschner, &fiber).unwrap();
            assert_eq!(kept.eval(wi, wo), fresh);
        }
        assert_eq!(models.builds(), 1);
        models.get(ModelId::DEon2011, &fiber).unwrap();
        models.get(ModelId::Marschner, &fiber).unwrap();
        assert_eq!(models.builds(), 2);
        let changed = models.get(ModelId::Marschner, &other).unwrap().eval(wi, wo);
        assert_ne!(changed, fresh);
        models.get(ModelId::Marschner, &fiber).unwrap();
        assert_eq!(
            models.builds(),
            4,
            "a fiber met again after another is built again"
        );
    }
}

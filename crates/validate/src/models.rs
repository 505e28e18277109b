//! The models a validation compares, by the names the command line uses, built from a
//! simulated configuration's parameters (α in radians, with the simulator's sign: positive α
//! tilts the scales toward +u, `cuticle_sim` crate docs).

use crate::error::ValidateError;
use cuticle_fiber::{DEon2011, FiberModel, FiberParams, Marschner2003, NonSeparable};
use std::str::FromStr;

/// A model under validation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ModelKind {
    /// With the losses of tilted scales (the fiber crate's default non-separable model).
    NonSeparable,
    /// As d'Eon et al. 2014 specifies it.
    NonSeparablePaper,
    DEon2011,
    Marschner,
}

impl ModelKind {
    pub const ALL: [ModelKind; 4] = [
        ModelKind::NonSeparable,
        ModelKind::NonSeparablePaper,
        ModelKind::DEon2011,
        ModelKind::Marschner,
    ];

    /// The command-line name.
    pub const fn name(self) -> &'static str {
        match self {
            ModelKind::NonSeparable => "nonseparable",
            ModelKind::NonSeparablePaper => "nonseparable-paper",
            ModelKind::DEon2011 => "deon2011",
            ModelKind::Marschner => "marschner",
        }
    }

    /// The model for `params`, each on its tabulated azimuthal fast path.
    pub fn build(self, params: &FiberParams) -> Result<Box<dyn FiberModel>, ValidateError> {
        let err = |message: String| ValidateError::Model {
            model: self.name(),
            message,
        };
        Ok(match self {
            ModelKind::NonSeparable => Box::new(
                NonSeparable::new(*params)
                    .map_err(|e| err(e.to_string()))?
                    .tabulated(),
            ),
            ModelKind::NonSeparablePaper => Box::new(
                NonSeparable::paper(*params)
                    .map_err(|e| err(e.to_string()))?
                    .tabulated(),
            ),
            ModelKind::DEon2011 => Box::new(
                DEon2011::new(*params)
                    .map_err(|e| err(e.to_string()))?
                    .tabulated(),
            ),
            ModelKind::Marschner => Box::new(
                Marschner2003::from_fiber(params)
                    .map_err(|e| err(e.to_string()))?
                    .tabulated(),
            ),
        })
    }

    /// A comma-separated list such as `nonseparable,deon2011`.
    pub fn parse_list(list: &str) -> Result<Vec<ModelKind>, ValidateError> {
        let mut out = Vec::new();
        for name in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let kind = name.parse()?;
            if !out.contains(&kind) {
                out.push(kind);
            }
        }
        if out.is_empty() {
            return Err(ValidateError::UnknownModel(list.to_string()));
        }
        Ok(out)
    }
}

/// The models of one fiber, each built on first use and kept while the configurations that
/// follow share that fiber: a validation visits its configurations grouped by fiber
/// ([`crate::sweep_dir::fiber_order`]), so each model is tabulated once per fiber instead of
/// once per inclination θ_i (the tables, not the comparison, were most of a validation's
/// time).
#[derive(Default)]
pub struct FiberModels {
    params: Option<FiberParams>,
    built: Vec<(ModelKind, Box<dyn FiberModel>)>,
    builds: usize,
}

impl FiberModels {
    /// `kind` for `params`: the one built before if the fiber is the same, else a new one (and
    /// the previous fiber's models are dropped).
    pub fn get(
        &mut self,
        kind: ModelKind,
        params: &FiberParams,
    ) -> Result<&dyn FiberModel, ValidateError> {
        if self.params.as_ref() != Some(params) {
            self.built.clear();
            self.params = Some(*params);
        }
        let at = match self.built.iter().position(|(k, _)| *k == kind) {
            Some(at) => at,
            None => {
                self.built.push((kind, kind.build(params)?));
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

impl FromStr for ModelKind {
    type Err = ValidateError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ModelKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| ValidateError::UnknownModel(s.to_string()))
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
        let fresh = ModelKind::Marschner.build(&fiber).unwrap().eval(wi, wo);
        let mut models = FiberModels::default();
        for _ in 0..3 {
            let kept = models.get(ModelKind::Marschner, &fiber).unwrap();
            assert_eq!(kept.eval(wi, wo), fresh);
        }
        assert_eq!(models.builds(), 1);
        models.get(ModelKind::DEon2011, &fiber).unwrap();
        models.get(ModelKind::Marschner, &fiber).unwrap();
        assert_eq!(models.builds(), 2);
        let changed = models
            .get(ModelKind::Marschner, &other)
            .unwrap()
            .eval(wi, wo);
        assert_ne!(changed, fresh);
        models.get(ModelKind::Marschner, &fiber).unwrap();
        assert_eq!(
            models.builds(),
            4,
            "a fiber met again after another is built again"
        );
    }
}

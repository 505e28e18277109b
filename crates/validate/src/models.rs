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

impl FromStr for ModelKind {
    type Err = ValidateError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ModelKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| ValidateError::UnknownModel(s.to_string()))
    }
}

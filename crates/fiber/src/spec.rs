//! A model as a user names it: the registry's [`ModelId`], the fiber's parameters (its
//! absorption given as μ_a or as melanin, [`absorption`]) and the build options, checked in one
//! place ([`ModelSpec::build`]) for every front end (the command line, the Python bindings).

use crate::model::FiberModel;
use crate::optics::absorption::mu_a_from_melanin;
use crate::params::FiberParams;
use crate::ranges::{self, RangeError};
use crate::registry::{BuildOptions, ModelId};
use glam::DVec3;
use thiserror::Error;

/// Why a named model cannot be built: one sentence.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SpecError {
    /// A parameter outside its range ([`crate::ranges`]).
    #[error(transparent)]
    Range(#[from] RangeError),
    /// μ_a and melanin both given.
    #[error("mu_a and melanin (eumelanin, pheomelanin) both set the absorption; give one")]
    TwoAbsorptions,
    /// The fiber's parameters map to Marschner 2003 parameters outside their ranges.
    #[error("Marschner 2003 parameters: {0}")]
    Marschner(RangeError),
}

/// The absorption μ_a: `mu_a` as given, else from melanin (each concentration checked against
/// [`ranges::MELANIN`], an absent one 0; d'Eon et al. 2011's coefficients), else `default`.
/// μ_a itself is checked with the other parameters ([`FiberParams::validate`]).
pub fn absorption(
    mu_a: Option<[f64; 3]>,
    eumelanin: Option<f64>,
    pheomelanin: Option<f64>,
    default: DVec3,
) -> Result<DVec3, SpecError> {
    Ok(match (mu_a, eumelanin, pheomelanin) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => return Err(SpecError::TwoAbsorptions),
        (Some(m), _, _) => DVec3::from_array(m),
        (None, None, None) => default,
        (None, eu, pheo) => {
            let eu = ranges::MELANIN
                .named("eumelanin")
                .check(eu.unwrap_or(0.0))?;
            let pheo = ranges::MELANIN
                .named("pheomelanin")
                .check(pheo.unwrap_or(0.0))?;
            mu_a_from_melanin(eu, pheo)
        }
    })
}

/// A model of the registry for one fiber.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelSpec {
    pub model: ModelId,
    pub params: FiberParams,
    pub options: BuildOptions,
}

impl ModelSpec {
    /// Every parameter against its range: the fiber's ([`FiberParams::validate`]) and the
    /// fixed-point iterations ([`ranges::ITERATIONS`]).
    pub fn check(&self) -> Result<(), SpecError> {
        self.params.validate()?;
        ranges::ITERATIONS.check(self.options.iterations.into())?;
        Ok(())
    }

    /// The model, once [`ModelSpec::check`] passes; Marschner 2003's own ranges are named as
    /// its parameters.
    pub fn build(&self) -> Result<Box<dyn FiberModel>, SpecError> {
        self.check()?;
        self.model
            .build(&self.params, &self.options)
            .map_err(|e| match self.model {
                ModelId::Marschner => SpecError::Marschner(e),
                _ => SpecError::Range(e),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absorption_takes_one_source_and_checks_melanin() {
        let default = DVec3::splat(0.3);
        assert_eq!(absorption(None, None, None, default), Ok(default));
        assert_eq!(
            absorption(Some([0.1, 0.2, 0.3]), None, None, default),
            Ok(DVec3::new(0.1, 0.2, 0.3))
        );
        assert_eq!(
            absorption(None, Some(1.0), None, default),
            Ok(mu_a_from_melanin(1.0, 0.0))
        );
        assert_eq!(
            absorption(Some([0.1; 3]), None, Some(1.0), default),
            Err(SpecError::TwoAbsorptions)
        );
        let e = absorption(None, Some(f64::NAN), None, default).unwrap_err();
        assert!(e.to_string().starts_with("eumelanin must be"), "{e}");
    }

    #[test]
    fn build_checks_every_range() {
        let spec = ModelSpec {
            model: ModelId::DEon2011,
            params: FiberParams::default(),
            options: BuildOptions::default(),
        };
        assert!(spec.build().is_ok());
        let mut bad = spec;
        bad.options.iterations = 0;
        assert!(
            bad.build()
                .err()
                .unwrap()
                .to_string()
                .starts_with("iterations must be")
        );
        bad = spec;
        bad.params.beta = f64::NAN;
        assert!(
            bad.build()
                .err()
                .unwrap()
                .to_string()
                .starts_with("beta must be")
        );
    }
}

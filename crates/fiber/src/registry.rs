//! Every model of the crate by the name the command line, the validation, the path tracer and
//! the benches use: [`ModelId`] parses a name, lists them all and builds the model for a
//! fiber's parameters, on its tabulated fast path or evaluated directly ([`Tabulation`]).
//! Adding a model is its folder under `models/` (with its `pub mod` line in `models/mod.rs`),
//! its variant of [`ModelId`] and its line in `REGISTRY`.

use crate::model::FiberModel;
use crate::models::chiang2016::Chiang2016;
use crate::models::deon2011::DEon2011;
use crate::models::marschner2003::Marschner2003;
use crate::models::nonseparable::{DEFAULT_ITERATIONS, NonSeparable};
use crate::params::{FiberParams, ParamError};
use std::fmt;
use std::str::FromStr;

/// A model of the crate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ModelId {
    /// The non-separable model with what tilted scales and a rough surface do (this
    /// project's extension, `models/nonseparable`).
    NonSeparable,
    /// The non-separable model as d'Eon et al. 2014 specifies it.
    NonSeparablePaper,
    /// d'Eon et al. 2011 (`models/deon2011`).
    DEon2011,
    /// Marschner et al. 2003, its parameters from the fiber's (`models/marschner2003`).
    Marschner,
    /// Chiang et al. 2016, far field (`models/chiang2016`).
    Chiang2016,
}

/// Whether a model reads its tables (built once per parameter set) or integrates at every call.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tabulation {
    /// The fast path: what renderers use.
    Tabulated,
    /// Quadrature over h (Marschner 2003: its cubics solved) at every evaluation: the
    /// reference the tables are measured against.
    Direct,
}

/// What a model needs beyond the fiber's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildOptions {
    pub tabulation: Tabulation,
    /// Fixed-point iterations per sample of the non-separable models.
    pub iterations: u32,
    /// Chiang 2016's azimuthal roughness β_n; `None` takes the fiber's β.
    pub beta_n: Option<f64>,
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self {
            tabulation: Tabulation::Tabulated,
            iterations: DEFAULT_ITERATIONS,
            beta_n: None,
        }
    }
}

impl BuildOptions {
    /// The defaults with `tabulation`.
    pub fn with(tabulation: Tabulation) -> Self {
        Self {
            tabulation,
            ..Self::default()
        }
    }
}

/// A model's constructor, untabulated.
type Construct = fn(&FiberParams, &BuildOptions) -> Result<Box<dyn FiberModel>, ParamError>;

/// One line per model: its id, the name the command line and the records use, and its
/// constructor. [`ModelId::ALL`] is this table's order, the default first.
const REGISTRY: [(ModelId, &str, Construct); 5] = [
    (ModelId::NonSeparable, "nonseparable", |p, o| {
        Ok(Box::new(
            NonSeparable::new(*p)?.with_iterations(o.iterations),
        ))
    }),
    (ModelId::NonSeparablePaper, "nonseparable-paper", |p, o| {
        Ok(Box::new(
            NonSeparable::paper(*p)?.with_iterations(o.iterations),
        ))
    }),
    (ModelId::DEon2011, "deon2011", |p, _| {
        Ok(Box::new(DEon2011::new(*p)?))
    }),
    (ModelId::Marschner, "marschner", |p, _| {
        Ok(Box::new(Marschner2003::from_fiber(p)?))
    }),
    (ModelId::Chiang2016, "chiang2016", |p, o| {
        Ok(Box::new(Chiang2016::new(*p, o.beta_n.unwrap_or(p.beta))?))
    }),
];

impl ModelId {
    /// Every model, in the registry's order (the default first).
    pub const ALL: [ModelId; REGISTRY.len()] = {
        let mut all = [ModelId::NonSeparable; REGISTRY.len()];
        let mut k = 0;
        while k < all.len() {
            all[k] = REGISTRY[k].0;
            k += 1;
        }
        all
    };

    /// The model's line in the registry.
    const fn entry(self) -> &'static (ModelId, &'static str, Construct) {
        let mut k = 0;
        while REGISTRY[k].0 as usize != self as usize {
            k += 1;
        }
        &REGISTRY[k]
    }

    /// The name the command line and the records use.
    pub const fn name(self) -> &'static str {
        self.entry().1
    }

    /// Every model's name, in [`ModelId::ALL`]'s order.
    pub fn names() -> [&'static str; REGISTRY.len()] {
        Self::ALL.map(Self::name)
    }

    /// The model for `params`, tabulated or not as `options` say.
    pub fn build(
        self,
        params: &FiberParams,
        options: &BuildOptions,
    ) -> Result<Box<dyn FiberModel>, ParamError> {
        let mut model = (self.entry().2)(params, options)?;
        if options.tabulation == Tabulation::Tabulated {
            model.tabulate();
        }
        Ok(model)
    }
}

impl fmt::Display for ModelId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A name that is not a model's.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown model {0:?} (models: {names})", names = ModelId::names().join(", "))]
pub struct UnknownModel(pub String);

impl FromStr for ModelId {
    type Err = UnknownModel;

    /// A model's [`ModelId::name`], or `marschner2003` for [`ModelId::Marschner`].
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "marschner2003" {
            return Ok(ModelId::Marschner);
        }
        ModelId::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| UnknownModel(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FiberAngles;

    /// Each name parses back to its model, an unknown one is refused with the list, and each
    /// model builds under the name it reports, both ways, to the same S where the table is
    /// exact (R, for the models whose R is closed-form in both).
    #[test]
    fn every_model_parses_and_builds_under_its_name() {
        let params = FiberParams::default();
        for id in ModelId::ALL {
            assert_eq!(id.name().parse::<ModelId>(), Ok(id));
            for tabulation in [Tabulation::Direct, Tabulation::Tabulated] {
                let model = id.build(&params, &BuildOptions::with(tabulation)).unwrap();
                let s = model.eval(FiberAngles::new(0.3, 0.0), FiberAngles::new(-0.2, 0.4));
                assert!(s.total().min_element() > 0.0, "{id} {tabulation:?}");
                assert_eq!(model.name(), id.name());
            }
        }
        let err = "marschner2004".parse::<ModelId>().unwrap_err();
        assert!(err.to_string().contains("chiang2016"), "{err}");
        assert_eq!("marschner2003".parse::<ModelId>(), Ok(ModelId::Marschner));
    }

    /// The registry's build is the model's own constructor: the same S to the bit.
    #[test]
    fn build_is_the_models_constructor() {
        let params = FiberParams::default();
        let (wi, wo) = (FiberAngles::new(0.4, 0.1), FiberAngles::new(-0.3, 2.0));
        let direct = ModelId::DEon2011
            .build(&params, &BuildOptions::with(Tabulation::Direct))
            .unwrap();
        let own = DEon2011::new(params).unwrap();
        assert_eq!(direct.eval(wi, wo), own.eval(wi, wo));
        let tabulated = ModelId::DEon2011
            .build(&params, &BuildOptions::default())
            .unwrap();
        assert_eq!(tabulated.eval(wi, wo), own.tabulated().eval(wi, wo));
    }
}

//! Flags shared by the commands that evaluate a fiber model (docs/conventions.md §5), and building
//! the model they name.

use anyhow::Result;
use cuticle_fiber::spec::absorption;
use cuticle_fiber::{BuildOptions, FiberModel, FiberParams, ModelId, ModelSpec, Tabulation};
use serde_json::{Value, json};

/// `--model`'s parser: the fiber crate's registry of models, its names listed in `--help`.
pub fn model_parser() -> impl clap::builder::TypedValueParser<Value = ModelId> {
    use clap::builder::TypedValueParser as _;
    clap::builder::PossibleValuesParser::new(ModelId::names())
        .map(|name| name.parse::<ModelId>().expect("a name of the registry"))
}

#[derive(clap::Args, Clone, Debug)]
pub struct FiberArgs {
    /// Fiber model.
    #[arg(long, value_parser = model_parser(), default_value = "nonseparable")]
    pub model: ModelId,
    /// Longitudinal roughness β (Beckmann, as the simulator uses it), in (0, 1].
    #[arg(long, default_value_t = FiberParams::default().beta, allow_negative_numbers = true)]
    pub beta: f64,
    /// Relative index of refraction η > 1.
    #[arg(long, default_value_t = FiberParams::default().eta, allow_negative_numbers = true)]
    pub eta: f64,
    /// Scale tilt α, degrees (human hair: about −2 to −4).
    #[arg(long, default_value_t = cuticle_fiber::params::DEFAULT_ALPHA_DEG, allow_negative_numbers = true)]
    pub alpha_deg: f64,
    /// Interior absorption per unit radius: one value or r,g,b [default: 0.12,0.25,0.5].
    #[arg(long, value_parser = crate::commands::sim::parse_mu_a, allow_negative_numbers = true, conflicts_with_all = ["eumelanin", "pheomelanin"])]
    pub mu_a: Option<[f64; 3]>,
    /// Eumelanin concentration, instead of --mu-a (d'Eon et al. 2011's coefficients).
    #[arg(long, allow_negative_numbers = true)]
    pub eumelanin: Option<f64>,
    /// Pheomelanin concentration, instead of --mu-a.
    #[arg(long, allow_negative_numbers = true)]
    pub pheomelanin: Option<f64>,
    /// Fixed-point iterations per sample of the non-separable model (d'Eon et al. 2014 uses 6).
    #[arg(long, default_value_t = cuticle_fiber::models::nonseparable::DEFAULT_ITERATIONS)]
    pub iterations: u32,
    /// Integrate N_p over h (Marschner 2003: solve its cubics for their roots) at every
    /// evaluation instead of reading the table built once per parameter set (slower; the
    /// reference the table is measured against).
    #[arg(long)]
    pub direct: bool,
}

impl FiberArgs {
    /// The model `--model` names for the flags' fiber, every value checked
    /// ([`ModelSpec::check`]).
    pub fn spec(&self) -> Result<ModelSpec> {
        let params = FiberParams {
            eta: self.eta,
            beta: self.beta,
            alpha: self.alpha_deg.to_radians(),
            mu_a: absorption(
                self.mu_a,
                self.eumelanin,
                self.pheomelanin,
                FiberParams::default().mu_a,
            )?,
        };
        let spec = ModelSpec {
            model: self.model,
            params,
            options: BuildOptions {
                tabulation: match self.direct {
                    true => Tabulation::Direct,
                    false => Tabulation::Tabulated,
                },
                iterations: self.iterations,
                beta_n: None,
            },
        };
        spec.check()?;
        Ok(spec)
    }

    /// The physical parameters, validated: one sentence per fault.
    pub fn params(&self) -> Result<FiberParams> {
        Ok(self.spec()?.params)
    }

    /// The model `--model` names, built from [`FiberArgs::spec`].
    pub fn model(&self) -> Result<Box<dyn FiberModel>> {
        Ok(self.spec()?.build()?)
    }

    /// The `"params"` object of the JSON records.
    pub fn json(&self, theta_i: Option<f64>) -> Result<Value> {
        let p = self.params()?;
        let mut v = json!({
            "model": self.model.name(),
            "beta": p.beta,
            "eta": p.eta,
            "alpha_deg": self.alpha_deg,
            "mu_a": p.mu_a.to_array(),
            "eumelanin": self.eumelanin,
            "pheomelanin": self.pheomelanin,
            "iterations": self.iterations,
            "direct": self.direct,
        });
        if let Some(t) = theta_i {
            v["theta_i"] = json!(t);
        }
        Ok(v)
    }
}

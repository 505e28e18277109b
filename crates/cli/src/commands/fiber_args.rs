//! Flags shared by the commands that evaluate a fiber model (docs/conventions.md §5), and building
//! the model they name.

use anyhow::{Context, Result};
use cuticle_fiber::absorption::mu_a_from_melanin;
use cuticle_fiber::ranges::{self, CountRange};
use cuticle_fiber::{BuildOptions, FiberModel, FiberParams, ModelId, Tabulation};
use glam::DVec3;
use serde_json::{Value, json};

/// Fixed-point iterations per sample of the non-separable model.
pub const ITERATIONS: CountRange = CountRange {
    name: "iterations",
    min: 1,
    max: 1000,
};

/// `--model`'s parser: the fiber crate's registry of models, its names listed in `--help`.
pub fn model_parser() -> impl clap::builder::TypedValueParser<Value = ModelId> {
    use clap::builder::TypedValueParser as _;
    clap::builder::PossibleValuesParser::new(ModelId::names())
        .map(|name| name.parse::<ModelId>().expect("a name of the registry"))
}

/// The absorption μ_a the flags give: `--mu-a`, else melanin (`--eumelanin`, `--pheomelanin`,
/// each checked), else `default`.
pub fn absorption(
    mu_a: Option<[f64; 3]>,
    eumelanin: Option<f64>,
    pheomelanin: Option<f64>,
    default: DVec3,
) -> Result<DVec3> {
    Ok(match (mu_a, eumelanin, pheomelanin) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => anyhow::bail!(
            "--mu-a and melanin (--eumelanin, --pheomelanin) both set the absorption; give one"
        ),
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

#[derive(clap::Args, Clone, Debug)]
pub struct FiberArgs {
    /// Fiber model.
    #[arg(long, value_parser = model_parser(), default_value = "nonseparable")]
    pub model: ModelId,
    /// Longitudinal roughness β (Beckmann, as the simulator uses it), in (0, 1].
    #[arg(long, default_value_t = 0.04, allow_negative_numbers = true)]
    pub beta: f64,
    /// Relative index of refraction η > 1.
    #[arg(long, default_value_t = 1.55, allow_negative_numbers = true)]
    pub eta: f64,
    /// Scale tilt α, degrees (human hair: about −2 to −4).
    #[arg(long, default_value_t = -2.0, allow_negative_numbers = true)]
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
    #[arg(long, default_value_t = cuticle_fiber::nonseparable::DEFAULT_ITERATIONS)]
    pub iterations: u32,
    /// Integrate N_p over h (Marschner 2003: solve its cubics for their roots) at every
    /// evaluation instead of reading the table built once per parameter set (slower; the
    /// reference the table is measured against).
    #[arg(long)]
    pub direct: bool,
}

impl FiberArgs {
    /// The physical parameters, validated: one sentence per fault.
    pub fn params(&self) -> Result<FiberParams> {
        let mu_a = absorption(
            self.mu_a,
            self.eumelanin,
            self.pheomelanin,
            DVec3::new(0.12, 0.25, 0.5),
        )?;
        let params = FiberParams {
            eta: self.eta,
            beta: self.beta,
            alpha: self.alpha_deg.to_radians(),
            mu_a,
        };
        params.validate()?;
        ITERATIONS.check(self.iterations.into())?;
        Ok(params)
    }

    /// The model `--model` names, built from [`FiberArgs::params`].
    pub fn model(&self) -> Result<Box<dyn FiberModel>> {
        let params = self.params()?;
        let options = BuildOptions {
            tabulation: match self.direct {
                true => Tabulation::Direct,
                false => Tabulation::Tabulated,
            },
            iterations: self.iterations,
            beta_n: None,
        };
        let model = self.model.build(&params, &options);
        Ok(match self.model {
            ModelId::Marschner => model.context("Marschner 2003 parameters")?,
            _ => model?,
        })
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

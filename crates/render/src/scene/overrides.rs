//! Values laid over a scene (a TOML file's, or the defaults): `cuticle render`'s and
//! `cuticle view`'s flags, and the Python bindings' keyword arguments of `cuticle.render`,
//! each `None` where the scene's value stands. One place that says which key each one sets,
//! so that every front end renders the same scene from the same values.

use crate::scene::{Method, SceneSpec};

/// Every value a front end may set over a [`SceneSpec`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SceneOverrides {
    pub groom: Option<String>,
    pub strands: Option<usize>,
    pub env: Option<String>,
    /// The number J of SRBF lights to fit.
    pub lights: Option<usize>,
    pub method: Option<Method>,
    pub quadrature: Option<usize>,
    /// `Some(false)` renders single scattering only.
    pub multiple: Option<bool>,
    pub width: Option<usize>,
    pub height: Option<usize>,
    pub supersampling: Option<usize>,
    pub brute_grid: Option<usize>,
    pub eta: Option<f64>,
    pub alpha_r_deg: Option<f64>,
    pub beta_r_deg: Option<f64>,
    /// Absorption μ_a per unit radius for every strand.
    pub mu_a: Option<[f64; 3]>,
    pub eccentricity: Option<f64>,
    pub caustic_width_deg: Option<f64>,
}

impl SceneOverrides {
    /// `spec` with every value given here laid over it (checked later, by
    /// [`SceneSpec::validate`]).
    pub fn apply(&self, mut spec: SceneSpec) -> SceneSpec {
        fn set<T: Clone>(field: &mut T, value: &Option<T>) {
            if let Some(v) = value {
                *field = v.clone();
            }
        }
        set(&mut spec.groom, &self.groom);
        set(&mut spec.strands, &self.strands);
        set(&mut spec.env, &self.env);
        set(&mut spec.lights, &self.lights);
        set(&mut spec.method, &self.method);
        set(&mut spec.quadrature, &self.quadrature);
        set(&mut spec.multiple, &self.multiple);
        set(&mut spec.width, &self.width);
        set(&mut spec.height, &self.height);
        set(&mut spec.supersampling, &self.supersampling);
        set(&mut spec.brute_grid, &self.brute_grid);
        let h = &mut spec.hair;
        set(&mut h.eta, &self.eta);
        set(&mut h.alpha_r_deg, &self.alpha_r_deg);
        set(&mut h.beta_r_deg, &self.beta_r_deg);
        set(&mut h.eccentricity, &self.eccentricity);
        set(&mut h.caustic_width_deg, &self.caustic_width_deg);
        if let Some(m) = self.mu_a {
            h.mu_a = Some(m);
        }
        spec
    }
}

impl std::str::FromStr for Method {
    type Err = String;

    /// `srbf`, `brute` or `path`, as scene files and `--method` spell them.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "srbf" => Ok(Method::Srbf),
            "brute" => Ok(Method::Brute),
            "path" => Ok(Method::Path),
            _ => Err(format!("method must be srbf, brute or path, got {s:?}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_given_values_change_the_scene() {
        let spec = SceneSpec::default();
        assert_eq!(SceneOverrides::default().apply(spec.clone()), spec);
        let changed = SceneOverrides {
            width: Some(32),
            multiple: Some(false),
            mu_a: Some([0.1, 0.2, 0.3]),
            method: "brute".parse().ok(),
            ..SceneOverrides::default()
        }
        .apply(spec.clone());
        assert_eq!((changed.width, changed.height), (32, spec.height));
        assert!(!changed.multiple && changed.method == Method::Brute);
        assert_eq!(changed.hair.mu_a, Some([0.1, 0.2, 0.3]));
        assert!("fast".parse::<Method>().is_err());
    }
}

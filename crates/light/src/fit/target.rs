//! What the fit approximates: samples of the map, each a world direction, a solid-angle weight and
//! an RGB radiance (the mean over the area it stands for), in double precision.

use glam::DVec3;

pub struct Target {
    pub dirs: Vec<DVec3>,
    pub weights: Vec<f64>,
    pub values: Vec<DVec3>,
    /// Per sample, the variance β of the box it averages over beyond a single pixel, per axis
    /// (see [`super::model::filtered_basis`]); 0 for single pixels.
    pub blur: Vec<f64>,
    /// Σ_p w_p ‖L_p‖², the denominator of the relative error.
    pub norm2: f64,
}

impl Target {
    pub fn new(dirs: Vec<DVec3>, weights: Vec<f64>, values: Vec<DVec3>, blur: Vec<f64>) -> Self {
        let norm2 = weights
            .iter()
            .zip(&values)
            .map(|(w, v)| w * v.length_squared())
            .sum();
        Self {
            dirs,
            weights,
            values,
            blur,
            norm2,
        }
    }

    pub fn len(&self) -> usize {
        self.dirs.len()
    }

    /// √(sse / norm2): the relative L2 error that a weighted sum of squared errors means here.
    pub fn relative(&self, sse: f64) -> f64 {
        if self.norm2 > 0.0 {
            (sse / self.norm2).sqrt()
        } else {
            sse.sqrt()
        }
    }
}

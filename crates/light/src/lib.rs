//! Environment light for cuticle: lat-long environment maps (Radiance `.hdr`, OpenEXR, or a
//! procedural sky built in code), spherical Gaussians (SRBFs) and the fit of a map by a few SRBF
//! lights that the renderer consumes (Xu et al. 2011 eq. 1, after Tsai & Shih 2006 and Ren et al.
//! 2010).
//!
//! # Direction convention
//!
//! World space is right-handed with **+y up**. A direction ω = (x, y, z) has
//! - elevation θ = asin(y) ∈ [−π/2, π/2] (+π/2 is the zenith),
//! - azimuth φ = atan2(z, x) ∈ (−π, π] (φ = 0 is +x, φ = +π/2 is +z),
//!
//! so ω = (cos θ cos φ, sin θ, cos θ sin φ). This is the lat-long layout of docs/conventions.md §4:
//! in a `width × height` map, column j covers φ ∈ [−π + 2πj/W, −π + 2π(j+1)/W) and row k covers θ
//! from π/2 − πk/H down to π/2 − π(k+1)/H. Row 0 is the sky's top, the image's centre column looks
//! along +x, its left edge along −x, and +z is a quarter of the width right of the centre. Seen
//! from inside the sphere with +y up, the picture is not mirrored.
//!
//! A pixel of row k subtends Δφ · (sin θ_top − sin θ_bottom) steradians, Δφ = 2π/W
//! ([`EnvMap::solid_angle`]); the pixels of a map sum to 4π.
//!
//! A map carries a rotation about the up axis ([`EnvMap::with_rotation`]): rotating by ρ moves the
//! content the file shows at azimuth φ to the world azimuth φ + ρ. OpenEXR's own lat-long
//! convention (`ImfEnvmap`: +y up, the image centre along +z) is this one rotated by ρ = +90°.
//!
//! # Values
//!
//! Pixel values are linear radiance (RGB). Loading rejects NaN and infinite values with an
//! error naming the pixel; negative values (ringing from resampling in some HDR tools) are clamped
//! to 0 and counted in [`EnvMap::clamped_negatives`].
//!
//! # SRBF lights
//!
//! [`SrbfLight`] is G(ω; ω_j, λ_j) = exp(2(ω·ω_j − 1)/λ_j²) times an RGB coefficient L_j (Xu et al.
//! 2011 eq. 1 and Table 1), with its closed-form integral, product and inner product. [`fit_srbf`]
//! approximates a map by J of them. Fitted suns can be a pixel wide (κ = 2/λ² ~ 10⁵): evaluate
//! G as exp(−κ‖ω − ω_j‖²/2), never as exp(κ(ω·ω_j − 1)) in single precision
//! ([`SrbfLight::basis`]).

mod color;
mod env_map;
mod error;
mod exr_reader;
pub mod file;
mod fit;
mod hdr;
pub mod image_file;
mod latlong;
mod load;
mod procedural_sky;
mod resample;
mod srbf;
mod tonemap;

pub use env_map::{EnvMap, EnvPixel};
pub use error::LightError;
pub use fit::{
    FitCache, FitOptions, FitProgress, FitReport, FitSource, fit_cache_key, fit_srbf,
    fit_srbf_cached, fit_srbf_with_progress,
};
pub use latlong::{direction_from_angles, direction_to_angles};
pub use load::{load_env_map, load_or_default};
pub use procedural_sky::ProceduralSky;
pub use srbf::{
    MAX_BANDWIDTH, MAX_COEFFICIENT, MAX_LIGHTS, MAX_RADIANCE, MIN_BANDWIDTH, SrbfLight,
    SrbfProduct, evaluate_lights, relative_l2_error, validate_lights,
};
pub use tonemap::{ToneMap, comparison_image};

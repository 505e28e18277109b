//! Tilted cuticle scales (this project's extension of the non-separable model): A(p, h) traced
//! through them ([`attenuation`]), the shift they add to TT's and TRT's Φ(p, h)
//! ([`deflection`]), and R's exact mirror off them ([`mirror`]).

pub mod attenuation;
pub mod deflection;
pub mod mirror;

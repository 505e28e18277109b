//! Lobe shapes the models are built from: longitudinal M_p ([`longitudinal`]: Gaussian, d'Eon's
//! Bessel lobe, cones), the wrapped Gaussian in azimuth ([`azimuthal`]), and the skewed sine
//! lobes of the non-separable model ([`sine_lobe`]).

pub mod azimuthal;
pub mod longitudinal;
pub mod sine_lobe;

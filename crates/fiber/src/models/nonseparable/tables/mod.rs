//! The non-separable model's fast paths, each built once per fiber: the skewed sine lobes'
//! shapes ([`sine_lobes`]), R's mirror cones ([`mirrors`]), the tilt's shift of Φ
//! ([`shifts`]) and the lobe-selection densities ([`selection`]).

pub(super) mod mirrors;
pub(super) mod selection;
pub(super) mod shifts;
pub(super) mod sine_lobes;

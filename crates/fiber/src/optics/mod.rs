//! What happens at the fiber's surface and inside it: Fresnel factors ([`fresnel`]), melanin's
//! absorption ([`absorption`]), the smooth fiber's attenuation A(p, h) of d'Eon et al. 2011
//! ([`attenuation`]), Beckmann micro-normals ([`beckmann`]) and their averages over a rough
//! interface ([`rough_interface`]).

pub mod absorption;
pub mod attenuation;
pub mod beckmann;
pub mod fresnel;
pub mod rough_interface;

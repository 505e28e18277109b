//! Where light meets the fiber: the fiber frame and its angles ([`frame`]), the lat-long grid
//! the models' S is pictured on ([`latlong`]), Bravais' refraction in the normal plane and the
//! azimuthal deflection Φ(p, h) it gives ([`bravais`]), and the Nusselt rotations through a
//! tilted cuticle scale ([`nusselt`]).

pub mod bravais;
pub mod frame;
pub mod latlong;
pub mod nusselt;

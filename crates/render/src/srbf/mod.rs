//! The fast path: Xu et al. 2011's shading of a visible point against SRBF lights.
//! 1. [`single_scattering`]: for each light and mode, the outer integral over θ_i by the
//!    m-segment [`quadrature`] of a Gaussian product, the inner azimuthal integral closed-form
//!    from the circular Gaussians of [`cg_lobes`] ([`circular_gaussian`], with the [`taylor`]
//!    expansion of the attenuation).
//! 2. [`dual_scattering`]: multiple scattering (Zinke et al. 2008) as a global term through
//!    [`forward_scattering`] along each light's shadow path and a local back-scattering term,
//!    from the lights merged in the groups of [`light_clusters`] at each point.
//!
//! Each has a reference twin of the same name in [`crate::brute`].

pub mod cg_lobes;
pub mod circular_gaussian;
pub mod dual_scattering;
pub mod forward_scattering;
pub mod light_clusters;
pub mod quadrature;
pub mod single_scattering;
pub mod taylor;

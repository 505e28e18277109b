//! The numerics every model and the simulator share, each function with its accuracy in its
//! name or documentation and tested against its reference: polynomials ([`polynomial`]), the
//! elementary functions without a library call ([`trig`], [`exp_log`], with SIMD twins for the
//! models' M and N), the Bessel function I0 ([`bessel`]), the standard normal density, quantile
//! and erfc ([`normal`]), Gauss–Legendre rules ([`quadrature`]), Blinn's cubic solver
//! ([`cubic`]), von Mises–Fisher lobes ([`vmf`]) and the helpers tabulated fast paths share
//! ([`grid`]). The functions of the first six are re-exported here (`math::exp_fast`).

pub mod bessel;
pub mod cubic;
pub mod exp_log;
pub mod grid;
pub mod normal;
pub mod polynomial;
pub mod quadrature;
pub mod trig;
pub mod vmf;

pub use bessel::*;
pub use exp_log::*;
pub use normal::*;
pub use polynomial::{narrow, narrow_mask, widen};
pub use quadrature::*;
pub use trig::*;

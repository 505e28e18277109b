//! The fiber models, one folder each: [`marschner2003`], [`deon2011`] (with its azimuthal
//! table), [`chiang2016`] and [`nonseparable`] (the non-separable lobes of Xu et al. and this
//! project's tilted and rough scales). Each implements [`crate::FiberModel`].

pub mod chiang2016;
pub mod deon2011;
pub mod marschner2003;
pub mod nonseparable;

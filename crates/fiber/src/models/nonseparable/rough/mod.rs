//! Rough scales (this project's extension of the non-separable model): TT's exit azimuth and
//! spread through a rough surface per offset ([`deflection`]), TRT's ([`trt`]), and R's
//! reflection off rough tilted scales ([`mirror`]).

pub mod deflection;
pub mod mirror;
pub mod trt;

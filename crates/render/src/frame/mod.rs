//! The frame, in the stages `render.json` times ([`renderer`] runs them):
//! 1. tables, once per process ([`crate::tables`]);
//! 2. drawing: strands rasterised into the supersampled visibility buffer ([`draw`]), and the
//!    background;
//! 3. shadows: T̃ of every light at every visible point, from deep opacity maps filtered to each
//!    light's bandwidth ([`shadows`]);
//! 4. shading: L_o at every visible point in its fiber frame
//!    ([`crate::angles::fiber_frame_at`]), by the SRBF
//!    path ([`crate::srbf`]) or the brute force ([`crate::brute`]), with [`progress`];
//!    A pass after an edit shades only the points whose inputs changed ([`reshade`]).
//! 5. resolve: subsamples averaged into pixels; the [`Image`](renderer::Image) as files
//!    ([`image_file`]).

pub mod draw;
pub mod image_file;
pub mod progress;
pub mod renderer;
pub mod reshade;
pub mod shadows;
pub mod sub_lights;

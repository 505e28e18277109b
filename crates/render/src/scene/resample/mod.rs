//! The points a groom is shaded at. The renderer shades and shadows a groom at its points and
//! interpolates colour along each segment between them (`frame::renderer::Renderer::resolve`),
//! so the points must lie close enough that the light between two of them is nearly linear.
//! [`shading_points`] adds points to a loaded groom, a file a step:
//! 1. [`long_segments`]: segments longer than [`long_segments::MAX_SEGMENT`] of the bounding
//!    radius split evenly;
//! 2. [`tips`]: each strand's last stretch (its segments within [`tips::TIP_ZONE`] of the tip)
//!    halved where a probe light's transmittance at a piece's midpoint departs from the blend
//!    of its ends' (where hair thins the light bends there);
//! 3. [`knots`]: the groom rebuilt with the points chosen (thickness, colour and transparency
//!    interpolated), the one builder both steps use.
//!
//! Splitting costs shading time in proportion to the points it adds, which is why neither
//! step splits everywhere (the cost and what each step buys: BENCHMARKS.md, docs/tips.md).

pub mod knots;
pub mod long_segments;
pub mod tips;

pub use long_segments::{MAX_SEGMENT, split_long_segments};
pub use tips::split_tips;

use cuticle_groom::Groom;

/// A loaded groom with the points it is shaded at: steps 1 and 2 of the module doc. The scene
/// and the window both load grooms through it. Not idempotent (step 2 reads maps of the groom
/// it is given), so a look saved with its points says `shading_points = false`.
pub fn shading_points(groom: Groom) -> Groom {
    split_tips(split_long_segments(groom))
}

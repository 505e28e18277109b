//! Painting absorption onto strands: a brush picks the strands under it through the frame's
//! visibility buffer ([`brush`]), and each stroke is a step of the undo history ([`history`]).

pub mod brush;
pub mod history;

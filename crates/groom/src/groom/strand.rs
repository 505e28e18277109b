//! [`Strand`]: a borrowed view of one strand of a groom.

use crate::appearance::Appearance;
use glam::Vec3;

/// One strand's slices of the groom's arrays, root first.
#[derive(Clone, Copy, Debug)]
pub struct Strand<'a> {
    pub positions: &'a [Vec3],
    pub thickness: &'a [f32],
    pub tangents: &'a [Vec3],
    pub colors: Option<&'a [Vec3]>,
    pub transparency: Option<&'a [f32]>,
    /// Arc length, root to tip.
    pub length: f32,
    pub appearance: &'a Appearance,
}

impl Strand<'_> {
    pub fn point_count(&self) -> usize {
        self.positions.len()
    }

    pub fn root(&self) -> Vec3 {
        self.positions[0]
    }

    pub fn tip(&self) -> Vec3 {
        self.positions[self.positions.len() - 1]
    }
}

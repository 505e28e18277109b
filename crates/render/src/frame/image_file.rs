//! A rendered [`Image`] as files, through the one encoder every crate uses
//! ([`cuticle_light::image_file`]): PNG tone-mapped with the environment's exposure, EXR
//! linear (`cuticle render`'s image.png and image.exr, the window's screenshots).

use crate::frame::renderer::Image;
use cuticle_light::{LightError, ToneMap, image_file};

impl Image {
    /// Tone-mapped 8-bit sRGB PNG bytes.
    pub fn png_bytes(&self, tone: ToneMap) -> Result<Vec<u8>, LightError> {
        image_file::tone_mapped_png(self.width, self.height, &self.pixels, tone)
    }

    /// Linear 32-bit float RGB OpenEXR bytes.
    pub fn exr_bytes(&self) -> Result<Vec<u8>, LightError> {
        image_file::exr_bytes(self.width, self.height, &self.pixels)
    }
}

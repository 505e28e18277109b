//! Comparison sheets like d'Eon et al. 2014 Figure 7: images of one grid stacked top to bottom
//! (simulation | sampled | evaluated | |difference| | d'Eon 2011), to be tone-mapped with one
//! white point.

use cuticle_fiber::{LatLongGrid, LatLongImage};

/// |a − b| per pixel and channel.
pub fn abs_difference(a: &LatLongImage, b: &LatLongImage) -> LatLongImage {
    LatLongImage {
        grid: a.grid,
        pixels: a
            .pixels
            .iter()
            .zip(&b.pixels)
            .map(|(x, y)| (*x - *y).abs())
            .collect(),
    }
}

/// The panels stacked vertically into one image (all on the same grid).
pub fn stack(panels: &[&LatLongImage]) -> LatLongImage {
    let g = panels[0].grid;
    let mut pixels = Vec::with_capacity(g.len() * panels.len());
    for p in panels {
        assert_eq!(p.grid, g, "sheet panels on different grids");
        pixels.extend_from_slice(&p.pixels);
    }
    LatLongImage {
        grid: LatLongGrid::new(g.width, g.height * panels.len()),
        pixels,
    }
}

/// The sum of the five lobe images.
pub fn total(lobes: &[LatLongImage; 5]) -> LatLongImage {
    let mut t = LatLongImage::zeros(lobes[0].grid);
    lobes.iter().for_each(|l| t.add(l));
    t
}

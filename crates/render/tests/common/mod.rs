//! Helpers shared by the renderer's integration tests.

use cuticle_render::Renderer;
use std::sync::OnceLock;

/// One renderer (its parameter-independent tables) for every test in a binary.
pub fn renderer() -> &'static Renderer {
    static R: OnceLock<Renderer> = OnceLock::new();
    R.get_or_init(Renderer::new)
}

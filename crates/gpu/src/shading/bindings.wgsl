// The shading pass's inputs (shading/mod.rs fills them): the frame's uniform, the tables, the
// strands, the visible points with their shadows, the lights, and the colours it writes.

const PI: f32 = 3.14159265358979;
const HALF_PI: f32 = 1.57079632679490;
const SQRT_2: f32 = 1.41421356237310;
// The lobes by name (the fiber crate's Lobe::{R, TT, TRT}: Lobe::index).
const LOBE_R: u32 = 0u;
const LOBE_TT: u32 = 1u;
const LOBE_TRT: u32 = 2u;

// shading/mod.rs's GridDesc.
struct Grid {
    nx: u32,
    ny: u32,
    n: u32,
    offset: u32,
    x0: f32,
    x1: f32,
    y0: f32,
    y1: f32,
}

// Slots of tables.rs's `slot` module.
const GRID_COSINE: u32 = 0u;
const GRID_H_TRT: u32 = 1u;
const GRID_HALF_COSINES: u32 = 2u;
const GRID_HALF_SHARE: u32 = 3u;
const GRID_SPREAD: u32 = 4u;
const GRID_WIDTH: u32 = 5u;
const GRID_LOBE_TT: u32 = 6u;
const GRID_LOBE_TRT: u32 = 7u;
const GRID_BACK: u32 = 8u;
const GRID_R_FRESNEL: u32 = 9u;

// shading/mod.rs's ShadeParams.
struct Params {
    eye: vec3<f32>,
    visible: u32,
    eta: f32,
    alpha_r: f32,
    beta_r: f32,
    eccentricity: f32,
    caustic_bandwidth: f32,
    caustic_fade: f32,
    d_b: f32,
    cutoff: f32,
    lights: u32,
    m: u32,
    multiple: u32,
    mu_a_scale: f32,
    min_z: f32,
    glint_scale: f32,
    caustic_limit: f32,
    // Bit t set: single-scattering lobe t (R, TT, TRT) shades.
    lobes: u32,
    grids: array<Grid, 10>,
}

// The lights one dispatch of the pass adds: first, first + 1, …, first + count − 1.
struct LightChunk {
    first: u32,
    count: u32,
    _pad0: u32,
    _pad1: u32,
}

// A visible point: where it is, its strand, its tangent and its index in the groom.
struct Point {
    position: vec3<f32>,
    strand: u32,
    tangent: vec3<f32>,
    index: u32,
}

// A light in world space (cuticle_render::WorldLight).
struct Light {
    direction: vec3<f32>,
    bandwidth: f32,
    radiance: vec3<f32>,
    // The end of the run of lights merged for dual scattering that this light starts, or 0
    // (srbf/light_clusters.rs's LightClusters::group_ends).
    group_end: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> static_tables: array<f32>;
@group(0) @binding(2) var<storage, read> lobe_tables: array<f32>;
@group(0) @binding(3) var<storage, read> back_tables: array<f32>;
// Per strand: μ_a (rgb), one spare.
@group(0) @binding(4) var<storage, read> strands: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> points: array<Point>;
// T̃ of light j at visible point k: shadow[k * lights + j].
@group(0) @binding(6) var<storage, read> shadow: array<f32>;
@group(0) @binding(7) var<storage, read> lights: array<Light>;
// L_o of each groom point (only visible ones are written).
@group(0) @binding(8) var<storage, read_write> colours: array<vec4<f32>>;
// This dispatch's lights.
@group(0) @binding(9) var<uniform> chunk: LightChunk;

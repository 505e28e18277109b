// frame/shadows.rs's deep opacity maps (Yuksel & Keyser 2008), one per lit SRBF light, built and
// read on the GPU: every entry point below is one dispatch of shadows/mod.rs, in its order.
// Depths are keyed for atomicMax (the key is the bitwise NOT of an order-preserving u32 of the
// f32 depth, so that a cleared 0 means no hair); optical depth is summed in fixed point
// (`params.scale` units per fiber count, chosen so that no sum can pass 2^31), and the
// summed-area tables wrap in u32, which keeps every box sum exact.

struct ShadowParams {
    maps: u32,
    lights: u32,
    n: u32,
    segments: u32,
    points: u32,
    scale: f32,
    density: f32,
    _pad: u32,
    // frame/shadows.rs's LAYERS, padded to 8.
    layers: array<vec4<f32>, 2>,
}

// One map's frame (frame/shadows.rs's MapFrame) and the light it belongs to.
struct MapRecord {
    centre: vec3<f32>,
    radius: f32,
    u: vec3<f32>,
    texel: f32,
    v: vec3<f32>,
    light: u32,
    travel: vec3<f32>,
    // The light's SRBF bandwidth λ_j.
    bandwidth: f32,
}

// A visible point (shading's Point).
struct Point {
    position: vec3<f32>,
    strand: u32,
    tangent: vec3<f32>,
    index: u32,
}

const NL: u32 = 6u;
const NO_MAP: u32 = 0xffffffffu;
// A light whose map another batch builds: its shadows are left as that batch writes them.
const OTHER_BATCH: u32 = 0xfffffffeu;
const WORKGROUP: u32 = 64u;

@group(0) @binding(0) var<uniform> params: ShadowParams;
@group(0) @binding(1) var<storage, read_write> maps: array<MapRecord>;
// Groom points: position and thickness.
@group(0) @binding(2) var<storage, read_write> groom: array<vec4<f32>>;
// The first point of every segment.
@group(0) @binding(3) var<storage, read_write> segments: array<u32>;
@group(0) @binding(4) var<storage, read_write> first: array<atomic<u32>>;
// Layer l of map m at texel t: layers[(m * NL + l) * n² + t].
@group(0) @binding(5) var<storage, read_write> layers: array<atomic<u32>>;
@group(0) @binding(6) var<storage, read_write> points: array<Point>;
// T̃ of light j at visible point k: shadow[k * lights + j].
@group(0) @binding(7) var<storage, read_write> shadow: array<f32>;
// The map of each light in this batch, NO_MAP for an unlit one, OTHER_BATCH for another
// batch's.
@group(0) @binding(8) var<storage, read_write> map_of_light: array<u32>;

fn layer_bound(l: u32) -> f32 {
    return params.layers[l / 4u][l % 4u];
}

fn local(m: MapRecord, x: vec3<f32>) -> vec3<f32> {
    let d = x - m.centre;
    return vec3<f32>(dot(d, m.u), dot(d, m.v), dot(d, m.travel));
}

// The texel under local point p, or NO_MAP outside the map.
fn texel_of(m: MapRecord, p: vec3<f32>) -> u32 {
    let x = floor((p.x + m.radius) / m.texel);
    let y = floor((p.y + m.radius) / m.texel);
    let n = f32(params.n);
    if (x >= 0.0 && y >= 0.0 && x < n && y < n) {
        return u32(y) * params.n + u32(x);
    }
    return NO_MAP;
}

fn depth_key(z: f32) -> u32 {
    let b = bitcast<u32>(z);
    var ordered: u32;
    if ((b & 0x80000000u) != 0u) {
        ordered = ~b;
    } else {
        ordered = b | 0x80000000u;
    }
    return ~ordered;
}

fn key_depth(key: u32) -> f32 {
    let ordered = ~key;
    if ((ordered & 0x80000000u) != 0u) {
        return bitcast<f32>(ordered & 0x7fffffffu);
    }
    return bitcast<f32>(~ordered);
}

// A segment as the map sees it: its local ends, its fiber count per texel and its steps (at
// most a texel apart), as frame/shadows.rs's `samples`.
struct Seen {
    a: vec3<f32>,
    d: vec3<f32>,
    area: f32,
    steps: u32,
}

fn seen(m: MapRecord, s: u32) -> Seen {
    let i = segments[s];
    let pa = groom[i];
    let pb = groom[i + 1u];
    let a = local(m, pa.xyz);
    let d = local(m, pb.xyz) - a;
    let across = length(d.xy);
    let area = across * 0.5 * (pa.w + pb.w) / (m.texel * m.texel);
    let steps = u32(max(ceil(across / m.texel), 1.0));
    return Seen(a, d, area, steps);
}

fn sample_at(v: Seen, k: u32) -> vec3<f32> {
    return v.a + v.d * ((f32(k) + 0.5) / f32(v.steps));
}

// Pass 1: the first hair of every texel.
@compute @workgroup_size(64)
fn first_hair(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let m = maps[id.y];
    let base = id.y * params.n * params.n;
    for (var s = id.x; s < params.segments; s += groups.x * WORKGROUP) {
        let v = seen(m, s);
        for (var k = 0u; k < v.steps; k++) {
            let p = sample_at(v, k);
            let t = texel_of(m, p);
            if (t != NO_MAP) {
                atomicMax(&first[base + t], depth_key(p.z));
            }
        }
    }
}

// Pass 2: each sample's fiber count into its layer behind the texel's first hair.
@compute @workgroup_size(64)
fn fill_layers(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let m = maps[id.y];
    let nn = params.n * params.n;
    for (var s = id.x; s < params.segments; s += groups.x * WORKGROUP) {
        let v = seen(m, s);
        let units = u32(round(v.area / f32(v.steps) * params.scale));
        for (var k = 0u; k < v.steps; k++) {
            let p = sample_at(v, k);
            let t = texel_of(m, p);
            if (t != NO_MAP) {
                let rel = (p.z - key_depth(atomicLoad(&first[id.y * nn + t]))) / m.radius;
                var l = NL - 1u;
                for (var b = 1u; b <= NL; b++) {
                    if (rel < layer_bound(b)) {
                        l = b - 1u;
                        break;
                    }
                }
                atomicAdd(&layers[(id.y * NL + l) * nn + t], units);
            }
        }
    }
}

// Passes 3 and 4: the summed-area tables, rows then columns, one invocation per line of one
// (map, layer); `id.y` is map × NL + layer.
@compute @workgroup_size(64)
fn sum_rows(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.n) {
        return;
    }
    let base = id.y * params.n * params.n + id.x * params.n;
    var acc = 0u;
    for (var x = 0u; x < params.n; x++) {
        acc += atomicLoad(&layers[base + x]);
        atomicStore(&layers[base + x], acc);
    }
}

@compute @workgroup_size(64)
fn sum_columns(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= params.n) {
        return;
    }
    let base = id.y * params.n * params.n + id.x;
    var acc = 0u;
    for (var y = 0u; y < params.n; y++) {
        acc += atomicLoad(&layers[base + y * params.n]);
        atomicStore(&layers[base + y * params.n], acc);
    }
}

fn sat_at(base: u32, x: i32, y: i32) -> u32 {
    if (x < 0 || y < 0) {
        return 0u;
    }
    return atomicLoad(&layers[base + u32(y) * params.n + u32(x)]);
}

// Mean fiber count of layer l over the texels within `reach` of p (at least p's own), as
// frame/shadows.rs's box_mean.
fn box_mean(mi: u32, m: MapRecord, l: u32, p: vec3<f32>, reach: f32) -> f32 {
    let n = i32(params.n);
    let cx = i32(floor((p.x + m.radius) / m.texel));
    let cy = i32(floor((p.y + m.radius) / m.texel));
    let r = i32(min(max(floor(reach / m.texel), 0.0), f32(n)));
    let x0 = max(cx - r, 0);
    let x1 = min(cx + r, n - 1);
    let y0 = max(cy - r, 0);
    let y1 = min(cy + r, n - 1);
    let base = (mi * NL + l) * params.n * params.n;
    let sum = sat_at(base, x1, y1) - sat_at(base, x0 - 1, y1) - sat_at(base, x1, y0 - 1)
        + sat_at(base, x0 - 1, y0 - 1);
    return f32(sum) / params.scale / f32((x1 - x0 + 1) * (y1 - y0 + 1));
}

// Optical depth in front of world point x (frame/shadows.rs's `depth`): each layer averaged over
// a square of half side max(½ texel, λ × the layer's distance behind the first hair).
fn optical_depth(mi: u32, x: vec3<f32>, lambda: f32) -> f32 {
    let m = maps[mi];
    let p = local(m, x);
    let t = texel_of(m, p);
    if (t == NO_MAP) {
        return 0.0;
    }
    let key = atomicLoad(&first[mi * params.n * params.n + t]);
    if (key == 0u) {
        return 0.0;
    }
    let rel = (p.z - key_depth(key)) / m.radius;
    var total = 0.0;
    for (var l = 0u; l < NL; l++) {
        let b0 = layer_bound(l);
        let b1 = layer_bound(l + 1u);
        let share = clamp((rel - b0) / (b1 - b0), 0.0, 1.0);
        if (share == 0.0) {
            break;
        }
        let reach = lambda * 0.5 * (b0 + b1) * m.radius;
        total += share * box_mean(mi, m, l, p, reach);
    }
    return total;
}

// Pass 5: T̃ = exp(−density × depth) of every light at every visible point (`id.y` the light).
@compute @workgroup_size(64)
fn transmittance(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let j = id.y;
    let mi = map_of_light[j];
    if (mi == OTHER_BATCH) {
        return;
    }
    for (var k = id.x; k < params.points; k += groups.x * WORKGROUP) {
        var t = 1.0;
        if (mi != NO_MAP && params.density > 0.0) {
            t = exp(-params.density * optical_depth(mi, points[k].position, maps[mi].bandwidth));
        }
        shadow[k * params.lights + j] = t;
    }
}

// frame/draw.rs's drawing on the GPU: strands as capsules of their projected width (at least
// a subsample, covering each subsample with probability true width / drawn width by the same
// hash as the CPU's) into the supersampled visibility buffer, each subsample keeping the nearest segment (the lowest
// segment among equal depths, as the CPU's strictly-nearer test in segment order keeps), and
// the visible points listed in ascending order. Every entry point below is one dispatch of
// draw/mod.rs, in its order; the prefix sums between them are scan.wgsl's.

struct DrawParams {
    // The eye, split into its f32 value and the rest of its f64 value (DVec3 − that), so that
    // p − eye keeps the precision of the CPU's f64 projection.
    eye_hi: vec3<f32>,
    points: u32,
    eye_lo: vec3<f32>,
    segments: u32,
    right: vec3<f32>,
    focal: f32,
    up: vec3<f32>,
    // Half the image's width and height, in pixels.
    half_width: f32,
    forward: vec3<f32>,
    half_height: f32,
    // Subsamples per pixel along each axis.
    ss: f32,
    sub_width: u32,
    sub_height: u32,
    // cover's pass: 0 keeps the nearest depth, 1 the lowest segment at that depth.
    mode: u32,
    near: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// A visible point (shading's Point).
struct Point {
    position: vec3<f32>,
    strand: u32,
    tangent: vec3<f32>,
    index: u32,
}

const WORKGROUP: u32 = 64u;
const EMPTY: u32 = 0xffffffffu;

@group(0) @binding(0) var<uniform> params: DrawParams;
// Groom points: position and thickness (the diameter).
@group(0) @binding(1) var<storage, read> groom: array<vec4<f32>>;
// The first point of every segment, in strand order (the CPU's capsule order).
@group(0) @binding(2) var<storage, read> segments: array<u32>;
// Per point: x, y in subsamples, depth (negative: behind the near plane) and true half width
// (the capsule is drawn at least half a subsample wide).
@group(0) @binding(3) var<storage, read_write> projected: array<vec4<f32>>;
// Per segment its count of major lines, then (scanned) the first line of each; one more entry
// at the end for the total.
@group(0) @binding(4) var<storage, read_write> lines: array<u32>;
// Per subsample: ~bits of the nearest depth (atomicMax; 0 none).
@group(0) @binding(5) var<storage, read_write> depth: array<atomic<u32>>;
// Per subsample: ~first point of the nearest segment at that depth (atomicMax; 0 none).
@group(0) @binding(6) var<storage, read_write> nearest: array<atomic<u32>>;
// Per subsample: the first point of the nearest segment (or EMPTY) and t along it (f32 bits),
// as the resolve reads it.
@group(0) @binding(7) var<storage, read_write> coverage: array<vec2<u32>>;
// Per point: 1 where a visible segment starts or ends, then (scanned) each visible point's
// slot; one more entry at the end for the count.
@group(0) @binding(8) var<storage, read_write> seen: array<u32>;
// Per point: the tangent (w spare) and the strand.
@group(0) @binding(9) var<storage, read> tangents: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read> strand_of_point: array<u32>;
@group(0) @binding(11) var<storage, read_write> visible: array<Point>;
// The indirect dispatch of cover: workgroups along x, y, z.
@group(0) @binding(12) var<storage, read_write> cover_groups: array<u32>;

// Pass 1: every point projected (camera.rs's View::project), in subsamples, with its true half
// width (raster.rs's `capsules`).
@compute @workgroup_size(64)
fn project(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    for (var i = id.x; i < params.points; i += groups.x * WORKGROUP) {
        let p = groom[i];
        let d = (p.xyz - params.eye_hi) - params.eye_lo;
        let z = dot(d, params.forward);
        if (z < params.near) {
            projected[i] = vec4<f32>(0.0, 0.0, -1.0, 0.0);
            continue;
        }
        let s = params.focal / z;
        let x = params.half_width + dot(d, params.right) * s;
        let y = params.half_height - dot(d, params.up) * s;
        let half = 0.5 * p.w * (params.focal / max(z, params.near)) * params.ss;
        projected[i] = vec4<f32>(x * params.ss, y * params.ss, z, half);
    }
}

// raster.rs's pcg: one step of the 32-bit PCG LCG, then its RXS-M-XS output permutation
// (O'Neill 2014); u32 arithmetic wraps in WGSL as wrapping_* does in Rust.
fn pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// raster.rs's coverage_hash.
fn coverage_hash(strand: u32, subsample: u32) -> u32 {
    return pcg(strand ^ pcg(subsample));
}

// raster.rs's keeps: whether a capsule drawn `half` wide, whose strand is truly `true_half`
// wide, covers the subsample (with probability true_half / half where that is below 1).
fn keeps(strand: u32, subsample: u32, half: f32, true_half: f32) -> bool {
    if (true_half >= half) {
        return true;
    }
    let u = f32(coverage_hash(strand, subsample) >> 8u) * (1.0 / 16777216.0);
    return u * half < true_half;
}

// A segment ready to draw (raster.rs's Capsule and the bounds of its Tile::draw): its ends
// (w: the true half width), its drawn half widths, its reach r, whether y is its major axis,
// and its major and minor ranges of subsamples.
struct Capsule {
    a: vec4<f32>,
    b: vec4<f32>,
    half_a: f32,
    half_b: f32,
    r: f32,
    steep: bool,
    u_lo: u32,
    u_hi: u32,
    v_lo: u32,
    v_hi: u32,
}

fn capsule(first: u32) -> Capsule {
    var c: Capsule;
    c.a = projected[first];
    c.b = projected[first + 1u];
    if (c.a.z < 0.0 || c.b.z < 0.0) {
        return c;
    }
    c.half_a = max(c.a.w, 0.5);
    c.half_b = max(c.b.w, 0.5);
    c.r = max(c.half_a, c.half_b);
    let w = f32(params.sub_width);
    let h = f32(params.sub_height);
    let x_lo = u32(clamp(floor(min(c.a.x, c.b.x) - c.r), 0.0, w));
    let x_hi = u32(clamp(ceil(max(c.a.x, c.b.x) + c.r), 0.0, w));
    let y_lo = u32(clamp(floor(min(c.a.y, c.b.y) - c.r), 0.0, h));
    let y_hi = u32(clamp(ceil(max(c.a.y, c.b.y) + c.r), 0.0, h));
    c.steep = abs(c.b.y - c.a.y) > abs(c.b.x - c.a.x);
    if (c.steep) {
        c.u_lo = y_lo;
        c.u_hi = y_hi;
        c.v_lo = x_lo;
        c.v_hi = x_hi;
    } else {
        c.u_lo = x_lo;
        c.u_hi = x_hi;
        c.v_lo = y_lo;
        c.v_hi = y_hi;
    }
    return c;
}

// Lines of the major axis the capsule covers (none where its minor range is empty).
fn line_count(c: Capsule) -> u32 {
    if (c.u_hi > c.u_lo && c.v_hi > c.v_lo) {
        return c.u_hi - c.u_lo;
    }
    return 0u;
}

// Pass 2: each segment's count of major lines, the work items of cover.
@compute @workgroup_size(64)
fn count_lines(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    for (var s = id.x; s < params.segments; s += groups.x * WORKGROUP) {
        lines[s] = line_count(capsule(segments[s]));
    }
    if (id.x == 0u) {
        lines[params.segments] = 0u;
    }
}

// Pass 3 (after the scan of `lines`): cover's workgroups for the total of lines.
@compute @workgroup_size(1)
fn size_cover() {
    let total = lines[params.segments];
    cover_groups[0] = clamp((total + WORKGROUP - 1u) / WORKGROUP, 1u, 65535u);
    cover_groups[1] = 1u;
    cover_groups[2] = 1u;
}

// raster.rs's minor_range: the span of the minor coordinate the capsule can cover at major
// coordinate u.
fn minor_range(c: Capsule, u: f32) -> vec2<f32> {
    var au = c.a.x;
    var av = c.a.y;
    var bu = c.b.x;
    var bv = c.b.y;
    if (c.steep) {
        au = c.a.y;
        av = c.a.x;
        bu = c.b.y;
        bv = c.b.x;
    }
    let lo_v = min(av, bv) - c.r;
    let hi_v = max(av, bv) + c.r;
    let du = bu - au;
    if (abs(du) < 1e-6) {
        return vec2<f32>(lo_v, hi_v);
    }
    let slope = (bv - av) / du;
    let centre = av + (clamp(u, min(au, bu), max(au, bu)) - au) * slope;
    let reach = c.r * sqrt(1.0 + slope * slope) + 1.0;
    return vec2<f32>(max(centre - reach, lo_v), min(centre + reach, hi_v));
}

// Position along the capsule's segment of the subsample centre (x, y) + ½, 0 at its first
// point (raster.rs's Tile::draw).
fn along(c: Capsule, x: u32, y: u32) -> f32 {
    let dx = c.b.x - c.a.x;
    let dy = c.b.y - c.a.y;
    let len2 = dx * dx + dy * dy;
    let px = f32(x) + 0.5 - c.a.x;
    let py = f32(y) + 0.5 - c.a.y;
    if (len2 > 0.0) {
        return clamp((px * dx + py * dy) / len2, 0.0, 1.0);
    }
    return 0.0;
}

// The segment whose lines include line `l`: the last s with lines[s] ≤ l.
fn segment_of_line(l: u32) -> u32 {
    var lo = 0u;
    var hi = params.segments;
    while (hi - lo > 1u) {
        let mid = (lo + hi) / 2u;
        if (lines[mid] <= l) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

// Pass 4, twice (params.mode 0 then 1): one invocation per major line of a segment covers the
// subsample centres within the capsule on that line that `keeps` keeps (raster.rs's
// Tile::draw), keeping the nearest depth, then, among the subsamples at that depth, the lowest
// segment. Both passes are
// this one entry point, so that both compute each depth alike. Work per invocation is one line,
// at most the image's extent along the minor axis.
@compute @workgroup_size(64)
fn cover(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let total = lines[params.segments];
    for (var l = id.x; l < total; l += groups.x * WORKGROUP) {
        let s = segment_of_line(l);
        let first = segments[s];
        let c = capsule(first);
        let u = c.u_lo + (l - lines[s]);
        let range = minor_range(c, f32(u) + 0.5);
        let v_start = u32(clamp(floor(range.x), f32(c.v_lo), f32(c.v_hi)));
        let v_end = u32(clamp(ceil(range.y), 0.0, f32(c.v_hi)));
        let dx = c.b.x - c.a.x;
        let dy = c.b.y - c.a.y;
        for (var v = v_start; v < v_end; v++) {
            var x = u;
            var y = v;
            if (c.steep) {
                x = v;
                y = u;
            }
            let t = along(c, x, y);
            let ex = f32(x) + 0.5 - c.a.x - t * dx;
            let ey = f32(y) + 0.5 - c.a.y - t * dy;
            let half = c.half_a + t * (c.half_b - c.half_a);
            if (ex * ex + ey * ey > half * half) {
                continue;
            }
            let k = y * params.sub_width + x;
            if (!keeps(strand_of_point[first], k, half, c.a.w + t * (c.b.w - c.a.w))) {
                continue;
            }
            let z = c.a.z + t * (c.b.z - c.a.z);
            let key = ~bitcast<u32>(z);
            if (params.mode == 0u) {
                atomicMax(&depth[k], key);
            } else if (atomicLoad(&depth[k]) == key) {
                atomicMax(&nearest[k], ~first);
            }
        }
    }
}

// Pass 5: each subsample's segment and t along it into the visibility buffer, and the two
// points of every visible segment flagged.
@compute @workgroup_size(64)
fn settle(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let n = params.sub_width * params.sub_height;
    for (var k = id.x; k < n; k += groups.x * WORKGROUP) {
        let key = atomicLoad(&nearest[k]);
        if (key == 0u) {
            coverage[k] = vec2<u32>(EMPTY, 0u);
            continue;
        }
        let first = ~key;
        let c = capsule(first);
        let t = along(c, k % params.sub_width, k / params.sub_width);
        coverage[k] = vec2<u32>(first, bitcast<u32>(t));
        seen[first] = 1u;
        seen[first + 1u] = 1u;
    }
}

// Pass 6 (after the scan of `seen`): every visible point's record into its slot, in ascending
// point order (raster.rs's Coverage::visible_points).
@compute @workgroup_size(64)
fn compact(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    for (var i = id.x; i < params.points; i += groups.x * WORKGROUP) {
        let slot = seen[i];
        if (seen[i + 1u] > slot) {
            visible[slot] = Point(groom[i].xyz, strand_of_point[i], tangents[i].xyz, i);
        }
    }
}

// The resolve pass (frame/renderer.rs's Renderer::resolve): each pixel the mean of its ss²
// subsamples, hair interpolated along its segment between the two point colours, the rest
// the background.

const EMPTY: u32 = 0xffffffffu;

struct ResolveParams {
    width: u32,
    height: u32,
    ss: u32,
    _pad: u32,
}

@group(0) @binding(0) var<uniform> rp: ResolveParams;
// Per subsample: the first point of the nearest segment (or EMPTY), and t along it (f32 bits).
@group(0) @binding(1) var<storage, read> coverage: array<vec2<u32>>;
@group(0) @binding(2) var<storage, read> background: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> colours: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> image: array<vec4<f32>>;

@compute @workgroup_size(8, 8)
fn resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    if (id.x >= rp.width || id.y >= rp.height) {
        return;
    }
    let pixel = id.y * rp.width + id.x;
    let sw = rp.width * rp.ss;
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < rp.ss * rp.ss; k++) {
        let s = (id.y * rp.ss + k / rp.ss) * sw + id.x * rp.ss + k % rp.ss;
        let c = coverage[s];
        if (c.x == EMPTY) {
            sum += background[pixel].xyz;
        } else {
            let t = bitcast<f32>(c.y);
            sum += mix(colours[c.x].xyz, colours[c.x + 1u].xyz, t);
        }
    }
    image[pixel] = vec4<f32>(sum / f32(rp.ss * rp.ss), 1.0);
}

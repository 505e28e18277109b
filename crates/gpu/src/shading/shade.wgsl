// The shading pass (frame/renderer.rs's SrbfFrame::shade): L_o at every visible point, single
// scattering from the shadowed lights above the cutoff, plus dual scattering. One dispatch
// adds the lights of one `chunk` (shading/mod.rs's lights_per_dispatch), the first writes.

@compute @workgroup_size(64)
fn shade(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = id.x + id.y * groups.x * 64u;
    if (k >= params.visible) {
        return;
    }
    let pt = points[k];
    let f = frame_at(pt.tangent, pt.position);
    let ao = angles(f, normalize(params.eye - pt.position));
    fiber = fiber_point(strands[pt.strand].xyz);
    var sum = vec3<f32>(0.0);
    let end = min(chunk.first + chunk.count, params.lights);
    for (var j = chunk.first; j < end; j++) {
        let light = lights[j];
        let la = angles(f, light.direction);
        let t = shadow[k * params.lights + j];
        let lit = select(vec3<f32>(0.0), light.radiance * t, passes(t));
        if (any(lit != vec3<f32>(0.0))) {
            sum += lit * modes(ao.theta, ao.phi, la.theta, la.phi, light.bandwidth, params.lobes);
        }
        // A group of lights merged for dual scattering is a run of lights (srbf/light_clusters.rs);
        // its first light's group_end ends it, the others' is 0.
        if (params.multiple != 0u && light.group_end == j + 1u) {
            sum += dual_light(ao.theta, ao.phi, la.theta, la.phi, light.bandwidth, light.radiance, t);
        } else if (params.multiple != 0u && light.group_end > j + 1u) {
            sum += dual_group(f, ao.theta, ao.phi, k, j, light.group_end);
        }
    }
    if (chunk.first != 0u) {
        sum += colours[pt.index].xyz;
    }
    colours[pt.index] = vec4<f32>(sum, 1.0);
}

// tables/lobe_table.rs in f32: a fiber's TT and TRT circular Gaussians read from the lobe table
// over (|θ_d|, absorption), or, for an eccentric fiber's TRT, fitted on the spot.

// The point's fiber: μ_a, its cells on the lobe table's absorption axis and its coordinates
// on the back-scattering tables' (absorption_axis.rs: x = ln(1 + μ_a/0.02)).
struct FiberPoint {
    mu: vec3<f32>,
    lobe_x: array<Cell, 3>,
    absorption: vec3<f32>,
}

var<private> fiber: FiberPoint;

fn absorption_coordinate(mu_a: f32) -> f32 {
    return log(1.0 + max(mu_a, 0.0) / params.mu_a_scale);
}

fn fiber_point(mu: vec3<f32>) -> FiberPoint {
    let x = vec3<f32>(absorption_coordinate(mu.x), absorption_coordinate(mu.y), absorption_coordinate(mu.z));
    let g = params.grids[GRID_LOBE_TT];
    return FiberPoint(mu, array<Cell, 3>(cell_y(g, x.x), cell_y(g, x.y), cell_y(g, x.z)), x);
}

// N_TT of the three channels: weight and bandwidth of a pair of Gaussians at π ± offset each.
struct TtLobes {
    weight: vec3<f32>,
    bandwidth: vec3<f32>,
    offset: vec3<f32>,
}

fn tt_lobes(theta_d: f32) -> TtLobes {
    let cx = cell_x(params.grids[GRID_LOBE_TT], abs(theta_d));
    var out: TtLobes;
    for (var c = 0u; c < 3u; c++) {
        out.weight[c] = lobe_at(GRID_LOBE_TT, cx, fiber.lobe_x[c], 0u);
        out.bandwidth[c] = lobe_at(GRID_LOBE_TT, cx, fiber.lobe_x[c], 1u);
        out.offset[c] = lobe_at(GRID_LOBE_TT, cx, fiber.lobe_x[c], 2u);
    }
    return out;
}

// N_TRT of the three channels: the slots' centres (φ*, −φ*, 0), and `weight[channel][slot]`,
// `bandwidth[channel][slot]`.
struct TrtLobes {
    centre: vec3<f32>,
    weight: array<vec3<f32>, 3>,
    bandwidth: array<vec3<f32>, 3>,
}

fn trt_lobes(eta: f32, theta_d: f32) -> TrtLobes {
    var out: TrtLobes;
    if (params.eccentricity != 1.0) {
        let g = geometry(eta, theta_d);
        let moments = caustic_moments(eta, theta_d, g.eta_prime);
        for (var c = 0u; c < 3u; c++) {
            let fit = trt_fit(g, moments, fiber.mu[c]);
            out.weight[c] = fit.weight;
            out.bandwidth[c] = fit.bandwidth;
            out.centre = fit.centre;
        }
        return out;
    }
    return trt_table(theta_d);
}

fn trt_table(theta_d: f32) -> TrtLobes {
    var out: TrtLobes;
    let cx = cell_x(params.grids[GRID_LOBE_TRT], abs(theta_d));
    for (var c = 0u; c < 3u; c++) {
        let x = fiber.lobe_x[c];
        if (c == 0u) {
            let phi_star = lobe_at(GRID_LOBE_TRT, cx, x, 0u);
            out.centre = vec3<f32>(phi_star, -phi_star, 0.0);
        }
        let glint_w = lobe_at(GRID_LOBE_TRT, cx, x, 1u);
        let glint_b = lobe_at(GRID_LOBE_TRT, cx, x, 2u);
        out.weight[c] = vec3<f32>(glint_w, glint_w, lobe_at(GRID_LOBE_TRT, cx, x, 3u));
        out.bandwidth[c] = vec3<f32>(glint_b, glint_b, lobe_at(GRID_LOBE_TRT, cx, x, 4u));
    }
    return out;
}

//! The controls, each live, each with its unit; the slider of every hair parameter spans the
//! range the scene validates (the fiber's `cuticle_fiber::ranges`, the scene's
//! `cuticle_render::scene`), nothing restated here.

use crate::app::{AbsorptionEdit, Tool, ViewApp};
use crate::presets::PRESETS;
use cuticle_fiber::ranges;
use cuticle_fiber::ranges::{CountRange, End, Range};
use cuticle_render::Method;
use cuticle_render::scene;
use egui::{Slider, Ui};
use std::sync::Arc;

/// The slider span of a range: an open end lies a thousandth of the span inside.
fn span(r: Range) -> std::ops::RangeInclusive<f64> {
    let (lo, hi) = r.bounds();
    let inside = (hi - lo) * 1e-3;
    let lo = match r.min {
        End::Closed(v) => v,
        End::Open(v) => v + inside,
    };
    let hi = match r.max {
        End::Closed(v) => v,
        End::Open(v) => v - inside,
    };
    lo..=hi
}

/// A slider over a validated range, its label, unit and range in the tooltip.
fn param(ui: &mut Ui, value: &mut f64, r: Range, label: &str, unit: &str, what: &str) -> bool {
    let mut s = Slider::new(value, span(r)).text(label);
    if !unit.is_empty() {
        s = s.suffix(format!(" {unit}"));
    }
    ui.add(s).on_hover_text(format!("{what}; {r}")).changed()
}

/// A logarithmic slider over a validated scene count, its unit and range in the tooltip.
fn count(ui: &mut Ui, value: &mut usize, r: CountRange, label: &str, unit: &str, what: &str) {
    ui.add(
        Slider::new(value, r.min as usize..=r.max as usize)
            .logarithmic(r.max > 64 * r.min.max(1))
            .text(label)
            .suffix(format!(" {unit}")),
    )
    .on_hover_text(format!("{what}; {r} {unit}"));
}

/// A slider over a validated scene range (logarithmic where it spans decades).
fn ranged(ui: &mut Ui, value: &mut f64, r: Range, label: &str, unit: &str, what: &str) {
    let end = |e: End| match e {
        End::Closed(v) | End::Open(v) => v,
    };
    let (lo, hi) = (end(r.min), end(r.max));
    ui.add(
        Slider::new(value, lo..=hi)
            .logarithmic(hi > 100.0 * lo.max(1e-300) && lo >= 0.0)
            .text(label)
            .suffix(format!(" {unit}")),
    )
    .on_hover_text(format!("{what}; {r} {unit}"));
}

pub fn show(app: &mut ViewApp, ui: &mut Ui) {
    egui::Panel::left("controls")
        .resizable(false)
        .exact_size(super::PANEL_WIDTH)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                if app.look.is_none() {
                    ui.label("loading the scene…");
                    return;
                }
                hair(app, ui);
                absorption(app, ui);
                scattering(app, ui);
                lighting(app, ui);
                groom(app, ui);
                paint(app, ui);
                files(app, ui);
            });
        });
}

fn hair(app: &mut ViewApp, ui: &mut Ui) {
    let Some(look) = &mut app.look else { return };
    let h = &mut look.spec.hair;
    egui::CollapsingHeader::new("Fiber")
        .default_open(true)
        .show(ui, |ui| {
            param(ui, &mut h.eta, ranges::ETA, "η", "", "index of refraction");
            param(
                ui,
                &mut h.alpha_r_deg,
                ranges::ALPHA_R_DEG,
                "α_R",
                "°",
                "longitudinal shift of R (TT −α/2, TRT −3α/2)",
            );
            param(
                ui,
                &mut h.beta_r_deg,
                ranges::BETA_R_DEG,
                "β_R",
                "°",
                "longitudinal width of R (TT β/2, TRT 2β)",
            );
            param(
                ui,
                &mut h.caustic_width_deg,
                ranges::CAUSTIC_WIDTH_DEG,
                "w_c",
                "°",
                "azimuthal width of the TRT glints",
            );
            param(
                ui,
                &mut h.caustic_fade,
                ranges::CAUSTIC_FADE,
                "caustic fade Δη'",
                "",
                "over which the glints fade once they merge",
            );
            param(
                ui,
                &mut h.eccentricity,
                ranges::ECCENTRICITY,
                "eccentricity a",
                "",
                "cross-section eccentricity (Xu et al. 2011 eq. 24)",
            );
            param(
                ui,
                &mut h.d_b,
                scene::hair::D_B,
                "d_b",
                "",
                "weight of local back scattering (Xu et al. 2011 eq. 4)",
            );
        });
}

/// Radio buttons for the way an absorption is entered, then its fields; true when changed.
fn absorption_editor(
    ui: &mut Ui,
    prefix: &str,
    edit: &mut AbsorptionEdit,
    text: &mut String,
    allow_own: bool,
    errors: &mut Vec<String>,
) -> bool {
    let mut changed = false;
    ui.horizontal_wrapped(|ui| {
        if allow_own
            && ui
                .radio(*edit == AbsorptionEdit::Own, "own")
                .on_hover_text("each strand's own absorption (the groom's)")
                .clicked()
        {
            *edit = AbsorptionEdit::Own;
            changed = true;
        }
        let sigma = crate::look::mu_a_of_edit(edit);
        if ui
            .radio(
                matches!(edit, AbsorptionEdit::MuA(_)),
                format!("{prefix}μ_a"),
            )
            .clicked()
        {
            *edit = AbsorptionEdit::MuA(sigma.to_array());
            *text = format_rgb(sigma.to_array());
            changed = true;
        }
        if ui
            .radio(
                matches!(edit, AbsorptionEdit::Melanin(_)),
                format!("{prefix}melanin"),
            )
            .clicked()
        {
            *edit = AbsorptionEdit::Melanin([1.3, 0.2]);
            changed = true;
        }
        if ui
            .radio(
                matches!(edit, AbsorptionEdit::Colour(_)),
                format!("{prefix}colour"),
            )
            .clicked()
        {
            *edit = AbsorptionEdit::Colour([0.5, 0.3, 0.15]);
            changed = true;
        }
    });
    match edit {
        AbsorptionEdit::Own => {}
        AbsorptionEdit::MuA(s) => {
            if text.is_empty() {
                *text = format_rgb(*s);
            }
            let r = ui
                .add(egui::TextEdit::singleline(text).hint_text("r, g, b"))
                .on_hover_text(format!(
                    "μ_a per unit radius, one value or r, g, b, each in {}",
                    ranges::MU_A
                ));
            if r.lost_focus() || (r.changed() && ui.input(|i| i.key_pressed(egui::Key::Enter))) {
                match parse_rgb(text) {
                    Ok(v) if v != *s => {
                        *s = v;
                        changed = true;
                    }
                    Ok(_) => {}
                    Err(e) => errors.push(e),
                }
            }
        }
        AbsorptionEdit::Melanin(m) => {
            // The largest concentration whose μ_a stays inside the validated range.
            let max =
                ranges::MU_A.bounds().1 / cuticle_fiber::optics::absorption::EUMELANIN_SIGMA_A.z;
            let r = 0.0..=max;
            changed |= ui
                .add(
                    Slider::new(&mut m[0], r.clone())
                        .logarithmic(true)
                        .text(format!("{prefix}eumelanin")),
                )
                .on_hover_text("concentration (d'Eon et al. 2011's mapping)")
                .changed();
            changed |= ui
                .add(
                    Slider::new(&mut m[1], r)
                        .logarithmic(true)
                        .text(format!("{prefix}pheomelanin")),
                )
                .changed();
        }
        AbsorptionEdit::Colour(c) => {
            ui.horizontal(|ui| {
                changed |= ui.color_edit_button_rgb(c).changed();
                ui.label("target colour (linear RGB; Chiang et al. 2016 eq. 9)");
            });
        }
    }
    changed
}

fn format_rgb(s: [f64; 3]) -> String {
    format!("{}, {}, {}", s[0], s[1], s[2])
}

/// One number or three, comma separated (as the CLI's `--mu-a`).
pub fn parse_rgb(text: &str) -> Result<[f64; 3], String> {
    let v: Result<Vec<f64>, _> = text.split(',').map(|x| x.trim().parse::<f64>()).collect();
    match v.as_deref() {
        Ok([x]) => Ok([*x; 3]),
        Ok([r, g, b]) => Ok([*r, *g, *b]),
        _ => Err(format!("μ_a takes one number or r, g, b, not {text:?}")),
    }
}

fn absorption(app: &mut ViewApp, ui: &mut Ui) {
    egui::CollapsingHeader::new("Absorption of all strands")
        .default_open(true)
        .show(ui, |ui| {
            let c = &mut app.controls;
            let mut errors = Vec::new();
            let mut changed = absorption_editor(
                ui,
                "",
                &mut c.all_edit,
                &mut c.sigma_text,
                true,
                &mut errors,
            );
            ui.horizontal_wrapped(|ui| {
                for p in PRESETS {
                    if ui.button(p.name).clicked() {
                        c.all_edit =
                            AbsorptionEdit::Melanin([p.eumelanin as f64, p.pheomelanin as f64]);
                        changed = true;
                    }
                }
            });
            if changed && let Some(look) = &mut app.look {
                look.all_strands = app.controls.all_edit.absorption();
            }
            errors.into_iter().for_each(|e| app.error(e));
        });
}

fn scattering(app: &mut ViewApp, ui: &mut Ui) {
    let gpu = app.on_gpu();
    let Some(look) = &mut app.look else { return };
    let spec = &mut look.spec;
    egui::CollapsingHeader::new("Scattering and shadows")
        .default_open(true)
        .show(ui, |ui| {
            ui.checkbox(&mut spec.multiple, "multiple scattering (dual scattering)");
            ui.horizontal(|ui| {
                ui.label("lobes:");
                let srbf = spec.method == Method::Srbf;
                let l = &mut spec.lobes;
                for (on, name) in [(&mut l.r, "R"), (&mut l.tt, "TT"), (&mut l.trt, "TRT")] {
                    ui.add_enabled(srbf, egui::Checkbox::new(on, name))
                        .on_hover_text("debug view: single scattering of the lobes ticked only")
                        .on_disabled_hover_text("the lobe views are of the SRBF method");
                }
            });
            ui.horizontal(|ui| {
                ui.radio_value(&mut spec.method, Method::Srbf, "SRBF");
                ui.add_enabled_ui(!gpu, |ui| {
                    ui.radio_value(&mut spec.method, Method::Brute, "brute force (slow)")
                        .on_disabled_hover_text("the GPU back end renders the SRBF method only");
                });
            });
            count(
                ui,
                &mut spec.quadrature,
                scene::QUADRATURE,
                "quadrature m",
                "segments",
                "segments of the linear quadrature (Xu et al. 2011 §4.2.2)",
            );
            count(
                ui,
                &mut spec.supersampling,
                scene::SUPERSAMPLING,
                "subsamples",
                "per axis",
                "subsamples per pixel along each axis",
            );
            let sh = &mut spec.shadows;
            ranged(
                ui,
                &mut sh.density,
                scene::SHADOW_DENSITY,
                "hair density",
                "× optical depth",
                "multiplies the opacity maps' optical depth (1 physical, 0 no shadows)",
            );
            count(
                ui,
                &mut sh.resolution,
                scene::SHADOW_RESOLUTION,
                "shadow map",
                "texels",
                "texels along each side of a light's opacity map",
            );
            ranged(
                ui,
                &mut sh.cutoff,
                scene::SHADOW_CUTOFF,
                "shadow cutoff",
                "T̃",
                "transmittance below which a light adds no direct light",
            );
        });
}

fn lighting(app: &mut ViewApp, ui: &mut Ui) {
    let mut refit = None;
    egui::CollapsingHeader::new("Environment")
        .default_open(true)
        .show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.add(egui::TextEdit::singleline(&mut app.controls.env_text).desired_width(200.0))
                    .on_hover_text("`default` (procedural sky) or an .hdr / .exr lat-long map");
                if ui.button("load map").clicked() {
                    refit = Some(false);
                }
            });
            if let Some(look) = &mut app.look {
                let before = look.spec.env_rotate_deg;
                let r = ui
                    .add(
                        Slider::new(&mut look.spec.env_rotate_deg, span(scene::ENV_ROTATE_DEG))
                            .text("rotation")
                            .suffix(" °"),
                    )
                    .on_hover_text(format!(
                        "rotation of the map about the up axis (the lights re-fitted after); {}",
                        scene::ENV_ROTATE_DEG
                    ));
                if r.changed() && look.spec.env_rotate_deg.is_finite() {
                    rotate(look, look.spec.env_rotate_deg - before);
                }
                if r.drag_stopped() || (r.changed() && !r.dragged()) {
                    refit = Some(true);
                }
            }
            let lights = scene::LIGHTS;
            let r = ui
                .add(
                    Slider::new(
                        &mut app.controls.lights,
                        lights.min as usize..=lights.max as usize,
                    )
                    .logarithmic(true)
                    .text("SRBF lights"),
                )
                .on_hover_text(format!(
                    "number J of SRBF lights fitted to the map (in the background); {lights}"
                ));
            if r.drag_stopped() || (r.changed() && !r.dragged()) {
                refit = Some(true);
            }
            if let Some(look) = &app.look {
                ui.label(match look.fit_error {
                    Some(e) => {
                        format!("{} lights, fit relative L2 error {e:.3}", look.lights.len())
                    }
                    None => format!("{} lights", look.lights.len()),
                });
            }
        });
    if let Some(same_map) = refit {
        app.refit(same_map);
    }
}

/// Turns the lights and the map by `delta_deg` about the up axis at once; the re-fit that
/// follows replaces the lights with the fit of the turned map.
fn rotate(look: &mut crate::look::Look, delta_deg: f64) {
    let (s, c) = (delta_deg.to_radians() as f32).sin_cos();
    let lights = look
        .lights
        .iter()
        .map(|l| {
            let d = l.direction;
            let mut l = *l;
            l.direction = glam::Vec3::new(d.x * c - d.z * s, d.y, d.x * s + d.z * c);
            l
        })
        .collect();
    look.lights = Arc::new(lights);
    look.env = Arc::new(
        (*look.env)
            .clone()
            .with_rotation(look.spec.env_rotate_deg.to_radians()),
    );
    look.revisions.lights += 1;
}

fn groom(app: &mut ViewApp, ui: &mut Ui) {
    let mut load = false;
    egui::CollapsingHeader::new("Groom")
        .default_open(true)
        .show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.add(
                    egui::TextEdit::singleline(&mut app.controls.groom_text).desired_width(200.0),
                )
                .on_hover_text("a preset (straight, wavy, curly), a .hair file or a USD groom (.usda, .usdc, .usdz)");
                load = ui.button("load groom").clicked();
            });
            ui.add(
                egui::DragValue::new(&mut app.controls.strands)
                    .range(scene::STRANDS.min as usize..=scene::STRANDS.max as usize)
                    .prefix("strands of a preset: "),
            );
        });
    if load {
        app.load_groom();
    }
}

fn paint(app: &mut ViewApp, ui: &mut Ui) {
    egui::CollapsingHeader::new("Paint")
        .default_open(true)
        .show(ui, |ui| {
            let c = &mut app.controls;
            ui.horizontal(|ui| {
                ui.radio_value(&mut c.tool, Tool::Camera, "camera")
                    .on_hover_text("drag: orbit; right/middle drag: pan; scroll: zoom");
                ui.radio_value(&mut c.tool, Tool::Paint, "brush")
                    .on_hover_text("drag: paint; right drag: orbit; scroll: zoom");
            });
            let b = &mut c.brush;
            ui.add(
                Slider::new(&mut b.radius_px, 1.0..=200.0)
                    .logarithmic(true)
                    .text("radius")
                    .suffix(" px"),
            );
            ui.add(Slider::new(&mut b.strength, 0.0..=1.0).text("strength"));
            ui.add(Slider::new(&mut b.soft_edge, 0.0..=1.0).text("soft edge"));
            let mut errors = Vec::new();
            absorption_editor(
                ui,
                "brush ",
                &mut c.brush_edit,
                &mut c.brush_sigma_text,
                false,
                &mut errors,
            );
            ui.horizontal_wrapped(|ui| {
                for p in PRESETS {
                    if ui.small_button(p.name).clicked() {
                        c.brush_edit =
                            AbsorptionEdit::Melanin([p.eumelanin as f64, p.pheomelanin as f64]);
                    }
                }
            });
            errors.into_iter().for_each(|e| app.error(e));
            ui.horizontal(|ui| {
                if ui
                    .add_enabled(app.history.can_undo(), egui::Button::new("undo"))
                    .clicked()
                {
                    app.undo();
                }
                if ui
                    .add_enabled(app.history.can_redo(), egui::Button::new("redo"))
                    .clicked()
                {
                    app.redo();
                }
                if ui.button("clear paint").clicked() {
                    app.clear_paint();
                }
            });
        });
}

fn files(app: &mut ViewApp, ui: &mut Ui) {
    egui::CollapsingHeader::new("Files")
        .default_open(true)
        .show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.label("folder");
                ui.add(egui::TextEdit::singleline(&mut app.controls.out_text).desired_width(200.0));
            });
            ui.horizontal(|ui| {
                if ui
                    .button("save look")
                    .on_hover_text(
                        "groom.hair, groom.absorption.json, groom.usda and scene.toml into FOLDER/look",
                    )
                    .clicked()
                {
                    app.save();
                }
                if ui
                    .button("screenshot")
                    .on_hover_text("the full-quality frame as PNG and EXR into FOLDER")
                    .clicked()
                {
                    app.screenshot();
                }
            });
        });
}

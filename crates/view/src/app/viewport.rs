//! The image and what the pointer does on it: orbit, pan and zoom the camera, or paint.
//! Pointer positions are turned into pixels of the full-resolution image, whatever the size
//! at which the frame on screen was made.

use crate::app::{Tool, ViewApp};
use crate::orbit;
use egui::{PointerButton, Rect, Sense, Ui, Vec2};

/// Zoom factor per point of scroll.
const ZOOM_PER_POINT: f64 = 0.002;

pub fn show(app: &mut ViewApp, ui: &mut Ui) {
    egui::CentralPanel::default().show(ui, |ui| {
        let Some((w, h)) = app.look.as_ref().map(|l| (l.spec.width, l.spec.height)) else {
            ui.centered_and_justified(|ui| ui.spinner());
            return;
        };
        let avail = ui.available_rect_before_wrap();
        let scale = (avail.width() / w as f32)
            .min(avail.height() / h as f32)
            .min(1.0);
        let size = Vec2::new(w as f32, h as f32) * scale.max(0.01);
        let rect = Rect::from_min_size(avail.min, size);
        app.image_rect = Some(rect);
        let response = ui.allocate_rect(rect, Sense::click_and_drag());
        if let Some(shown) = &app.shown {
            let uv = Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter()
                .image(shown.texture.id(), rect, uv, egui::Color32::WHITE);
        }
        let to_image = |p: egui::Pos2| {
            let v = (p - rect.min) / rect.size();
            (v.x as f64 * w as f64, v.y as f64 * h as f64)
        };
        let pixels_per_point = w as f64 / rect.width().max(1.0) as f64;
        camera(app, ui, &response, pixels_per_point, h as f64);
        paint(app, ui, &response, to_image, rect, pixels_per_point);
    });
}

fn camera(app: &mut ViewApp, ui: &Ui, response: &egui::Response, px: f64, height: f64) {
    let Some(look) = &mut app.look else { return };
    let Some(cam) = look.spec.camera else { return };
    let d = response.drag_delta();
    let (dx, dy) = (d.x as f64 * px, d.y as f64 * px);
    let orbit_button = match app.controls.tool {
        Tool::Camera => PointerButton::Primary,
        Tool::Paint => PointerButton::Secondary,
    };
    let mut cam2 = cam;
    if response.dragged_by(orbit_button) && (dx != 0.0 || dy != 0.0) {
        cam2 = orbit::orbit(&cam2, dx, dy);
    } else if app.controls.tool == Tool::Camera
        && (response.dragged_by(PointerButton::Secondary)
            || response.dragged_by(PointerButton::Middle))
    {
        cam2 = orbit::pan(&cam2, dx, dy, height);
    }
    if response.hovered() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y) as f64;
        if scroll != 0.0 {
            cam2 = orbit::zoom(&cam2, (-scroll * ZOOM_PER_POINT).exp());
        }
    }
    if cam2 != cam {
        look.spec.camera = Some(cam2);
    }
}

fn paint(
    app: &mut ViewApp,
    ui: &Ui,
    response: &egui::Response,
    to_image: impl Fn(egui::Pos2) -> (f64, f64),
    rect: Rect,
    px: f64,
) {
    if app.controls.tool != Tool::Paint {
        return;
    }
    let pointer = ui.input(|i| i.pointer.interact_pos().or(i.pointer.hover_pos()));
    if let Some(p) = pointer.filter(|p| rect.contains(*p)) {
        let r = (app.controls.brush.radius_px / px) as f32;
        ui.painter()
            .circle_stroke(p, r, egui::Stroke::new(1.0, egui::Color32::WHITE));
    }
    let down = ui.input(|i| i.pointer.primary_down());
    if down && response.is_pointer_button_down_on() {
        if let Some(p) = pointer {
            app.begin_edit();
            let spacing = (app.controls.brush.radius_px / px / 4.0).max(1.0) as f32;
            if app.last_dab.is_none_or(|q| q.distance(p) >= spacing) {
                let (x, y) = to_image(p);
                app.dab(x, y);
                app.last_dab = Some(p);
            }
        }
    } else if !down {
        app.end_edit();
    }
}

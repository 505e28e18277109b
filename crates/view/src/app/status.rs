//! The status line: which back end shades, the frame on screen (quality, size, seconds), loads
//! in progress, and errors and notes.

use crate::app::ViewApp;
use crate::worker::Quality;
use egui::{Color32, RichText, Ui};

pub fn show(app: &mut ViewApp, ui: &mut Ui) {
    egui::Panel::bottom("status").show(ui, |ui| {
        ui.horizontal(|ui| {
            match &app.shown {
                Some(s) => {
                    let f = &s.frame;
                    let q = match f.quality {
                        Quality::Preview => "preview",
                        Quality::Full => "full",
                    };
                    ui.label(format!(
                        "{} · {q} {}×{} · frame {:.0} ms (prepare {:.0}, shade {:.0}) · {:.0} ms after the edit",
                        f.backend,
                        f.image.width,
                        f.image.height,
                        1e3 * (f.prepare_s + f.shade_s),
                        1e3 * f.prepare_s,
                        1e3 * f.shade_s,
                        1e3 * f.latency_s,
                    ));
                }
                None => {
                    ui.label("no frame yet");
                }
            }
            if let Some((what, p)) = app.loading() {
                ui.add(egui::ProgressBar::new(p).desired_width(120.0).text(what));
            }
        });
        let mut dismiss = false;
        if let Some(e) = app.errors.last() {
            ui.horizontal(|ui| {
                ui.label(RichText::new(format!("error: {e}")).color(Color32::from_rgb(255, 90, 90)));
                dismiss = ui.small_button("dismiss").clicked();
            });
        } else if let Some(n) = app.notes.last() {
            ui.label(RichText::new(n).weak());
        }
        if dismiss {
            app.errors.clear();
        }
    });
}

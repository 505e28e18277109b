//! A small line plot written as SVG: enough to look at azimuthal distributions and error curves
//! without a plotting stack (plotters needs a font backend for its labels).

use std::fmt::Write;

/// One curve: a legend name, an SVG colour, and a value per x.
pub struct Series<'a> {
    pub name: &'a str,
    pub color: &'a str,
    pub values: Vec<f64>,
}

const W: f64 = 720.0;
const H: f64 = 360.0;
const MARGIN: f64 = 50.0;

/// An SVG document plotting every series against `xs`, with axes labelled by their extremes.
pub fn line_plot(title: &str, x_label: &str, xs: &[f64], series: &[Series]) -> String {
    let finite = |v: &&f64| v.is_finite();
    let (x0, x1) = extent(xs.iter().filter(finite).copied());
    let (mut y0, y1) = extent(
        series
            .iter()
            .flat_map(|s| s.values.iter().filter(finite).copied()),
    );
    y0 = y0.min(0.0);
    let sx = |x: f64| MARGIN + (x - x0) / (x1 - x0).max(1e-300) * (W - 2.0 * MARGIN);
    let sy = |y: f64| H - MARGIN - (y - y0) / (y1 - y0).max(1e-300) * (H - 2.0 * MARGIN);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="20" text-anchor="middle" font-size="14">{}</text>"#,
        W / 2.0,
        escape(title)
    );
    let (l, r, b, t) = (MARGIN, W - MARGIN, H - MARGIN, MARGIN);
    let _ = writeln!(
        svg,
        r#"<path d="M{l} {t} L{l} {b} L{r} {b}" stroke="black" fill="none"/>"#
    );
    let _ = writeln!(
        svg,
        r#"<text x="{l}" y="{}" text-anchor="middle">{x0:.3}</text>"#,
        b + 16.0
    );
    let _ = writeln!(
        svg,
        r#"<text x="{r}" y="{}" text-anchor="middle">{x1:.3}</text>"#,
        b + 16.0
    );
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
        W / 2.0,
        b + 32.0,
        escape(x_label)
    );
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{b}" text-anchor="end">{y0:.3}</text>"#,
        l - 4.0
    );
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{}" text-anchor="end">{y1:.3}</text>"#,
        l - 4.0,
        t + 4.0
    );
    for (i, s) in series.iter().enumerate() {
        let points: Vec<String> = xs
            .iter()
            .zip(&s.values)
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .map(|(x, y)| format!("{:.2},{:.2}", sx(*x), sy(*y)))
            .collect();
        let _ = writeln!(
            svg,
            r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="1.5"/>"#,
            points.join(" "),
            s.color
        );
        let ly = t + 14.0 * i as f64;
        let _ = writeln!(
            svg,
            r#"<text x="{}" y="{ly}" fill="{}">{}</text>"#,
            r - 100.0,
            s.color,
            escape(s.name)
        );
    }
    svg.push_str("</svg>\n");
    svg
}

fn extent(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if lo.is_finite() && hi > lo {
        (lo, hi)
    } else {
        (0.0, 1.0)
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plots_every_finite_point_and_escapes_labels() {
        let xs = [0.0, 1.0, 2.0, f64::NAN];
        let svg = line_plot(
            "a < b",
            "x",
            &xs,
            &[Series {
                name: "s",
                color: "red",
                values: vec![0.0, 1.0, 4.0, 2.0],
            }],
        );
        assert!(svg.contains("a &lt; b"));
        let polyline = svg.lines().find(|l| l.starts_with("<polyline")).unwrap();
        assert_eq!(polyline.matches(',').count(), 3);
    }
}

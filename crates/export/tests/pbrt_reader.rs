//! The pbrt-v4 export read back by a strict reader of exactly the statements the exporter
//! writes (anything else is an error), and every value checked against the scene: camera,
//! film, sampler, integrator, the light's equal-area image (its bright texel where cuticle's
//! is), each absorption group's material, and each strand's curves (the polyline's points bit
//! for bit, the Bézier's inner points on the segments, every point's diameter).

use cuticle_export::env::{cuticle_world_direction, equal_area_square_to_sphere};
use cuticle_export::strands::polyline;
use cuticle_export::{Absorption, ChiangHair, Format, HairLook, RenderSettings, export};
use cuticle_groom::{Groom, GroomParts};
use cuticle_light::EnvMap;
use cuticle_render::{Camera, Scene, SceneSpec};
use glam::{DVec3, Vec3};

/// One parameter: `"type name" [ values ]`.
#[derive(Debug, Clone, PartialEq)]
struct Param {
    ty: String,
    name: String,
    numbers: Vec<f64>,
    strings: Vec<String>,
}

/// One statement: its keyword, bare numbers (Scale, LookAt), its quoted kind and parameters.
#[derive(Debug, Clone, PartialEq)]
struct Statement {
    keyword: String,
    numbers: Vec<f64>,
    kind: String,
    params: Vec<Param>,
}

impl Statement {
    fn param(&self, ty: &str, name: &str) -> &Param {
        let p = self
            .params
            .iter()
            .find(|p| p.name == name)
            .unwrap_or_else(|| panic!("{} has no {name}", self.keyword));
        assert_eq!(p.ty, ty, "{name}'s type");
        p
    }

    fn number(&self, ty: &str, name: &str) -> f64 {
        let p = self.param(ty, name);
        assert_eq!(p.numbers.len(), 1, "{name}");
        p.numbers[0]
    }

    fn string(&self, name: &str) -> &str {
        let p = self.param("string", name);
        assert_eq!(p.strings.len(), 1, "{name}");
        &p.strings[0]
    }
}

/// The parameters each (statement, kind) may carry: exactly those the exporter writes.
const ALLOWED: &[(&str, &str, &[&str])] = &[
    ("Camera", "perspective", &["float fov"]),
    (
        "Film",
        "rgb",
        &[
            "string filename",
            "integer xresolution",
            "integer yresolution",
        ],
    ),
    ("PixelFilter", "box", &["float xradius", "float yradius"]),
    (
        "Sampler",
        "independent",
        &["integer pixelsamples", "integer seed"],
    ),
    ("Integrator", "path", &["integer maxdepth"]),
    (
        "LightSource",
        "infinite",
        &["string filename", "float scale"],
    ),
    (
        "Material",
        "hair",
        &[
            "rgb sigma_a",
            "float beta_m",
            "float beta_n",
            "float alpha",
            "float eta",
        ],
    ),
    (
        "Shape",
        "curve",
        &[
            "string type",
            "string basis",
            "integer degree",
            "point3 P",
            "float width0",
            "float width1",
        ],
    ),
];

/// Splits the file into tokens: quoted strings (kept with their quotes), brackets and words;
/// `#` starts a comment to the end of the line.
fn tokens(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let line = line.split('#').next().unwrap_or("");
        let mut rest = line.trim_start();
        while !rest.is_empty() {
            let (token, tail) = if let Some(quoted) = rest.strip_prefix('"') {
                let end = quoted.find('"').expect("an unterminated string");
                (&rest[..end + 2], &quoted[end + 1..])
            } else if rest.starts_with('[') || rest.starts_with(']') {
                rest.split_at(1)
            } else {
                let end = rest
                    .find(|c: char| c.is_whitespace() || c == '[' || c == ']' || c == '"')
                    .unwrap_or(rest.len());
                rest.split_at(end)
            };
            out.push(token.to_string());
            rest = tail.trim_start();
        }
    }
    out
}

fn unquote(token: &str) -> Option<&str> {
    token.strip_prefix('"')?.strip_suffix('"')
}

fn number(token: &str) -> f64 {
    let x: f64 = token
        .parse()
        .unwrap_or_else(|_| panic!("{token} is not a number"));
    assert!(x.is_finite(), "{token}");
    x
}

/// Reads the statements, refusing any keyword, kind, parameter or type not in [`ALLOWED`].
fn read(text: &str) -> Vec<Statement> {
    let tokens = tokens(text);
    let mut k = 0;
    let mut out = Vec::new();
    while k < tokens.len() {
        let keyword = tokens[k].clone();
        k += 1;
        let bare = match keyword.as_str() {
            "Scale" => 3,
            "LookAt" => 9,
            "WorldBegin" | "AttributeBegin" | "AttributeEnd" => 0,
            _ => usize::MAX,
        };
        let mut s = Statement {
            keyword: keyword.clone(),
            numbers: Vec::new(),
            kind: String::new(),
            params: Vec::new(),
        };
        if bare != usize::MAX {
            s.numbers = tokens[k..k + bare].iter().map(|t| number(t)).collect();
            k += bare;
            out.push(s);
            continue;
        }
        s.kind = unquote(&tokens[k])
            .unwrap_or_else(|| panic!("{keyword}: no kind"))
            .to_string();
        k += 1;
        let allowed = ALLOWED
            .iter()
            .find(|(kw, kind, _)| *kw == keyword && *kind == s.kind)
            .unwrap_or_else(|| panic!("unexpected statement {keyword} \"{}\"", s.kind))
            .2;
        while k < tokens.len() && tokens[k].starts_with('"') {
            let decl = unquote(&tokens[k]).unwrap();
            assert!(allowed.contains(&decl), "{keyword}: unexpected \"{decl}\"");
            let (ty, name) = decl.split_once(' ').unwrap();
            assert_eq!(tokens[k + 1], "[", "{decl}: values in brackets");
            k += 2;
            let mut p = Param {
                ty: ty.into(),
                name: name.into(),
                numbers: Vec::new(),
                strings: Vec::new(),
            };
            while tokens[k] != "]" {
                match (ty, unquote(&tokens[k])) {
                    ("string", Some(v)) => p.strings.push(v.into()),
                    ("string", None) => panic!("{decl}: {} is not a string", tokens[k]),
                    (_, None) => p.numbers.push(number(&tokens[k])),
                    (_, Some(v)) => panic!("{decl}: string {v} among numbers"),
                }
                k += 1;
            }
            k += 1;
            s.params.push(p);
        }
        out.push(s);
    }
    out
}

/// Three strands: a tapering one, one with a repeated point, one of a single point repeated.
fn groom() -> Groom {
    let positions = vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(0.1, 0.2, 1.0),
        Vec3::new(0.3, 0.1, 2.0),
        Vec3::new(0.2, 0.4, 3.0),
        Vec3::new(0.25, 0.5, 3.7),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.5, 0.3, 1.2),
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(2.0, 0.0, 0.0),
    ];
    let thickness = vec![0.08, 0.08, 0.08, 0.05, 0.01, 0.06, 0.06, 0.04, 0.05, 0.05];
    Groom::from_parts(GroomParts {
        positions,
        thickness,
        strand_offsets: vec![0, 5, 8, 10],
        ..GroomParts::default()
    })
    .unwrap()
}

fn scene() -> Scene {
    let (w, h) = (32, 16);
    let mut pixels = vec![Vec3::splat(0.1); w * h];
    pixels[5 * w + 9] = Vec3::new(500.0, 400.0, 300.0);
    let env = EnvMap::new(w, h, pixels).with_rotation(40f64.to_radians());
    let spec = SceneSpec {
        width: 30,
        height: 40,
        camera: Some(Camera {
            eye: [3.0, -8.0, 2.5],
            target: [0.5, 0.2, 1.5],
            up: [0.0, 0.0, 1.0],
            fov_deg: 35.0,
        }),
        ..SceneSpec::default()
    };
    Scene::from_parts(spec, groom(), env, Vec::new())
}

const FIBER: ChiangHair = ChiangHair {
    beta_m: 0.21,
    beta_n: 0.43,
    alpha_deg: -2.5,
    eta: 1.6,
};

fn look() -> HairLook {
    HairLook {
        fiber: FIBER,
        sigma_a: Absorption::PerStrand(vec![
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.5, 2.5, 3.5),
            DVec3::new(0.1, 0.2, 0.3),
        ]),
    }
}

const SETTINGS: RenderSettings = RenderSettings {
    spp: 96,
    seed: 7,
    max_depth: 12,
};

/// The exported file's statements and the environment image (width, pixels).
fn exported() -> (Vec<Statement>, usize, Vec<[f32; 3]>) {
    let e = export(&scene(), &look(), &SETTINGS, Format::Pbrt).unwrap();
    let names: Vec<&str> = e.files.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["scene.pbrt", "env.exr"]);
    assert_eq!((e.summary.strands, e.summary.skipped_strands), (2, 1));
    let text = String::from_utf8(e.files[0].bytes.clone()).unwrap();
    let (width, pixels) = decode_exr(&e.files[1].bytes);
    (read(&text), width, pixels)
}

fn decode_exr(bytes: &[u8]) -> (usize, Vec<[f32; 3]>) {
    use exr::prelude::{ReadChannels, ReadLayers, read};
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |size, _| (size.width(), vec![[0f32; 3]; size.area()]),
            |(w, px): &mut (usize, Vec<[f32; 3]>), pos, (r, g, b): (f32, f32, f32)| {
                px[pos.y() * *w + pos.x()] = [r, g, b]
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .unwrap();
    let size = image.layer_data.size;
    assert_eq!(
        size.width(),
        size.height(),
        "pbrt's infinite light takes square images"
    );
    image.layer_data.channel_data.pixels
}

#[test]
fn the_header_carries_camera_film_sampler_and_integrator() {
    let (s, _, _) = exported();
    let keywords: Vec<&str> = s.iter().take(8).map(|s| s.keyword.as_str()).collect();
    assert_eq!(
        keywords,
        [
            "Scale",
            "LookAt",
            "Camera",
            "Film",
            "PixelFilter",
            "Sampler",
            "Integrator",
            "WorldBegin"
        ]
    );
    assert_eq!(s[0].numbers, [-1.0, 1.0, 1.0]);
    assert_eq!(s[1].numbers, [3.0, -8.0, 2.5, 0.5, 0.2, 1.5, 0.0, 0.0, 1.0]);
    // A tall image: pbrt's fov is the width's, 2 atan(tan(35°/2) · 30/40).
    let want = 2.0 * (17.5f64.to_radians().tan() * 0.75).atan().to_degrees();
    assert!((s[2].number("float", "fov") - want).abs() < 1e-12);
    assert_eq!(s[3].string("filename"), "image.exr");
    assert_eq!(s[3].number("integer", "xresolution"), 30.0);
    assert_eq!(s[3].number("integer", "yresolution"), 40.0);
    assert_eq!(s[4].number("float", "xradius"), 0.5);
    assert_eq!(s[5].number("integer", "pixelsamples"), 96.0);
    assert_eq!(s[5].number("integer", "seed"), 7.0);
    assert_eq!(s[6].number("integer", "maxdepth"), 12.0);
}

#[test]
fn the_light_is_the_environment_where_cuticle_has_it() {
    let (s, n, pixels) = exported();
    let light = s.iter().find(|s| s.keyword == "LightSource").unwrap();
    assert_eq!(light.string("filename"), "env.exr");
    assert_eq!(light.number("float", "scale"), 1.0);
    let k = (0..pixels.len())
        .max_by(|&a, &b| pixels[a][0].total_cmp(&pixels[b][0]))
        .unwrap();
    let (i, j) = (k % n, k / n);
    let there =
        equal_area_square_to_sphere((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
    let want = cuticle_world_direction(&scene().env, 9, 5);
    let angle = there.dot(want).clamp(-1.0, 1.0).acos().to_degrees();
    assert!(angle < 6.0, "the bright texel is {angle}° from cuticle's");
    // The dim texels keep their radiance.
    let dim = pixels.iter().filter(|p| (p[1] - 0.1).abs() < 1e-6).count();
    assert!(dim > pixels.len() * 9 / 10);
}

/// Each group is `AttributeBegin`, `Material "hair"`, its strands' curves, `AttributeEnd`.
#[test]
fn materials_and_curves_are_the_groom_and_its_look() {
    let (s, _, _) = exported();
    let world = s.iter().position(|s| s.keyword == "WorldBegin").unwrap();
    let blocks: Vec<&[Statement]> = s[world + 1..]
        .split(|s| s.keyword == "AttributeEnd")
        .filter(|b| !b.is_empty())
        .collect();
    assert_eq!(blocks.len(), 3, "the light and two materials");
    assert_eq!(blocks[0][0].keyword, "AttributeBegin");
    let groom = groom();
    let sigma = [DVec3::new(0.1, 0.2, 0.3), DVec3::new(1.5, 2.5, 3.5)];
    for (block, (sigma_a, strands)) in blocks[1..].iter().zip([(sigma[0], [0]), (sigma[1], [1])]) {
        assert_eq!(block[0].keyword, "AttributeBegin");
        let m = &block[1];
        assert_eq!((m.keyword.as_str(), m.kind.as_str()), ("Material", "hair"));
        assert_eq!(m.param("rgb", "sigma_a").numbers, sigma_a.to_array());
        assert_eq!(m.number("float", "beta_m"), FIBER.beta_m);
        assert_eq!(m.number("float", "beta_n"), FIBER.beta_n);
        assert_eq!(m.number("float", "alpha"), FIBER.alpha_deg);
        assert_eq!(m.number("float", "eta"), FIBER.eta);
        let shapes = &block[2..];
        let want: Vec<_> = strands.iter().map(|&k| polyline(&groom, k)).collect();
        check_curves(shapes, &want);
    }
}

/// The shapes make exactly the strands' polylines, with every point's diameter.
fn check_curves(shapes: &[Statement], strands: &[cuticle_export::strands::Polyline]) {
    let mut points: Vec<Vec3> = Vec::new();
    let mut widths: Vec<f32> = Vec::new();
    for shape in shapes {
        assert_eq!(
            (shape.keyword.as_str(), shape.kind.as_str()),
            ("Shape", "curve")
        );
        assert_eq!(shape.string("type"), "cylinder");
        assert_eq!(shape.string("basis"), "bezier");
        assert_eq!(shape.number("integer", "degree"), 3.0);
        let p: Vec<Vec3> = shape
            .param("point3", "P")
            .numbers
            .chunks(3)
            .map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32))
            .collect();
        assert_eq!((p.len() - 1) % 3, 0, "3n + 1 control points");
        let segments = (p.len() - 1) / 3;
        let (w0, w1) = (
            shape.number("float", "width0") as f32,
            shape.number("float", "width1") as f32,
        );
        for k in 0..segments {
            let (a, b) = (p[3 * k], p[3 * k + 3]);
            assert!((p[3 * k + 1] - (a + (b - a) / 3.0)).length() < 1e-6);
            assert!((p[3 * k + 2] - (a + (b - a) * (2.0 / 3.0))).length() < 1e-6);
        }
        // A new strand starts where the last shape did not end.
        if points.last() != Some(&p[0]) {
            points.push(p[0]);
            widths.push(w0);
        }
        for k in 1..=segments {
            points.push(p[3 * k]);
            widths.push(w0 + (w1 - w0) * k as f32 / segments as f32);
        }
    }
    let want_points: Vec<Vec3> = strands.iter().flat_map(|s| s.points.clone()).collect();
    let want_widths: Vec<f32> = strands.iter().flat_map(|s| s.diameters.clone()).collect();
    assert_eq!(points, want_points, "control points bit for bit");
    assert_eq!(widths.len(), want_widths.len());
    for (got, want) in widths.iter().zip(&want_widths) {
        assert!(
            (got - want).abs() < 1e-6,
            "width {got} for a diameter {want}"
        );
    }
}

/// The reader is strict: a statement or parameter the exporter does not write is refused.
#[test]
fn the_reader_refuses_what_the_exporter_does_not_write() {
    for bad in [
        "Shape \"sphere\" \"float radius\" [ 1 ]",
        "Material \"hair\" \"float sigma_a\" [ 1 ]",
        "Material \"hair\" \"float reflectance\" [ 1 ]",
        "Shape \"curve\" \"float width\" [ 1 ]",
        "Translate 1 2 3",
        "Camera \"perspective\" \"float fov\" 30",
    ] {
        let text = bad.to_string();
        assert!(std::panic::catch_unwind(|| read(&text)).is_err(), "{bad}");
    }
}

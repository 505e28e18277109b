//! A pinhole camera in the groom's space (+z up for procedural grooms), and its default framing
//! of a groom: a three-quarter view from behind and above, where hair covers the head.

use crate::scene::{SceneError, exactly_three};
use cuticle_fiber::ranges::{End, Range};
use glam::{DVec3, Vec3};
use serde::{Deserialize, Serialize};

/// Where the camera stands and looks.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    #[serde(deserialize_with = "exactly_three")]
    pub eye: [f64; 3],
    #[serde(deserialize_with = "exactly_three")]
    pub target: [f64; 3],
    #[serde(deserialize_with = "exactly_three")]
    pub up: [f64; 3],
    /// Vertical field of view, degrees.
    pub fov_deg: f64,
}

/// A camera ready to project: its basis and scale for an image size.
#[derive(Clone, Copy, Debug)]
pub struct View {
    pub eye: DVec3,
    /// Unit vectors of the image's x axis, its upward y axis, and the view direction.
    pub right: DVec3,
    pub up: DVec3,
    pub forward: DVec3,
    /// Pixels per unit of tan(angle off the axis).
    pub focal: f64,
    /// The image size in pixels.
    pub width: f64,
    pub height: f64,
}

/// A projected point: pixel coordinates (x right, y down) and depth along the view axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projected {
    pub x: f32,
    pub y: f32,
    pub depth: f32,
}

/// Nearest depth drawn.
pub const NEAR: f64 = 1e-3;

/// The vertical field of view, degrees: a pinhole sees less than a half space.
pub const FOV_DEG: Range = Range {
    name: "camera.fov_deg",
    min: End::Closed(0.1),
    max: End::Closed(170.0),
    unit: " degrees",
};

/// Each coordinate of the camera's eye, target and up, in the groom's units (centimetres).
pub const COORDINATE: Range = Range {
    name: "camera coordinate",
    min: End::Closed(-1e6),
    max: End::Closed(1e6),
    unit: "",
};

/// Least |eye − target| and |up × forward| / |up| a view needs to have a direction and an up.
const MIN_SEPARATION: f64 = 1e-6;

impl Camera {
    /// A view of the box [lo, hi] from the back-left, slightly above, filling the frame.
    pub fn framing(lo: Vec3, hi: Vec3, up_z: bool) -> Self {
        let (lo, hi) = (lo.as_dvec3(), hi.as_dvec3());
        let centre = 0.5 * (lo + hi);
        let radius = (0.5 * (hi - lo).length()).max(1e-3);
        let fov_deg: f64 = 30.0;
        let distance = radius / (0.5 * fov_deg.to_radians()).sin() * 0.85;
        let (dir, up) = if up_z {
            (DVec3::new(-0.55, -1.0, 0.3).normalize(), DVec3::Z)
        } else {
            (DVec3::new(-0.55, 0.3, -1.0).normalize(), DVec3::Y)
        };
        let eye = centre + dir * distance;
        Self {
            eye: eye.to_array(),
            target: centre.to_array(),
            up: up.to_array(),
            fov_deg,
        }
    }

    /// Checks the camera describes a view: finite coordinates, a field of view in
    /// [`FOV_DEG`], an eye apart from its target, and an up that is neither zero nor along the
    /// view direction.
    pub fn validate(&self) -> Result<(), SceneError> {
        for (key, v) in [("eye", self.eye), ("target", self.target), ("up", self.up)] {
            COORDINATE.named(key_name(key)).check_all(&v)?;
        }
        FOV_DEG.check(self.fov_deg)?;
        let (eye, target, up) = (
            DVec3::from_array(self.eye),
            DVec3::from_array(self.target),
            DVec3::from_array(self.up),
        );
        let forward = target - eye;
        if forward.length() <= MIN_SEPARATION {
            return Err(SceneError::Invalid(format!(
                "camera.eye {:?} and camera.target {:?} must differ: the camera looks nowhere",
                self.eye, self.target
            )));
        }
        if forward.normalize().cross(up).length() <= MIN_SEPARATION * up.length().max(1e-300) {
            return Err(SceneError::Invalid(format!(
                "camera.up {:?} must be non-zero and not along the view direction",
                self.up
            )));
        }
        Ok(())
    }

    /// The view for an image of `width × height` pixels.
    pub fn view(&self, width: usize, height: usize) -> View {
        let eye = DVec3::from_array(self.eye);
        let forward = (DVec3::from_array(self.target) - eye)
            .try_normalize()
            .unwrap_or(DVec3::NEG_Y);
        let up_hint = DVec3::from_array(self.up);
        let right = forward
            .cross(up_hint)
            .try_normalize()
            .unwrap_or(forward.any_orthonormal_vector());
        let up = right.cross(forward);
        let focal = 0.5 * height as f64 / (0.5 * self.fov_deg.to_radians()).tan();
        View {
            eye,
            right,
            up,
            forward,
            focal,
            width: width as f64,
            height: height as f64,
        }
    }
}

impl View {
    /// Pixel coordinates and depth of `p`, or `None` behind the near plane.
    pub fn project(&self, p: DVec3) -> Option<Projected> {
        let d = p - self.eye;
        let z = d.dot(self.forward);
        if z < NEAR {
            return None;
        }
        let s = self.focal / z;
        Some(Projected {
            x: (0.5 * self.width + d.dot(self.right) * s) as f32,
            y: (0.5 * self.height - d.dot(self.up) * s) as f32,
            depth: z as f32,
        })
    }

    /// The unit ray direction through pixel coordinates (x, y).
    pub fn ray(&self, x: f64, y: f64) -> DVec3 {
        let dx = (x - 0.5 * self.width) / self.focal;
        let dy = (0.5 * self.height - y) / self.focal;
        (self.forward + self.right * dx + self.up * dy).normalize()
    }

    /// Pixels per unit length at depth z.
    pub fn pixels_per_unit(&self, depth: f64) -> f64 {
        self.focal / depth.max(NEAR)
    }
}

/// The scene key of one of the camera's vectors.
fn key_name(key: &str) -> &'static str {
    match key {
        "eye" => "camera.eye",
        "target" => "camera.target",
        _ => "camera.up",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The target lands in the image centre and a ray through a projected point hits it.
    #[test]
    fn projection_and_rays_agree() {
        let cam = Camera::framing(Vec3::splat(-10.0), Vec3::splat(10.0), true);
        let view = cam.view(320, 200);
        let c = view.project(DVec3::from_array(cam.target)).unwrap();
        assert!((c.x - 160.0).abs() < 1e-3 && (c.y - 100.0).abs() < 1e-3);
        let p = DVec3::new(3.0, -2.0, 5.0);
        let q = view.project(p).unwrap();
        let ray = view.ray(q.x as f64, q.y as f64);
        assert!((ray - (p - view.eye).normalize()).length() < 1e-5);
    }

    /// Every camera that gives no view is refused, naming the key at fault.
    #[test]
    fn degenerate_cameras_are_refused() {
        let good = Camera::framing(Vec3::splat(-10.0), Vec3::splat(10.0), true);
        assert!(good.validate().is_ok());
        type Spoil = (&'static str, fn(&mut Camera));
        let cases: [Spoil; 9] = [
            ("camera.fov_deg", |c| c.fov_deg = f64::NAN),
            ("camera.fov_deg", |c| c.fov_deg = f64::INFINITY),
            ("camera.fov_deg", |c| c.fov_deg = 0.0),
            ("camera.fov_deg", |c| c.fov_deg = 180.0),
            ("camera.fov_deg", |c| c.fov_deg = -35.0),
            ("camera.eye", |c| c.eye[0] = f64::NAN),
            ("must differ", |c| c.eye = c.target),
            ("camera.up", |c| c.up = [0.0; 3]),
            ("camera.up", |c| {
                c.up = (DVec3::from_array(c.target) - DVec3::from_array(c.eye)).to_array()
            }),
        ];
        for (needle, spoil) in cases {
            let mut c = good;
            spoil(&mut c);
            let e = c.validate().unwrap_err().to_string();
            assert!(e.contains(needle), "{needle}: {e}");
        }
    }
}

//! Orbit, pan and zoom of the camera about its target, in the groom's space (+z up): the
//! camera's eye on a sphere around the target, turned by a drag, the target moved in the view
//! plane by a pan, the sphere's radius scaled by a zoom.

use cuticle_render::Camera;
use glam::DVec3;

/// Radians per pixel of drag.
const ORBIT_PER_PIXEL: f64 = 0.01;
/// Closest the eye comes to the poles, radians.
const POLE_MARGIN: f64 = 0.05;

fn parts(c: &Camera) -> (DVec3, DVec3, DVec3) {
    (
        DVec3::from_array(c.eye),
        DVec3::from_array(c.target),
        DVec3::from_array(c.up).try_normalize().unwrap_or(DVec3::Z),
    )
}

/// The camera turned about its target by a drag of (dx, dy) pixels: right turns the eye to the
/// left about the up axis, down raises it.
pub fn orbit(c: &Camera, dx: f64, dy: f64) -> Camera {
    let (eye, target, up) = parts(c);
    let offset = eye - target;
    let r = offset.length().max(1e-6);
    let polar = (offset.dot(up) / r).clamp(-1.0, 1.0).acos();
    let new_polar =
        (polar - dy * ORBIT_PER_PIXEL).clamp(POLE_MARGIN, std::f64::consts::PI - POLE_MARGIN);
    let yaw = glam::DQuat::from_axis_angle(up, -dx * ORBIT_PER_PIXEL);
    let flat = yaw * (offset - up * offset.dot(up));
    let flat = flat.try_normalize().unwrap_or(up.any_orthonormal_vector());
    let dir = up * new_polar.cos() + flat * new_polar.sin();
    Camera {
        eye: (target + dir * r).to_array(),
        ..*c
    }
}

/// The camera and its target moved across the view by (dx, dy) pixels of an image `height`
/// pixels tall, so that the point under the cursor follows it.
pub fn pan(c: &Camera, dx: f64, dy: f64, height: f64) -> Camera {
    let (eye, target, up) = parts(c);
    let forward = (target - eye).try_normalize().unwrap_or(DVec3::NEG_Y);
    let right = forward.cross(up).try_normalize().unwrap_or(DVec3::X);
    let true_up = right.cross(forward);
    let per_pixel =
        2.0 * (eye - target).length() * (0.5 * c.fov_deg.to_radians()).tan() / height.max(1.0);
    let shift = (-right * dx + true_up * dy) * per_pixel;
    Camera {
        eye: (eye + shift).to_array(),
        target: (target + shift).to_array(),
        ..*c
    }
}

/// The eye moved toward (factor < 1) or away from (factor > 1) the target.
pub fn zoom(c: &Camera, factor: f64) -> Camera {
    let (eye, target, _) = parts(c);
    let factor = if factor.is_finite() {
        factor.clamp(0.1, 10.0)
    } else {
        1.0
    };
    Camera {
        eye: (target + (eye - target) * factor).to_array(),
        ..*c
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera {
            eye: [0.0, -50.0, 10.0],
            target: [0.0, 0.0, 5.0],
            up: [0.0, 0.0, 1.0],
            fov_deg: 30.0,
        }
    }

    fn distance(c: &Camera) -> f64 {
        (DVec3::from_array(c.eye) - DVec3::from_array(c.target)).length()
    }

    /// Orbiting keeps the distance and target, a sideways drag keeps the height, and an orbit
    /// there and back returns to the start.
    #[test]
    fn orbit_keeps_distance_and_undoes() {
        let c = camera();
        let side = orbit(&c, 40.0, 0.0);
        assert!((distance(&side) - distance(&c)).abs() < 1e-9);
        assert_eq!(side.target, c.target);
        assert!((side.eye[2] - c.eye[2]).abs() < 1e-9);
        assert!((side.eye[0] - c.eye[0]).abs() > 1.0);
        let back = orbit(&orbit(&c, 30.0, 12.0), -30.0, -12.0);
        let d = DVec3::from_array(back.eye) - DVec3::from_array(c.eye);
        assert!(d.length() < 1e-6, "{d}");
        let up = orbit(&c, 0.0, 1e6);
        assert!(up.eye[2] < c.target[2] + distance(&c) && up.eye[2] > c.eye[2]);
    }

    #[test]
    fn pan_moves_eye_and_target_together_and_zoom_scales_distance() {
        let c = camera();
        let p = pan(&c, 10.0, 0.0, 100.0);
        let shift = DVec3::from_array(p.eye) - DVec3::from_array(c.eye);
        let shift_t = DVec3::from_array(p.target) - DVec3::from_array(c.target);
        assert!((shift - shift_t).length() < 1e-9 && shift.length() > 0.1);
        let z = zoom(&c, 0.5);
        assert!((distance(&z) - 0.5 * distance(&c)).abs() < 1e-9);
        assert_eq!(zoom(&c, f64::NAN), c);
    }
}

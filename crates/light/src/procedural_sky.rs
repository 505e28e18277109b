//! The project's default environment, built in code (docs/conventions.md §6): a blue sky graded to
//! a pale horizon, a warm sun disc with a soft aureole as the bright, compact key light for hair
//! highlights, and a dim earthy ground. Radiance is linear and in arbitrary but consistent units
//! (the zenith is about 0.3, the sun disc about 2000).

use crate::EnvMap;
use crate::latlong::direction_from_angles;
use glam::DVec3;

/// Parameters of the procedural sky (+y up, azimuth φ = atan2(z, x) as in the crate docs).
#[derive(Clone, Debug, PartialEq)]
pub struct ProceduralSky {
    /// Sun elevation above the horizon, radians.
    pub sun_elevation: f64,
    /// Sun azimuth φ, radians.
    pub sun_azimuth: f64,
    /// Angular radius of the sun disc, radians (larger than the real sun's 0.27° so that a
    /// 1k map resolves it and an SRBF fit keeps it compact).
    pub sun_radius: f64,
    /// Radiance of the sun disc.
    pub sun_radiance: DVec3,
    /// Peak radiance added by the aureole around the sun, and its angular width (radians).
    pub aureole_radiance: DVec3,
    pub aureole_width: f64,
    pub zenith: DVec3,
    pub horizon: DVec3,
    pub ground: DVec3,
}

impl Default for ProceduralSky {
    fn default() -> Self {
        Self {
            sun_elevation: 35f64.to_radians(),
            sun_azimuth: 45f64.to_radians(),
            sun_radius: 2f64.to_radians(),
            sun_radiance: DVec3::new(2000.0, 1850.0, 1600.0),
            aureole_radiance: DVec3::new(3.0, 2.6, 2.0),
            aureole_width: 8f64.to_radians(),
            zenith: DVec3::new(0.12, 0.25, 0.6),
            horizon: DVec3::new(0.75, 0.8, 0.9),
            ground: DVec3::new(0.22, 0.18, 0.14),
        }
    }
}

impl ProceduralSky {
    /// Unit direction toward the sun's centre.
    pub fn sun_direction(&self) -> DVec3 {
        direction_from_angles(self.sun_elevation, self.sun_azimuth)
    }

    /// Radiance from unit direction `dir`: sky gradient + aureole above the horizon, ground below
    /// (blended over ±0.5° so the horizon is not a hard step), plus the sun disc.
    pub fn radiance(&self, dir: DVec3) -> DVec3 {
        let cos_to_sun = dir.dot(self.sun_direction()).clamp(-1.0, 1.0);
        let angle_to_sun = cos_to_sun.acos();
        let sky = self.sky(dir.y.max(0.0), angle_to_sun);
        let ground = self.ground * (0.6 + 0.4 * (1.0 + dir.y).max(0.0));
        let blend = smoothstep(-0.009, 0.009, dir.y);
        let sun = if angle_to_sun < self.sun_radius {
            self.sun_radiance
        } else {
            DVec3::ZERO
        };
        ground.lerp(sky, blend) + sun
    }

    /// The sky above the horizon: zenith → horizon gradient in √(sin θ), plus a Gaussian aureole.
    fn sky(&self, sin_elevation: f64, angle_to_sun: f64) -> DVec3 {
        let gradient = self.horizon.lerp(self.zenith, sin_elevation.sqrt());
        let x = angle_to_sun / self.aureole_width;
        gradient + self.aureole_radiance * (-x * x).exp()
    }

    /// A `width × width/2` map, each pixel the mean of 4 × 4 stratified samples (so the sun disc's
    /// edge is antialiased and its power is close to the analytic one).
    pub fn to_env_map(&self, width: usize) -> EnvMap {
        let height = (width / 2).max(1);
        let n = 4;
        let d_theta = std::f64::consts::PI / height as f64;
        let d_phi = 2.0 * std::f64::consts::PI / width as f64;
        EnvMap::from_fn(width, height, |centre| {
            let (theta, phi) = crate::latlong::direction_to_angles(centre);
            let mut sum = DVec3::ZERO;
            for a in 0..n {
                for b in 0..n {
                    let t = theta + d_theta * ((a as f64 + 0.5) / n as f64 - 0.5);
                    let p = phi + d_phi * ((b as f64 + 0.5) / n as f64 - 0.5);
                    sum += self.radiance(direction_from_angles(t, p));
                }
            }
            (sum / (n * n) as f64).as_vec3()
        })
    }
}

fn smoothstep(edge0: f64, edge1: f64, x: f64) -> f64 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::luminance;

    #[test]
    fn the_sun_is_a_compact_key_light() {
        let sky = ProceduralSky::default();
        let map = sky.to_env_map(512);
        let sun = sky.sun_direction();
        let (mut near, mut total) = (0.0, 0.0);
        for p in map.iter() {
            let power = luminance(p.radiance) as f64 * p.solid_angle;
            total += power;
            if p.direction.dot(sun) > (3.0 * sky.sun_radius).cos() {
                near += power;
            }
        }
        let fraction = near / total;
        assert!(
            fraction > 0.5 && fraction < 0.95,
            "sun holds {fraction} of the power"
        );
        let disc = 2.0 * std::f64::consts::PI * (1.0 - sky.sun_radius.cos());
        let sun_power = luminance(sky.sun_radiance.as_vec3()) as f64 * disc;
        assert!(near > sun_power && near < 1.2 * sun_power);
    }

    #[test]
    fn sky_is_blue_above_and_ground_is_darker_below() {
        let sky = ProceduralSky::default();
        let zenith = sky.radiance(DVec3::Y);
        let nadir = sky.radiance(-DVec3::Y);
        let horizon = sky.radiance(DVec3::new(-1.0, 0.02, 0.0).normalize());
        assert!(zenith.z > zenith.x && zenith.z > zenith.y);
        assert!(luminance(horizon.as_vec3()) > luminance(zenith.as_vec3()));
        assert!(luminance(nadir.as_vec3()) < luminance(horizon.as_vec3()));
        assert!(sky.radiance(sky.sun_direction()).min_element() > 1000.0);
    }
}

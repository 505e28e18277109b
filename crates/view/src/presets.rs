//! Colour presets: melanin concentrations (eumelanin, pheomelanin) that read as the named hair
//! under the default sky, through the fiber crate's melanin mapping (d'Eon et al. 2011's
//! absorption spectra). The values are this project's choice, not measurements.

use cuticle_groom::Absorption;

/// A named hair colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    pub name: &'static str,
    pub eumelanin: f32,
    pub pheomelanin: f32,
}

pub const PRESETS: [Preset; 5] = [
    Preset {
        name: "black",
        eumelanin: 8.0,
        pheomelanin: 0.0,
    },
    Preset {
        name: "brown",
        eumelanin: 1.3,
        pheomelanin: 0.2,
    },
    Preset {
        name: "auburn",
        eumelanin: 0.4,
        pheomelanin: 2.5,
    },
    Preset {
        name: "blond",
        eumelanin: 0.15,
        pheomelanin: 0.4,
    },
    Preset {
        name: "white",
        eumelanin: 0.0,
        pheomelanin: 0.0,
    },
];

impl Preset {
    pub fn absorption(&self) -> Absorption {
        Absorption::Melanin {
            eumelanin: self.eumelanin,
            pheomelanin: self.pheomelanin,
        }
    }
}

/// The preset of this name.
pub fn by_name(name: &str) -> Option<Preset> {
    PRESETS.iter().copied().find(|p| p.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;
    use cuticle_render::scene::hair::mu_a_of;

    /// From black to white each preset absorbs less in every channel, and auburn is the
    /// reddest (its blue absorbed most relative to red).
    #[test]
    fn presets_run_dark_to_light_and_auburn_is_red() {
        let s = |n| mu_a_of(by_name(n).unwrap().absorption());
        let order = ["black", "brown", "blond", "white"];
        for pair in order.windows(2) {
            let (a, b) = (s(pair[0]), s(pair[1]));
            assert!(a.cmpgt(b).all(), "{} {a} vs {} {b}", pair[0], pair[1]);
        }
        let red = |n| s(n).z / s(n).x;
        assert!(red("auburn") > red("brown") && red("auburn") > red("blond"));
    }
}

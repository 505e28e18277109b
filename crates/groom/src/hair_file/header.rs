//! The 128-byte header of a `.hair` file: magic, counts, array flags, defaults and info text,
//! all little-endian.

use crate::error::HairFileError;
use glam::Vec3;

/// Size of the header in bytes; the arrays follow it.
pub const HEADER_LEN: usize = 128;
/// Size of the free-text info field that closes the header.
pub const INFO_LEN: usize = 88;
/// The four bytes every `.hair` file starts with.
pub const MAGIC: [u8; 4] = *b"HAIR";

/// Which optional arrays a file holds, in the order they follow the header.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize)]
pub struct ArrayFlags {
    /// Per strand: its number of segments (points − 1), as u16.
    pub segments: bool,
    /// Per point: x, y, z as f32.
    pub points: bool,
    /// Per point: thickness as f32.
    pub thickness: bool,
    /// Per point: transparency as f32.
    pub transparency: bool,
    /// Per point: r, g, b as f32.
    pub colors: bool,
}

impl ArrayFlags {
    const SEGMENTS: u32 = 1;
    const POINTS: u32 = 2;
    const THICKNESS: u32 = 4;
    const TRANSPARENCY: u32 = 8;
    const COLORS: u32 = 16;
    const DEFINED: u32 = 0x1f;

    /// Decodes the header's flag word, refusing bits the format does not define.
    pub fn from_bits(bits: u32) -> Result<Self, HairFileError> {
        if bits & !Self::DEFINED != 0 {
            return Err(HairFileError::UnknownFlags { flags: bits });
        }
        Ok(Self {
            segments: bits & Self::SEGMENTS != 0,
            points: bits & Self::POINTS != 0,
            thickness: bits & Self::THICKNESS != 0,
            transparency: bits & Self::TRANSPARENCY != 0,
            colors: bits & Self::COLORS != 0,
        })
    }

    /// The header's flag word.
    pub fn bits(self) -> u32 {
        [
            (self.segments, Self::SEGMENTS),
            (self.points, Self::POINTS),
            (self.thickness, Self::THICKNESS),
            (self.transparency, Self::TRANSPARENCY),
            (self.colors, Self::COLORS),
        ]
        .iter()
        .filter(|(present, _)| *present)
        .fold(0, |bits, (_, bit)| bits | bit)
    }

    /// All 32 combinations of the five arrays.
    pub fn all_combinations() -> impl Iterator<Item = ArrayFlags> {
        (0..=Self::DEFINED).map(|bits| Self::from_bits(bits).expect("bits are within DEFINED"))
    }
}

/// The values that stand in for an array the file leaves out.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct HairDefaults {
    /// Segments of every strand when there is no segments array (points per strand − 1).
    pub segments: u32,
    pub thickness: f32,
    pub transparency: f32,
    pub color: [f32; 3],
}

impl Default for HairDefaults {
    fn default() -> Self {
        Self {
            segments: 0,
            thickness: 1.0,
            transparency: 0.0,
            color: [1.0; 3],
        }
    }
}

impl HairDefaults {
    /// The default colour as a vector.
    pub fn color_vec(&self) -> Vec3 {
        Vec3::from_array(self.color)
    }
}

/// The header's 88-byte free-text field, kept byte for byte so files round-trip exactly.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct HairInfo(pub [u8; INFO_LEN]);

impl Default for HairInfo {
    fn default() -> Self {
        Self([0; INFO_LEN])
    }
}

impl HairInfo {
    /// Info holding `text`, cut to 88 bytes at a character boundary and padded with zeros.
    pub fn from_text(text: &str) -> Self {
        let mut end = text.len().min(INFO_LEN);
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        let mut bytes = [0; INFO_LEN];
        bytes[..end].copy_from_slice(&text.as_bytes()[..end]);
        Self(bytes)
    }

    /// The text up to the first zero byte (invalid UTF-8 replaced).
    pub fn text(&self) -> String {
        let end = self.0.iter().position(|&b| b == 0).unwrap_or(INFO_LEN);
        String::from_utf8_lossy(&self.0[..end]).into_owned()
    }
}

impl std::fmt::Debug for HairInfo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "HairInfo({:?})", self.text())
    }
}

/// Everything the header says, decoded but not yet checked against the rest of the file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Header {
    pub strand_count: u32,
    pub point_count: u32,
    pub flags: ArrayFlags,
    pub defaults: HairDefaults,
    pub info: HairInfo,
}

impl Header {
    /// Decodes the first 128 bytes of a file: checks the magic and the flag bits.
    pub fn decode(bytes: &[u8; HEADER_LEN]) -> Result<Self, HairFileError> {
        let magic: [u8; 4] = field(bytes, 0);
        if magic != MAGIC {
            return Err(HairFileError::BadMagic { found: magic });
        }
        let u32_at = |at| u32::from_le_bytes(field(bytes, at));
        let f32_at = |at| f32::from_le_bytes(field(bytes, at));
        Ok(Self {
            strand_count: u32_at(4),
            point_count: u32_at(8),
            flags: ArrayFlags::from_bits(u32_at(12))?,
            defaults: HairDefaults {
                segments: u32_at(16),
                thickness: f32_at(20),
                transparency: f32_at(24),
                color: [f32_at(28), f32_at(32), f32_at(36)],
            },
            info: HairInfo(field(bytes, 40)),
        })
    }

    /// The 128 bytes of this header.
    pub fn encode(&self) -> [u8; HEADER_LEN] {
        let d = &self.defaults;
        let mut out = [0; HEADER_LEN];
        let words: [[u8; 4]; 10] = [
            MAGIC,
            self.strand_count.to_le_bytes(),
            self.point_count.to_le_bytes(),
            self.flags.bits().to_le_bytes(),
            d.segments.to_le_bytes(),
            d.thickness.to_le_bytes(),
            d.transparency.to_le_bytes(),
            d.color[0].to_le_bytes(),
            d.color[1].to_le_bytes(),
            d.color[2].to_le_bytes(),
        ];
        for (slot, word) in out.chunks_exact_mut(4).zip(words) {
            slot.copy_from_slice(&word);
        }
        out[40..].copy_from_slice(&self.info.0);
        out
    }
}

/// `N` bytes of the header starting at `at`.
fn field<const N: usize>(bytes: &[u8; HEADER_LEN], at: usize) -> [u8; N] {
    let mut out = [0; N];
    out.copy_from_slice(&bytes[at..at + N]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flag_bits_round_trip_for_all_32_combinations() {
        let all: Vec<u32> = ArrayFlags::all_combinations()
            .map(ArrayFlags::bits)
            .collect();
        assert_eq!(all, (0..32).collect::<Vec<u32>>());
    }

    #[test]
    fn flag_bits_name_the_right_arrays() {
        let straight = ArrayFlags::from_bits(0x12).unwrap();
        assert!(straight.points && straight.colors);
        assert!(!straight.segments && !straight.thickness && !straight.transparency);
    }

    #[test]
    fn undefined_flag_bits_are_refused() {
        for bits in [0x20, 0x80, 0x8000_0000] {
            let err = ArrayFlags::from_bits(bits).unwrap_err();
            assert!(matches!(err, HairFileError::UnknownFlags { flags } if flags == bits));
        }
    }

    #[test]
    fn header_encodes_each_field_at_its_offset() {
        let header = Header {
            strand_count: 7,
            point_count: 0x0102_0304,
            flags: ArrayFlags::from_bits(0x15).unwrap(),
            defaults: HairDefaults {
                segments: 9,
                thickness: 0.5,
                transparency: 0.25,
                color: [0.1, 0.2, 0.3],
            },
            info: HairInfo::from_text("made by a test"),
        };
        let bytes = header.encode();
        assert_eq!(&bytes[0..4], b"HAIR");
        assert_eq!(bytes[4..8], 7u32.to_le_bytes());
        assert_eq!(bytes[8..12], [4, 3, 2, 1]);
        assert_eq!(bytes[12..16], 0x15u32.to_le_bytes());
        assert_eq!(bytes[16..20], 9u32.to_le_bytes());
        assert_eq!(bytes[20..24], 0.5f32.to_le_bytes());
        assert_eq!(bytes[24..28], 0.25f32.to_le_bytes());
        assert_eq!(bytes[36..40], 0.3f32.to_le_bytes());
        assert_eq!(&bytes[40..54], b"made by a test");
        assert_eq!(Header::decode(&bytes).unwrap(), header);
    }

    #[test]
    fn info_is_cut_at_a_character_boundary() {
        let text = "é".repeat(50);
        let info = HairInfo::from_text(&text);
        assert_eq!(info.text(), "é".repeat(44));
        assert_eq!(HairInfo::from_text("abc").text(), "abc");
    }
}

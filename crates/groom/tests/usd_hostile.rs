//! Hostile USD gets what hostile `.hair` gets: one error, no panic, no unbounded allocation.

use cuticle_groom::usd::{PrimFault, UsdError};
use cuticle_groom::{Groom, GroomReadError};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/usd")
        .join(name)
}

/// Reads `path`, which must be refused as USD; returns the error.
fn refused(path: &Path) -> UsdError {
    match Groom::read(path) {
        Ok(g) => panic!("{} was read: {} strands", path.display(), g.strand_count()),
        Err(GroomReadError::Usd(e)) => {
            let line = e.to_string();
            assert!(!line.contains('\n'), "more than one line: {line}");
            e
        }
        Err(other) => panic!("{}: not a USD error: {other}", path.display()),
    }
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

const HEADER: &str = "#usda 1.0\n(\n    metersPerUnit = 0.01\n    upAxis = \"Z\"\n)\n";

/// A stage of one BasisCurves prim with `body` inside it.
fn stage(dir: &Path, name: &str, body: &str) -> PathBuf {
    write(
        dir,
        name,
        format!("{HEADER}\ndef BasisCurves \"Hair\"\n{{\n{body}\n}}\n"),
    )
}

fn prim_fault(e: UsdError) -> PrimFault {
    match e {
        UsdError::Prim { fault, .. } => fault,
        other => panic!("not a prim's fault: {other}"),
    }
}

const FOUR: &str = "point3f[] points = [(0,0,0), (0,0,1), (0,0,2), (0,0,3)]";

#[test]
fn a_curve_with_fewer_points_than_its_basis_needs() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        (
            "uniform token type = \"cubic\"\nuniform token basis = \"bspline\"",
            3,
            "at least 4",
        ),
        (
            "uniform token type = \"cubic\"\nuniform token basis = \"bezier\"",
            3,
            "3 per segment",
        ),
        (
            "uniform token type = \"cubic\"\nuniform token basis = \"catmullRom\"\nuniform token wrap = \"pinned\"",
            1,
            "at least 2",
        ),
        ("uniform token type = \"linear\"", 1, "at least 2"),
    ];
    for (i, (kind, count, needs)) in cases.into_iter().enumerate() {
        let points: Vec<String> = (0..count).map(|k| format!("(0,0,{k})")).collect();
        let body = format!(
            "{kind}\nint[] curveVertexCounts = [4, {count}]\npoint3f[] points = [(1,0,0), (1,0,1), (1,0,2), (1,0,3), {}]",
            points.join(", ")
        );
        let e = refused(&stage(tmp.path(), &format!("few{i}.usda"), &body));
        let line = e.to_string();
        assert!(
            matches!(prim_fault(e), PrimFault::TooFewPoints { curve: 1, .. })
                && line.contains(needs),
            "{line}"
        );
    }
    // a Bézier of 5 points is no whole number of segments.
    let body = "uniform token type = \"cubic\"\nint[] curveVertexCounts = [5]\npoint3f[] points = [(0,0,0), (0,0,1), (0,0,2), (0,0,3), (0,0,4)]";
    assert!(matches!(
        prim_fault(refused(&stage(tmp.path(), "b5.usda", body))),
        PrimFault::TooFewPoints { .. }
    ));
}

#[test]
fn nan_points_negative_widths_and_bad_lengths_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let linear = "uniform token type = \"linear\"\nint[] curveVertexCounts = [4]";
    let nan = format!("{linear}\npoint3f[] points = [(0,0,0), (0,nan,1), (0,0,2), (0,0,3)]");
    assert!(matches!(
        prim_fault(refused(&stage(tmp.path(), "nan.usda", &nan))),
        PrimFault::NonFinite { .. }
    ));
    let negative = format!(
        "{linear}\n{FOUR}\nfloat[] widths = [0.1, -0.2, 0.1, 0.1] (interpolation = \"vertex\")"
    );
    let fault = prim_fault(refused(&stage(tmp.path(), "neg.usda", &negative)));
    assert!(
        matches!(fault, PrimFault::Negative { index: 1, .. }),
        "{fault}"
    );
    let short =
        format!("{linear}\n{FOUR}\nfloat[] widths = [0.1, 0.2] (interpolation = \"vertex\")");
    let fault = prim_fault(refused(&stage(tmp.path(), "short.usda", &short)));
    assert!(
        matches!(
            fault,
            PrimFault::Length {
                expected: 4,
                actual: 2,
                ..
            }
        ),
        "{fault}"
    );
    let mismatch = format!(
        "uniform token type = \"linear\"\nint[] curveVertexCounts = [2147483647, 2]\n{FOUR}"
    );
    let fault = prim_fault(refused(&stage(tmp.path(), "counts.usda", &mismatch)));
    assert!(
        matches!(fault, PrimFault::CountMismatch { points: 4, .. }),
        "{fault}"
    );
    let negative_count =
        format!("uniform token type = \"linear\"\nint[] curveVertexCounts = [-2, 6]\n{FOUR}");
    assert!(matches!(
        prim_fault(refused(&stage(tmp.path(), "negc.usda", &negative_count))),
        PrimFault::TooFewPoints {
            curve: 0,
            count: -2,
            ..
        }
    ));
    let melanin =
        format!("{linear}\n{FOUR}\nfloat[] primvars:melanin = [1.5] (interpolation = \"uniform\")");
    assert!(matches!(
        prim_fault(refused(&stage(tmp.path(), "mel.usda", &melanin))),
        PrimFault::NotAFraction { .. }
    ));
    let eumelanin =
        format!("{linear}\n{FOUR}\nfloat primvars:eumelanin = -1 (interpolation = \"constant\")");
    assert!(matches!(
        prim_fault(refused(&stage(tmp.path(), "eu.usda", &eumelanin))),
        PrimFault::Negative { .. }
    ));
}

#[test]
fn what_this_reader_does_not_draw_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    for (attr, value) in [
        ("wrap", "periodic"),
        ("basis", "hermite"),
        ("type", "quadratic"),
    ] {
        let body = format!(
            "uniform token type = \"cubic\"\nuniform token {attr} = \"{value}\"\nint[] curveVertexCounts = [4]\n{FOUR}"
        );
        let fault = prim_fault(refused(&stage(tmp.path(), &format!("{value}.usda"), &body)));
        assert!(
            matches!(&fault, PrimFault::Unsupported { value: v, .. } if v == value),
            "{fault}"
        );
    }
    let empty = write(
        tmp.path(),
        "empty.usda",
        format!("{HEADER}\ndef Xform \"Nothing\"\n{{\n}}\n"),
    );
    assert!(matches!(refused(&empty), UsdError::NoCurves));
    let up = write(
        tmp.path(),
        "up.usda",
        "#usda 1.0\n(\n    upAxis = \"X\"\n)\n",
    );
    assert!(matches!(
        refused(&up),
        UsdError::StageMetadata {
            field: "upAxis",
            ..
        }
    ));
    let units = write(
        tmp.path(),
        "units.usda",
        "#usda 1.0\n(\n    metersPerUnit = -1\n)\n",
    );
    assert!(matches!(
        refused(&units),
        UsdError::StageMetadata {
            field: "metersPerUnit",
            ..
        }
    ));
    let text = write(
        tmp.path(),
        "junk.usda",
        "#usda 1.0\ndef BasisCurves \"H\" {{{{ ((( ",
    );
    assert!(matches!(refused(&text), UsdError::Open(_)));
}

#[test]
fn a_cycle_of_references_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let curves = format!("uniform token type = \"linear\"\nint[] curveVertexCounts = [4]\n{FOUR}");
    write(
        tmp.path(),
        "a.usda",
        format!(
            "{HEADER}\ndef Xform \"Root\" (references = @./b.usda@</Root>)\n{{\n    def BasisCurves \"Hair\"\n    {{\n{curves}\n    }}\n}}\n"
        ),
    );
    write(
        tmp.path(),
        "b.usda",
        format!("{HEADER}\ndef Xform \"Root\" (references = @./a.usda@</Root>)\n{{\n}}\n"),
    );
    let e = refused(&tmp.path().join("a.usda"));
    assert!(e.to_string().contains("cycle"), "{e}");
    // a cycle of sublayers.
    write(
        tmp.path(),
        "c.usda",
        "#usda 1.0\n(\n    subLayers = [@./d.usda@]\n)\n",
    );
    write(
        tmp.path(),
        "d.usda",
        "#usda 1.0\n(\n    subLayers = [@./c.usda@]\n)\n",
    );
    refused(&tmp.path().join("c.usda"));
}

/// Where the `points` array of upright_z_m.usdc (4 points, the first (0, 0, 0.1)) keeps its
/// count: the u64 right before the first point.
fn points_count_at(bytes: &[u8]) -> usize {
    let mut pattern = 4u64.to_le_bytes().to_vec();
    for v in [0.0f32, 0.0, 0.1] {
        pattern.extend(v.to_le_bytes());
    }
    bytes
        .windows(pattern.len())
        .position(|w| w == pattern)
        .expect("the fixture's points array")
}

#[test]
fn a_usdc_declaring_two_to_the_31_points_is_refused_before_allocating() {
    let tmp = tempfile::tempdir().unwrap();
    let mut bytes = std::fs::read(data("upright_z_m.usdc")).unwrap();
    let at = points_count_at(&bytes);
    for count in [1u64 << 31, 1 << 40, u64::MAX] {
        bytes[at..at + 8].copy_from_slice(&count.to_le_bytes());
        let path = write(tmp.path(), "huge.usdc", &bytes);
        let e = refused(&path);
        assert!(e.to_string().contains("declares"), "{count}: {e}");
    }
}

/// The same inside a `.usdz` package (which the USD library unpacks without the resolver).
#[test]
fn a_usdz_holding_such_a_usdc_is_refused_too() {
    use std::io::Write;
    let tmp = tempfile::tempdir().unwrap();
    let mut bytes = std::fs::read(data("upright_z_m.usdc")).unwrap();
    let at = points_count_at(&bytes);
    bytes[at..at + 8].copy_from_slice(&(1u64 << 31).to_le_bytes());
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let stored =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    zip.start_file("huge.usdc", stored).unwrap();
    zip.write_all(&bytes).unwrap();
    let package = zip.finish().unwrap().into_inner();
    let e = refused(&write(tmp.path(), "huge.usdz", package));
    assert!(e.to_string().contains("declares 2147483648"), "{e}");
    // and a package cut short.
    let whole = std::fs::read(data("upright_z_m.usdz")).unwrap();
    refused(&write(tmp.path(), "cut.usdz", &whole[..whole.len() / 2]));
}

#[test]
fn a_truncated_or_scrambled_usdc_is_refused_without_a_panic() {
    let tmp = tempfile::tempdir().unwrap();
    let bytes = std::fs::read(data("transforms.usdc")).unwrap();
    for len in [0, 8, 16, 24, 88, bytes.len() / 2, bytes.len() - 1] {
        let path = write(tmp.path(), "cut.usdc", &bytes[..len]);
        refused(&path);
    }
    // every byte of the file in turn flipped: refused or read, never a panic or a hang.
    for i in 0..bytes.len() {
        let mut b = bytes.clone();
        b[i] ^= 0xff;
        let path = write(tmp.path(), "flip.usdc", &b);
        let _ = Groom::read(&path);
    }
}

#[test]
fn hair_files_keep_their_reader_and_their_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let junk = write(tmp.path(), "junk.hair", b"HAIx then nothing much at all");
    let e = Groom::read(&junk).unwrap_err();
    assert!(matches!(e, GroomReadError::Hair(_)), "{e}");
    let hair = cuticle_groom::HairFile::read(&junk).unwrap_err();
    assert_eq!(e.to_string(), hair.to_string());
    assert!(matches!(
        Groom::read(tmp.path()).unwrap_err(),
        GroomReadError::Hair(_)
    ));
    // a .hair name is read as .hair whatever it holds: a USD stage there gets the .hair error.
    let usda = std::fs::read(data("bases.usda")).unwrap();
    let named = write(tmp.path(), "really.hair", &usda);
    let e = Groom::read(&named).unwrap_err();
    assert!(
        matches!(e, GroomReadError::Hair(_)) && e.to_string().contains("\"HAIR\""),
        "{e}"
    );
    // with no extension the content decides, and the USD reader asks for one.
    let bare = write(tmp.path(), "groom", &usda);
    assert!(refused(&bare).to_string().contains("extension"));
}

//! The 3MF loader's unit tests.

use std::io::Write;

use super::part::{color, transform};
use super::*;

const MODEL: &str = r#"<model xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"><resources>
    <object id="1"><mesh><vertices><vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/>
    <vertex x="0" y="1" z="0"/></vertices><triangles><triangle v1="0" v2="1" v3="2"/></triangles>
    </mesh></object></resources><build><item objectid="1"/></build></model>"#;

/// A deflated archive holding `model` as the 3D model part.
fn archive(model: &str) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file(DEFAULT_MODEL_PART, options).unwrap();
    zip.write_all(model.as_bytes()).unwrap();
    zip.finish().unwrap().into_inner()
}

fn message(bytes: &[u8], limit: u64) -> String {
    parse_within(Path::new("t.3mf"), bytes, limit).unwrap_err().to_string()
}

#[test]
fn a_part_that_inflates_past_its_declared_size_stops_at_the_limit() {
    let padded = MODEL.replace("<build>", &format!("{}<build>", " ".repeat(10_000)));
    let mut bytes = archive(&padded);
    assert_eq!(parse_within(Path::new("t.3mf"), &bytes, 20_000).unwrap().len(), 1);
    let m = message(&bytes, 1000);
    assert!(m.contains(&format!("declares {} bytes uncompressed", padded.len())), "{m}");
    // The central directory lies: 100 bytes.
    let at = bytes.windows(4).position(|w| w == b"PK\x01\x02").unwrap();
    bytes[at + 24..at + 28].copy_from_slice(&100u32.to_le_bytes());
    let m = message(&bytes, 1000);
    assert_eq!(m, "t.3mf: 3D/3dmodel.model: inflates to more than the limit of 1000 bytes for model parts");
}

#[test]
fn a_text_longer_than_the_token_limit_is_refused_as_it_streams() {
    let long = MODEL.replace("<build>", &format!("{}<build>", "x".repeat(MAX_XML_TOKEN as usize + 1)));
    let m = message(&archive(&long), MAX_MODEL_FILE_BYTES);
    assert!(
        m.starts_with("t.3mf: 3D/3dmodel.model: cannot read the part: a text or tag longer than 16 MiB"),
        "{m}"
    );
}

#[test]
fn archives_of_too_many_entries_are_refused_before_the_zip_crate_reads_them() {
    let mut bytes = b"PK\x03\x04".to_vec();
    for _ in 0..=MAX_ARCHIVE_ENTRIES {
        bytes.extend(b"PK\x01\x02");
    }
    let m = message(&bytes, MAX_MODEL_FILE_BYTES);
    assert_eq!(m, "t.3mf: ZIP archive of more than 10000 entries, more than the limit for a 3MF file");
    assert!(message(b"PK\x03\x04 but nothing more", 1000).contains("not a 3MF file: bad ZIP archive"));
}

#[test]
fn colours_and_transforms_parse_as_the_specification_writes_them() {
    assert_eq!(color("c", "#ff800080"), Ok([255, 128, 0, 128]));
    assert_eq!(color("c", " #102030 "), Ok([16, 32, 48, 255]));
    for bad in ["ff8000", "#ff80", "#ff80000", "#gg0000", "#ff800080ff"] {
        assert!(color("c", bad).unwrap_err().contains("is not a colour"), "{bad}");
    }
    let m = transform("1 0 0 0 1 0 0 0 1 1 2 3").unwrap();
    assert_eq!(m.transform_point3(glam::DVec3::ZERO), glam::DVec3::new(1.0, 2.0, 3.0));
    for bad in ["1 0 0 0 1 0 0 0 1 0 0", "1 0 0 0 1 0 0 0 1 0 0 0 0", "1 0 0 0 1 0 0 0 1 0 0 inf"] {
        assert!(transform(bad).unwrap_err().contains("is not 12 finite numbers"), "{bad}");
    }
    assert_eq!(quote(&"é".repeat(100)).chars().count(), 61);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

    /// Any bytes changed anywhere in a valid file (stored or deflated)
    /// give meshes or an error naming the file, never a panic.
    #[test]
    fn corrupted_files_never_panic(
        edits in proptest::collection::vec((0usize..4096, proptest::prelude::any::<u8>()), 1..8),
        deflated in proptest::prelude::any::<bool>(),
    ) {
        let mut bytes = if deflated {
            include_bytes!("../../../../assets/3mf/assembly.3mf").to_vec()
        } else {
            include_bytes!("../../../../assets/3mf/cube.3mf").to_vec()
        };
        for (at, value) in edits {
            let n = bytes.len();
            bytes[at % n] = value;
        }
        if let Err(e) = parse_3mf(Path::new("fuzz.3mf"), &bytes) {
            proptest::prop_assert!(e.to_string().starts_with("fuzz.3mf: "), "{e}");
        }
    }
}

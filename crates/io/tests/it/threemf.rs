//! 3MF loading: the samples of `assets/3mf/` (made by its
//! `make_samples.py`) give the triangles, places and colours worked out
//! by hand; every broken file `tests/bad/3mf_*.3mf` and every hostile
//! archive made here gives a one-line error naming the file and the
//! problem, never a panic.

use std::io::Write;
use std::path::{Path, PathBuf};

use glam::Vec3;
use zline_io::{load_3mf, MAX_COMPONENT_DEPTH};
use zline_scene::{face_normal, Mesh};

use crate::{check_message, repo};

/// The bounding box of all the meshes.
fn bounds(meshes: &[Mesh]) -> (Vec3, Vec3) {
    let points = meshes.iter().flat_map(|m| m.positions.iter().copied());
    points.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)))
}

#[track_caller]
fn near(a: Vec3, b: Vec3) {
    assert!((a - b).abs().max_element() < 1e-5, "{a} != {b}");
}

/// An archive of `parts` (name, text), deflated, in a fresh file `name`.
fn archive(name: &str, parts: &[(&str, &str)]) -> PathBuf {
    let path = crate::temp_file(name, "");
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&path).unwrap());
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    for (part, text) in parts {
        zip.start_file(*part, options).unwrap();
        zip.write_all(text.as_bytes()).unwrap();
    }
    zip.finish().unwrap();
    path
}

/// A 3MF file whose model part holds `resources` and `build`.
fn three_mf(name: &str, resources: &str, build: &str) -> PathBuf {
    let model = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
<resources>{resources}</resources><build>{build}</build></model>"#
    );
    archive(name, &[("3D/3dmodel.model", &model)])
}

const TRIANGLE: &str = r#"<mesh><vertices><vertex x="1" y="2" z="3"/><vertex x="2" y="2" z="3"/>
<vertex x="1" y="3" z="3"/></vertices><triangles><triangle v1="0" v2="1" v3="2"/></triangles></mesh>"#;

#[test]
fn the_cube_is_scaled_and_moved_by_its_build_item() {
    let meshes = load_3mf(&repo("assets/3mf/cube.3mf")).unwrap();
    assert_eq!(meshes.len(), 1);
    let cube = &meshes[0];
    assert_eq!((cube.name.as_str(), cube.triangle_count(), cube.vertex_count()), ("Cube", 12, 8));
    // transform "2 0 0 0 3 0 0 0 4 10 20 30": [0, 1]³ scaled by (2, 3, 4)
    // then moved by (10, 20, 30).
    let (lo, hi) = bounds(&meshes);
    near(lo, Vec3::new(10.0, 20.0, 30.0));
    near(hi, Vec3::new(12.0, 23.0, 34.0));
    // displaycolor "#FF8000".
    let orange = Vec3::new(1.0, 128.0 / 255.0, 0.0);
    assert_eq!((cube.material.kd, cube.material.ka, cube.material.opacity), (orange, orange, 1.0));
    assert!(cube.is_closed());
    // Outward faces: the corner at the far end points away from the centre.
    let corner = cube.positions.iter().position(|p| *p == Vec3::new(12.0, 23.0, 34.0)).unwrap();
    assert!(cube.normals[corner].min_element() > 0.0, "{}", cube.normals[corner]);
}

#[test]
fn the_assembly_is_split_by_colour_and_placed_through_its_components() {
    let meshes = load_3mf(&repo("assets/3mf/assembly.3mf")).unwrap();
    let names: Vec<&str> = meshes.iter().map(|m| m.name.as_str()).collect();
    // Pair (two wedges through components), then the wedge itself.
    let wedge = ["Wedge (Red)", "Wedge (#00FF0080)", "Wedge (Blue)"];
    assert_eq!(names, [wedge, wedge, wedge].concat());
    let triangles: Vec<usize> = meshes.iter().map(Mesh::triangle_count).collect();
    assert_eq!(triangles, [2, 1, 1, 2, 1, 1, 2, 1, 1]);
    let (red, green, blue) = (&meshes[0].material, &meshes[1].material, &meshes[2].material);
    assert_eq!((red.kd, red.opacity), (Vec3::X, 1.0));
    assert_eq!((green.kd, green.opacity), (Vec3::Y, 128.0 / 255.0));
    assert_eq!((blue.kd, blue.ka, blue.opacity), (Vec3::Z, Vec3::Z, 1.0));
    // The first wedge: moved up by 5; the second: mirrored, x' = −x − 2,
    // then up by 5; the third: turned a quarter about z, x' = 10 − y,
    // y' = x.
    let (lo, hi) = bounds(&meshes[0..3]);
    near(lo, Vec3::new(0.0, 0.0, 5.0));
    near(hi, Vec3::new(1.0, 1.0, 6.0));
    let (lo, hi) = bounds(&meshes[3..6]);
    near(lo, Vec3::new(-3.0, 0.0, 5.0));
    near(hi, Vec3::new(-2.0, 1.0, 6.0));
    let (lo, hi) = bounds(&meshes[6..9]);
    near(lo, Vec3::new(9.0, 0.0, 0.0));
    near(hi, Vec3::new(10.0, 1.0, 1.0));
    near(bounds(&meshes).0, Vec3::new(-3.0, 0.0, 0.0));
    near(bounds(&meshes).1, Vec3::new(10.0, 1.0, 6.0));
    // The bottom face faces down in every copy: the mirrored one's
    // triangles are reversed.
    for red in [&meshes[0], &meshes[3], &meshes[6]] {
        let bottom = (0..red.triangle_count())
            .map(|t| red.triangle(t))
            .find(|t| t.iter().all(|p| p.z == t[0].z))
            .expect("a horizontal triangle");
        near(face_normal(bottom[0], bottom[1], bottom[2]).unwrap(), Vec3::NEG_Z);
    }
}

#[test]
fn production_paths_name_objects_in_other_parts() {
    // _rels/.rels names 3D/main.model, whose component names object 7 of
    // 3D/Objects/part.model.
    let meshes = load_3mf(&repo("assets/3mf/production.3mf")).unwrap();
    assert_eq!(meshes.len(), 1);
    assert_eq!((meshes[0].name.as_str(), meshes[0].triangle_count()), ("Part", 12));
    let (lo, hi) = bounds(&meshes);
    near(lo, Vec3::new(5.0, 0.0, 1.0));
    near(hi, Vec3::new(6.0, 1.0, 2.0));
}

#[test]
fn transforms_map_row_vectors() {
    // p·M with M = "0 1 0  −1 0 0  0 0 2  10 20 30": x' = m00·x + m10·y +
    // m20·z + m30 = 0 − 2 + 0 + 10 = 8, y' = m01·x + m11·y + m21·z + m31 =
    // 1 + 0 + 0 + 20 = 21, z' = m02·x + m12·y + m22·z + m32 = 0 + 0 + 6 +
    // 30 = 36, for p = (1, 2, 3).
    let path = three_mf(
        "turned.3mf",
        &format!(r#"<object id="1">{TRIANGLE}</object>"#),
        r#"<item objectid="1" transform="0 1 0 -1 0 0 0 0 2 10 20 30"/>"#,
    );
    let meshes = load_3mf(&path).unwrap();
    assert_eq!(meshes[0].positions[0], Vec3::new(8.0, 21.0, 36.0));
    // A component's transform applies first: (1, 2, 3) + (1, 0, 0), then
    // doubled.
    let path = three_mf(
        "nested.3mf",
        &format!(
            r#"<object id="1">{TRIANGLE}</object><object id="2"><components>
            <component objectid="1" transform="1 0 0 0 1 0 0 0 1 1 0 0"/></components></object>"#
        ),
        r#"<item objectid="2" transform="2 0 0 0 2 0 0 0 2 0 0 0"/>"#,
    );
    assert_eq!(load_3mf(&path).unwrap()[0].positions[0], Vec3::new(4.0, 4.0, 6.0));
}

#[test]
fn each_broken_sample_gives_its_error() {
    let cases: &[(&str, &[&str])] = &[
        ("3mf_not_a_zip.3mf", &["not a 3MF file: not a ZIP archive"]),
        ("3mf_no_model.3mf", &["the archive has no 3D model part ('3D/3dmodel.model')"]),
        ("3mf_malformed_xml.3mf", &["3D/3dmodel.model: malformed XML at byte", "vertexes"]),
        (
            "3mf_index_out_of_range.3mf",
            &["3D/3dmodel.model: object 1: triangle 0: vertex index 9 is outside 0..3 (the object's vertices)"],
        ),
        ("3mf_nan_coordinate.3mf", &["3D/3dmodel.model: object 1: vertex 1: y 'NaN' is not a finite number"]),
        (
            "3mf_bad_transform.3mf",
            &["3D/3dmodel.model: build item 0: transform '1 0 0 0 1 0 0 0 1 a b c' is not 12 finite numbers"],
        ),
        ("3mf_missing_object.3mf", &["3D/3dmodel.model: build item 0: objectid 7 names no object"]),
        ("3mf_self_component.3mf", &["build item 0: object 1 contains itself (objects 1 → 1)"]),
        ("3mf_deep_components.3mf", &[&format!("components nest more than {MAX_COMPONENT_DEPTH} deep")]),
        ("3mf_bad_color.3mf", &["basematerials 2: entry 0: displaycolor 'red' is not a colour #RRGGBB or #RRGGBBAA"]),
        (
            "3mf_property_out_of_range.3mf",
            &["object 1: triangle 0: property index 5 is outside 0..1 (basematerials 2)"],
        ),
        ("3mf_unknown_extension.3mf", &["requires the 3MF extension 's'", "slice", "which zline does not read"]),
        (
            "3mf_zip_bomb_declared.3mf",
            &["3D/3dmodel.model: declares 4294967294 bytes uncompressed, more than the limit of 1 GiB"],
        ),
    ];
    // The broken files live in the bad-input corpus, `3mf_` before their names.
    let folder = repo("tests/bad");
    let mut on_disk: Vec<String> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|name| name.starts_with("3mf_"))
        .collect();
    on_disk.sort();
    let mut listed: Vec<String> = cases.iter().map(|(f, _)| f.to_string()).collect();
    listed.sort();
    assert_eq!(on_disk, listed, "every broken sample has a case, and every case a file");
    for (file, parts) in cases {
        let path = folder.join(file);
        let e = load_3mf(&path).expect_err(file).to_string();
        assert!(e.starts_with(&format!("{}: ", path.display())), "{e}");
        check_message(&e, parts);
    }
}

/// Objects `ids`, each holding ten of the one before.
fn tens(ids: std::ops::RangeInclusive<u32>) -> String {
    ids.map(|i| {
        let components = format!(r#"<component objectid="{}"/>"#, i - 1).repeat(10);
        format!(r#"<object id="{i}"><components>{components}</components></object>"#)
    })
    .collect()
}

#[test]
fn hostile_structures_are_refused_before_they_are_built() {
    let cases: &[(&str, String, &str, &[&str])] = &[
        // Ten components of ten components … nine levels: 10⁹ placements,
        // counted without walking them.
        (
            "fanout.3mf",
            format!(r#"<object id="1">{TRIANGLE}</object>{}"#, tens(2..=10)),
            r#"<item objectid="10"/>"#,
            &["1000000000 triangles, more than the limit of 16777216"],
        ),
        // The same with an empty object: nothing to draw, but 10⁹ objects
        // to walk.
        (
            "empty_fanout.3mf",
            format!(r#"<object id="1"><mesh><vertices/><triangles/></mesh></object>{}"#, tens(2..=10)),
            r#"<item objectid="10"/>"#,
            &["the build places 1111111111 objects, more than the limit of 1048576"],
        ),
        // A two-colour triangle pair placed 200 × 200 times.
        (
            "many_meshes.3mf",
            format!(
                r##"<basematerials id="9"><base name="a" displaycolor="#FF0000"/>
                <base name="b" displaycolor="#00FF00"/></basematerials>
                <object id="1" pid="9" pindex="0"><mesh><vertices><vertex x="0" y="0" z="0"/>
                <vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/></vertices><triangles>
                <triangle v1="0" v2="1" v3="2"/><triangle v1="0" v2="2" v3="1" pid="9" p1="1"/>
                </triangles></mesh></object>
                <object id="2"><components>{c1}</components></object>
                <object id="3"><components>{c2}</components></object>"##,
                c1 = r#"<component objectid="1"/>"#.repeat(200),
                c2 = r#"<component objectid="2"/>"#.repeat(200),
            ),
            r#"<item objectid="3"/>"#,
            &["the build makes 80000 meshes (objects placed × colours), more than the limit of 65536"],
        ),
        (
            "cycle.3mf",
            r#"<object id="1"><components><component objectid="2"/></components></object>
            <object id="2"><components><component objectid="1"/></components></object>"#
                .into(),
            r#"<item objectid="1"/>"#,
            &["object 1 contains itself (objects 1 → 2 → 1)"],
        ),
        (
            "twice.3mf",
            format!(r#"<object id="1">{TRIANGLE}</object><basematerials id="1"/>"#),
            r#"<item objectid="1"/>"#,
            &["3D/3dmodel.model: two resources have the id 1"],
        ),
        (
            "group.3mf",
            format!(r#"<object id="1">{TRIANGLE}</object><basematerials id="2"/>"#),
            r#"<item objectid="2"/>"#,
            &["build item 0: objectid 2 names a property group, not an object"],
        ),
        (
            "flat.3mf",
            format!(r#"<object id="1">{TRIANGLE}</object>"#),
            r#"<item objectid="1" transform="0 0 0 0 0 0 0 0 0 1 1 1"/>"#,
            &["build item 0: transform '0 0 0 0 0 0 0 0 0 1 1 1' collapses everything to a point"],
        ),
        (
            "infinite.3mf",
            format!(r#"<object id="1">{TRIANGLE}</object>"#),
            r#"<item objectid="1" transform="1e308 0 0 0 1 0 0 0 1 0 0 0"/>"#,
            &["mesh 'object 1': vertex 0 has non-finite position"],
        ),
        (
            "pid.3mf",
            format!(r#"<object id="1" pid="9">{TRIANGLE}</object>"#),
            r#"<item objectid="1"/>"#,
            &["object 1: triangle 0: the object's pid 9 names no property group"],
        ),
        (
            "path.3mf",
            format!(r#"<object id="1">{TRIANGLE}</object>"#),
            r#"<item xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06"
                p:path="/3D/missing.model" objectid="1"/>"#,
            &["3D/3dmodel.model: p:path '3D/missing.model' names no part of the archive"],
        ),
        ("3mf_empty.3mf", format!(r#"<object id="1">{TRIANGLE}</object>"#), "", &["no triangles"]),
        (
            "index.3mf",
            r#"<object id="-1"/>"#.into(),
            "",
            &["object id '-1' is not a whole number (0 or more)"],
        ),
    ];
    for (name, resources, build, parts) in cases {
        let path = three_mf(name, resources, build);
        let e = load_3mf(&path).expect_err(name).to_string();
        assert!(e.starts_with(&format!("{}: ", path.display())), "{e}");
        check_message(&e, parts);
    }
}

#[test]
fn package_problems_name_the_file() {
    let model = |attributes: &str| {
        format!(
            r#"<model {attributes} xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
            <resources><object id="1">{TRIANGLE}</object></resources><build><item objectid="1"/></build></model>"#
        )
    };
    // (file, its parts (name, text), the error's parts)
    type Case<'a> = (&'a str, Vec<(&'a str, String)>, &'a [&'a str]);
    let cases: &[Case] = &[
        (
            "unit.3mf",
            vec![("3D/3dmodel.model", model(r#"unit="furlong""#))],
            &["unit 'furlong' is not one of"],
        ),
        (
            "root.3mf",
            vec![("3D/3dmodel.model", "<svg/>".into())],
            &["the root element is <svg>, not a 3MF <model>"],
        ),
        (
            "two_roots.3mf",
            vec![("3D/3dmodel.model", model("") + "<model/>")],
            &["more than one root element"],
        ),
        ("3mf_truncated.3mf", vec![("3D/3dmodel.model", model("")[..200].into())], &["3D/3dmodel.model: "]),
        (
            "cut.3mf",
            vec![("3D/3dmodel.model", model("").split("<build>").next().unwrap().into())],
            &["3D/3dmodel.model: the XML ends before </model>: the part is cut short"],
        ),
        (
            "entity.3mf",
            vec![("3D/3dmodel.model", model(r#"unit="&bomb;""#))],
            &["3D/3dmodel.model: <model>: "],
        ),
        ("3mf_folder.3mf", vec![("3D/3dmodel.model/", String::new())], &["3D/3dmodel.model"]),
    ];
    for (name, parts, expected) in cases {
        let parts: Vec<(&str, &str)> = parts.iter().map(|(n, t)| (*n, t.as_str())).collect();
        let path = archive(name, &parts);
        let e = load_3mf(&path).expect_err(name).to_string();
        assert!(e.starts_with(&format!("{}: ", path.display())), "{e}");
        check_message(&e, expected);
    }
    // Upper-case part names and a model part without a relationship still
    // load; so does a file without a unit or namespace prefix on its
    // attributes.
    let path = archive("3mf_case.3mf", &[("3D/3DModel.model", &model(""))]);
    assert_eq!(load_3mf(&path).unwrap()[0].triangle_count(), 1);
    let e = load_3mf(Path::new("/nonexistent/x.3mf")).unwrap_err().to_string();
    check_message(&e, &["/nonexistent/x.3mf: cannot read file"]);
}

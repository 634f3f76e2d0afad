//! OBJ+MTL loading: a Wavefront OBJ file → one [`Mesh`] per OBJ object,
//! group or material run.
//!
//! Contract: [`load_obj`] returns at least one mesh with at least one
//! triangle, or a [`SceneError`] naming the file, the line and the text.
//! Polygons are fan-triangulated, points and lines ignored, and each vertex
//! split where its (v, vt, vn) index triple differs (tobj's `single_index`).
//!
//! The OBJ statements are read in parallel by [`read`], which
//! hands on tobj's own `Model` values (tests check it against
//! `tobj::load_obj_buf` bit for bit); tobj reads the MTL files. tobj was
//! the OBJ parser before and stays its definition, so what follows holds
//! for both. tobj's errors carry no location
//! (`PositionParseError`), some malformed input makes it panic (a negative
//! texture index reaching before the first `vt` overflows; an MTL colour
//! with two numbers fails an `unwrap`) and some it silently ignores (a
//! texture index `0` is taken as "none"). So the text is first
//! checked by a small scanner of our own, [`check`], that rejects
//! what tobj would reject or trip over, with the line number and text, and
//! also non-finite coordinates, which tobj accepts. Face indices must refer
//! to vertices defined earlier in the file, as the OBJ format says.
//!
//! Materials come from the MTL files named by `mtllib`, relative to the OBJ
//! file: `Ka`, `Kd`, `Ks`, `Ke` (emission), `Ns`, `d` (opacity) or else `Tr` (opacity =
//! 1 − Tr), sanitized to their valid ranges. A missing `Ka` is taken equal
//! to `Kd`; other missing keys take [`Material::DEFAULT`]'s values. A
//! missing or broken MTL file, or an unknown `usemtl` name, is not an error:
//! the meshes get [`Material::DEFAULT`] and a warning is reported —
//! returned by [`load_obj_with_warnings`], printed to stderr by
//! [`load_obj`].
//!
//! Textures (SPEC §7): texture coordinates come from `vt` (OBJ's t already
//! runs up, as the spec wants) and are kept when every vertex of the mesh
//! has one. `map_Kd` names the diffuse texture, a PNG or JPEG file relative
//! to the MTL file, read with the default sampler (trilinear, repeat) or
//! clamp-to-edge with `-clamp on`; other `map_Kd` options are ignored with
//! a warning. Each image file is decoded once per load and shared. The
//! fallbacks, each with a warning: a texture file that is missing or
//! unreadable, or in a format other than PNG and JPEG, and a mesh with a
//! `map_Kd` but no texture coordinates, are drawn untextured with the
//! material's Kd. A PNG or JPEG that does not decode is an error naming the
//! model, the material and the image file.
//!
//! Bump maps: `bump` or `map_bump` (tobj's `normal_texture`) names a height
//! map (the red channel), `-bm mult` its scale k (default 1; see
//! `zline_scene::NormalMap` for the formula); a mesh with one gets
//! MikkTSpace tangents. Drawn with Phong shading only; the same fallbacks
//! as `map_Kd`, each with a warning. The map statements and their options
//! are read, and the maps attached to meshes, in `maps`.
//!
//! MTL values (see `mtl`): a non-finite `Ka`, `Kd`, `Ks`, `Ke`, `Ns`, `d`
//! or `Tr` is an error naming the MTL file, line and key; a finite value
//! outside its range is clamped with a warning.
//!
//! Vertex colours (`v x y z r g b`) are read by tobj but not drawn. When
//! only some vertices carry one, tobj fails (`FaceColorOutOfBounds`); the
//! file is then read again with the colours left out, with a warning.
//!
//! Limits and confinement (see `files`): the OBJ file is read when at most
//! [`MAX_MODEL_FILE_BYTES`](zline_scene::MAX_MODEL_FILE_BYTES), an MTL file
//! at most [`MAX_TEXT_FILE_BYTES`](zline_scene::MAX_TEXT_FILE_BYTES); an
//! `mtllib` must lie in the OBJ file's folder and a `map_Kd` in the MTL
//! file's folder, unless [`LoadOptions::allow_outside`]; a refused path is
//! an error naming the file that names it. At most
//! [`MAX_MATERIAL_LIBRARIES`] `mtllib` statements are read. The model may
//! have at most
//! [`MAX_TRIANGLES`](zline_scene::MAX_TRIANGLES) triangles and
//! [`MAX_VERTICES`](zline_scene::MAX_VERTICES) vertices.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use zline_scene::{Mesh, MAX_MATERIAL_LIBRARIES};
use zline_shading::Material;

use crate::error::SceneError;
use crate::files::{read_text, resolve, FileKind, LoadOptions};
use crate::texture_file::TextureCache;
use check::check_obj_text;
use maps::{attach_bump_map, attach_diffuse_map, ObjMaterial};
use mtl::load_mtl;

mod check;
mod maps;
mod mtl;
mod read;

/// Loads an OBJ file, printing warnings (such as a missing MTL file) to
/// stderr as `warning: ...` lines.
pub fn load_obj(path: &Path) -> Result<Vec<Mesh>, SceneError> {
    let (meshes, warnings) = load_obj_with_warnings(path)?;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    Ok(meshes)
}

/// Loads an OBJ file and returns the meshes with the warnings, each a
/// one-line message starting with the file it is about.
pub fn load_obj_with_warnings(path: &Path) -> Result<(Vec<Mesh>, Vec<String>), SceneError> {
    load_obj_with_options(path, LoadOptions::default())
}

/// [`load_obj_with_warnings`] with options (files outside the model's
/// folder).
pub fn load_obj_with_options(
    path: &Path,
    options: LoadOptions,
) -> Result<(Vec<Mesh>, Vec<String>), SceneError> {
    let text = read_text(path, FileKind::Model).map_err(|e| e.into_error(path))?;
    parse_obj(path, &text, options)
}

/// Loads OBJ text read from `path` (which names the file in messages and
/// locates MTL files).
pub(crate) fn parse_obj(
    path: &Path,
    text: &str,
    options: LoadOptions,
) -> Result<(Vec<Mesh>, Vec<String>), SceneError> {
    let (pieces, before) = check_obj_text(path, text)?;
    let warnings = RefCell::new(Vec::new());
    // The MTL file each material came from, in the order libraries are
    // read (their materials are appended as each `mtllib` comes).
    let material_files = RefCell::new(Vec::new());
    // The first MTL failure that must stop the load (tobj's callback can
    // only say "no materials").
    let failure = RefCell::new(None);
    let mut libraries = 0;
    // Libraries read without error, even those that define no material.
    let libraries_read = std::cell::Cell::new(0);
    let loaded = read::read_models(&pieces, &before, |mtl| {
        libraries += 1;
        let loaded = if libraries > MAX_MATERIAL_LIBRARIES {
            let message = format!("more than {MAX_MATERIAL_LIBRARIES} material libraries (mtllib)");
            Err(SceneError::File { path: path.to_path_buf(), message })
        } else {
            resolve(path, mtl, options)
                .map_err(|why| SceneError::File {
                    path: path.to_path_buf(),
                    message: format!("mtllib: {why}"),
                })
                .and_then(|mtl_path| {
                    let result = load_mtl(&mtl_path, &mut warnings.borrow_mut())?;
                    if let Ok((materials, _)) = &result {
                        libraries_read.set(libraries_read.get() + 1);
                        material_files.borrow_mut().extend(std::iter::repeat_n(mtl_path, materials.len()));
                    }
                    Ok(result)
                })
        };
        loaded.unwrap_or_else(|e| {
            failure.borrow_mut().get_or_insert(e);
            Err(tobj::LoadError::OpenFileFailed)
        })
    });
    if let Some(e) = failure.into_inner() {
        return Err(e);
    }
    let (models, materials) = match loaded {
        Err(tobj::LoadError::FaceColorOutOfBounds) => return parse_obj_without_colors(path, text, options),
        loaded => loaded.map_err(|e| SceneError::File {
            path: path.to_path_buf(),
            message: format!("cannot load OBJ: {e}"),
        })?,
    };
    check_size(path, &models)?;
    let mut warnings = warnings.into_inner();
    let material_files = material_files.into_inner();
    let materials = materials
        .unwrap_or_default()
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let mtl = material_files.get(i).map_or(path, PathBuf::as_path);
            ObjMaterial::from_mtl(m, mtl, options, &mut warnings)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let meshes = meshes_from_models(path, models, &materials, libraries_read.get() > 0, &mut warnings)?;
    Ok((meshes, warnings))
}

/// The text read again with the vertex colours left out, when only some
/// vertices have one (see the module doc). Lines keep their numbers.
fn parse_obj_without_colors(
    path: &Path,
    text: &str,
    options: LoadOptions,
) -> Result<(Vec<Mesh>, Vec<String>), SceneError> {
    let mut plain = String::with_capacity(text.len());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        match (words.next(), words.clone().count()) {
            (Some("v"), 6) => {
                plain.push_str("v ");
                plain.push_str(&words.take(3).collect::<Vec<_>>().join(" "));
            }
            _ => plain.push_str(line),
        }
        plain.push('\n');
    }
    let (meshes, mut warnings) = parse_obj(path, &plain, options)?;
    warnings.insert(
        0,
        format!(
            "{}: only some vertices have a colour (v x y z r g b); vertex colours are not drawn and were left out",
            path.display()
        ),
    );
    Ok((meshes, warnings))
}

/// Refuses a model over the triangle or vertex limit.
fn check_size(path: &Path, models: &[tobj::Model]) -> Result<(), SceneError> {
    let triangles: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
    let vertices: usize = models.iter().map(|m| m.mesh.positions.len() / 3).sum();
    SceneError::check_size(path, triangles, vertices)
}

fn meshes_from_models(
    path: &Path,
    models: Vec<tobj::Model>,
    materials: &[ObjMaterial],
    any_library: bool,
    warnings: &mut Vec<String>,
) -> Result<Vec<Mesh>, SceneError> {
    let stem = path.file_stem().map_or_else(|| "model".to_owned(), |s| s.to_string_lossy().into_owned());
    let mut textures = TextureCache::default();
    let mut meshes = Vec::with_capacity(models.len());
    for model in models.into_iter().filter(|m| m.mesh.indices.len() >= 3) {
        let name = if model.name.is_empty() { stem.clone() } else { model.name };
        let material = match model.mesh.material_id {
            Some(id) => materials.get(id),
            None => {
                // A library was read (perhaps without materials): the
                // mesh's `usemtl` names none of them, or it has none.
                if any_library || !materials.is_empty() {
                    warnings.push(format!("{}: mesh '{name}' has no known material", path.display()));
                }
                None
            }
        };
        let mesh =
            mesh_from_tobj(path, name, model.mesh, material.map_or(Material::DEFAULT, |m| m.material))?;
        let mesh = attach_diffuse_map(path, mesh, material, &mut textures, warnings)?;
        meshes.push(attach_bump_map(path, mesh, material, &mut textures, warnings)?);
    }
    if meshes.is_empty() {
        return Err(SceneError::NoTriangles { path: path.to_path_buf() });
    }
    Ok(meshes)
}

fn mesh_from_tobj(path: &Path, name: String, m: tobj::Mesh, material: Material) -> Result<Mesh, SceneError> {
    let vec3s = |v: &[f32]| v.chunks_exact(3).map(Vec3::from_slice).collect::<Vec<_>>();
    let positions = vec3s(&m.positions);
    // tobj leaves normals and texture coordinates out for vertices whose
    // face gave none; use the file's only when every vertex has one.
    let normals = (m.normals.len() == m.positions.len()).then(|| vec3s(&m.normals));
    let has_uvs = !m.texcoords.is_empty() && m.texcoords.len() / 2 == positions.len();
    let uvs: Vec<Vec2> =
        if has_uvs { m.texcoords.chunks_exact(2).map(Vec2::from_slice).collect() } else { Vec::new() };
    let triangles = m.indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    let mesh_error = |source| SceneError::Mesh { path: path.to_path_buf(), mesh: name.clone(), source };
    let mesh = Mesh::new(name.clone(), positions, normals, triangles, material).map_err(mesh_error)?;
    if uvs.is_empty() {
        return Ok(mesh);
    }
    mesh.with_uvs(uvs).map_err(mesh_error)
}

#[cfg(test)]
mod tests {
    use std::io::Cursor;

    use super::check::{check_obj_text_in, CHECK_PIECE};
    use super::maps::material_from_mtl;
    use super::*;

    #[test]
    fn mtl_values_map_to_the_material() {
        let mut m =
            tobj::Material { diffuse: Some([0.2, 0.4, 0.6]), shininess: Some(64.0), ..Default::default() };
        m.unknown_param.insert("Tr".into(), "0.25".into());
        let mat = material_from_mtl(&m);
        assert_eq!(mat.ka, Vec3::new(0.2, 0.4, 0.6));
        assert_eq!(mat.kd, Vec3::new(0.2, 0.4, 0.6));
        assert_eq!(mat.ks, Material::DEFAULT.ks);
        assert_eq!(mat.ns, 64.0);
        assert_eq!(mat.opacity, 0.75);
        assert_eq!(mat.ke, Vec3::ZERO, "no Ke, no emission");
        m.dissolve = Some(0.5);
        m.specular = Some([2.0, f32::NAN, 0.5]);
        m.emissive = Some([0.1, 3.0, -1.0]);
        let mat = material_from_mtl(&m);
        assert_eq!(mat.opacity, 0.5, "d wins over Tr");
        assert_eq!(mat.ks, Vec3::new(1.0, 0.0, 0.5), "sanitized");
        assert_eq!(mat.ke, Vec3::new(0.1, 1.0, 0.0), "Ke, sanitized");
    }

    /// The ray tracer's coefficients (SPEC §12): `Ni` is the index of
    /// refraction; `Ks` is the mirror coefficient under `illum` 3–7 only.
    #[test]
    fn illum_and_ni_give_the_mirror_and_the_index_of_refraction() {
        let mut m = tobj::Material { specular: Some([0.5, 0.6, 0.7]), ..Default::default() };
        assert_eq!((material_from_mtl(&m).kr, material_from_mtl(&m).ior), (Vec3::ZERO, 1.0));
        for (illum, mirror) in [(2, false), (3, true), (4, true), (7, true), (8, false)] {
            m.illumination_model = Some(illum);
            let want = if mirror { Vec3::new(0.5, 0.6, 0.7) } else { Vec3::ZERO };
            assert_eq!(material_from_mtl(&m).kr, want, "illum {illum}");
        }
        m.optical_density = Some(1.33);
        assert_eq!(material_from_mtl(&m).ior, 1.33);
        m.optical_density = Some(0.0);
        assert_eq!(material_from_mtl(&m).ior, 1.0, "an index of refraction of 0 is replaced by 1");
    }

    /// `Tf` gives d = 1 − its largest channel under the refracting `illum`
    /// modes, when neither `d` nor `Tr` is given.
    #[test]
    fn the_transmission_filter_gives_the_opacity_of_glass() {
        let mut m = tobj::Material::default();
        m.unknown_param.insert("Tf".into(), "0.2 0.9 0.5".into());
        for (illum, opacity) in [(None, 1.0), (Some(2), 1.0), (Some(4), 0.1), (Some(6), 0.1), (Some(7), 0.1)]
        {
            m.illumination_model = illum;
            assert!((material_from_mtl(&m).opacity - opacity).abs() < 1e-6, "illum {illum:?}");
        }
        m.unknown_param.insert("Tf".into(), "0.7".into());
        assert!((material_from_mtl(&m).opacity - 0.3).abs() < 1e-6, "one value: grey");
        m.unknown_param.insert("Tf".into(), "spectral glass.rfl".into());
        assert_eq!(material_from_mtl(&m).opacity, 1.0, "the spectral form is not read");
        m.unknown_param.insert("Tf".into(), "3 nan".into());
        assert_eq!(material_from_mtl(&m).opacity, 0.0, "clamped to [0, 1], NaN ignored");
        m.unknown_param.insert("Tf".into(), "0.2 0.9 0.5".into());
        m.dissolve = Some(0.6);
        assert_eq!(material_from_mtl(&m).opacity, 0.6, "d wins");
    }

    proptest::proptest! {
        #![proptest_config(proptest::test_runner::Config { cases: 512, ..Default::default() })]

        /// Whatever the text, loading returns, never panics: the scanner
        /// keeps from tobj what it would trip over.
        #[test]
        fn arbitrary_obj_text_never_panics(lines in proptest::collection::vec(obj_line(), 0..12)) {
            let text = lines.join("\n");
            if let Ok((meshes, _)) = parse_obj(Path::new("fuzz.obj"), &text, LoadOptions::default()) {
                for m in meshes {
                    proptest::prop_assert!(m.positions.iter().all(|p| p.is_finite()));
                    proptest::prop_assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
                }
            }
        }
    }

    /// The models and materials as tobj reads `text` (the definition
    /// `obj_read` must match), and as `obj_read` does with `piece`-byte
    /// pieces; `None` when the check rejects the text.
    fn both_readers(text: &str, dir: &Path, piece: usize) -> Option<(String, String)> {
        let (pieces, before) = check_obj_text_in(Path::new("t.obj"), text, piece).ok()?;
        let loader = |mtl: &Path| {
            load_mtl(&dir.join(mtl), &mut Vec::new()).unwrap_or(Err(tobj::LoadError::OpenFileFailed))
        };
        #[allow(clippy::needless_update, reason = "tobj's `merging`/`reordering` features add fields")]
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: true,
            ignore_points: true,
            ignore_lines: true,
            ..Default::default()
        };
        let theirs = tobj::load_obj_buf(&mut Cursor::new(text.as_bytes()), &options, loader);
        let ours = read::read_models(&pieces, &before, loader);
        Some((describe(theirs), describe(ours)))
    }

    /// Everything a load result holds, floats by their bits.
    fn describe(r: tobj::LoadResult) -> String {
        let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        match r {
            Err(e) => format!("error {e:?}"),
            Ok((models, materials)) => {
                let mut out = format!("materials {materials:?}\n");
                for m in models {
                    let x = &m.mesh;
                    out += &format!(
                        "model {:?} mat {:?}\n pos {:?}\n color {:?}\n normals {:?}\n uv {:?}\n idx {:?} {:?} {:?} {:?}\n",
                        m.name,
                        x.material_id,
                        bits(&x.positions),
                        bits(&x.vertex_color),
                        bits(&x.normals),
                        bits(&x.texcoords),
                        x.indices,
                        x.face_arities,
                        x.texcoord_indices,
                        x.normal_indices,
                    );
                }
                out
            }
        }
    }

    /// The shipped models read both ways, whole and in small pieces.
    #[test]
    fn parallel_reader_matches_tobj_on_the_assets() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/obj");
        let mut read = 0;
        for model in ["spot/spot.obj", "suzanne/suzanne.obj"] {
            let path = root.join(model);
            let text = read_text(&path, FileKind::Model).unwrap();
            for piece in [CHECK_PIECE, 4096, 100] {
                let (theirs, ours) = both_readers(&text, path.parent().unwrap(), piece).unwrap();
                assert!(theirs == ours, "{model}, pieces of {piece} bytes");
                read += 1;
            }
        }
        assert_eq!(read, 6);
    }

    proptest::proptest! {
        #![proptest_config(proptest::test_runner::Config { cases: 256, ..Default::default() })]

        /// Text that passes the check, in pieces of any size: the parallel
        /// reader gives tobj's models and materials, bit for bit.
        #[test]
        fn parallel_reader_matches_tobj(lines in proptest::collection::vec(valid_obj_line(), 0..40), piece in 1usize..200) {
            // Three of each attribute first, so that most faces are valid.
            let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nvn 0 1 0\nvn 1 0 0\n";
            let text = head.to_owned() + &lines.join("\n");
            let dir = materials_dir();
            let (theirs, ours) = both_readers(&text, &dir, piece).expect("the lines pass the check");
            proptest::prop_assert_eq!(theirs, ours);
        }

        /// The same on the troublesome lines of the panic test.
        #[test]
        fn parallel_reader_matches_tobj_on_odd_text(lines in proptest::collection::vec(obj_line(), 0..12), piece in 1usize..64) {
            let text = lines.join("\n");
            if let Some((theirs, ours)) = both_readers(&text, Path::new("/nonexistent"), piece) {
                proptest::prop_assert_eq!(theirs, ours);
            }
        }
    }

    /// A folder with `m.mtl`, defining materials `ax` and `bx`.
    fn materials_dir() -> PathBuf {
        let dir = std::env::temp_dir().join(format!("zline-obj-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("m.mtl"), "newmtl ax\nKd 1 0 0\nnewmtl bx\nKd 0 1 0\n").unwrap();
        dir
    }

    /// Lines that pass the check after three of each attribute: vertices (with w or colours),
    /// texture coordinates, normals, faces of 1–6 corners in every index
    /// form, objects, groups, materials, comments.
    fn valid_obj_line() -> impl proptest::strategy::Strategy<Value = String> {
        use proptest::prelude::*;
        let num = prop::sample::select(vec!["0", "1", "-2.5", "0.25", "3e2", "-0.0", "7"]);
        let nums =
            |n: std::ops::Range<usize>| prop::collection::vec(num.clone(), n).prop_map(|v| v.join(" "));
        let index = prop::sample::select(vec!["1", "2", "3", "-1", "-2"]);
        let corner = (index.clone(), prop::option::of(index.clone()), prop::option::of(index), 0..3u8)
            .prop_map(|(v, t, n, form)| match form {
                0 => v.to_owned(),
                1 => format!("{v}/{}", t.unwrap_or("1")),
                _ => format!("{v}/{}/{}", t.unwrap_or(""), n.unwrap_or("1")),
            });
        let face = prop::collection::vec(corner, 1..7).prop_map(|c| format!("f {}", c.join(" ")));
        let name = prop::sample::select(vec!["a", "b", "two words", " "]);
        prop_oneof![
            4 => nums(3..4).prop_map(|n| format!("v {n}")),
            1 => nums(3..4).prop_map(|n| format!("v {n} 2")),
            1 => nums(6..7).prop_map(|n| format!("v {n}")),
            2 => nums(2..3).prop_map(|n| format!("vt {n}")),
            2 => nums(3..4).prop_map(|n| format!("vn {n}")),
            6 => face,
            1 => name.clone().prop_map(|n| format!("o {n}")),
            1 => name.clone().prop_map(|n| format!("g {n}")),
            1 => name.prop_map(|n| format!("usemtl {n}x")),
            1 => prop::sample::select(vec!["mtllib m.mtl", "mtllib missing.mtl"]).prop_map(str::to_owned),
            1 => Just("# comment".to_owned()),
            1 => Just(String::new()),
        ]
    }

    /// OBJ-like lines built from keywords and troublesome tokens.
    fn obj_line() -> impl proptest::strategy::Strategy<Value = String> {
        use proptest::prelude::*;
        let key = prop::sample::select(vec![
            "v", "vt", "vn", "f", "l", "p", "g", "o", "usemtl", "mtllib", "s", "x", "",
        ]);
        let index =
            prop::sample::select(vec!["1", "2", "3", "-1", "-4", "0", "7", "99999999999999999999", "a", ""]);
        let corner = prop::collection::vec(index, 1..4).prop_map(|parts| parts.join("/"));
        let number =
            prop::sample::select(vec!["0", "1", "-2.5", "1e30", "1e39", "nan", "inf", "0.0", "x", "1e-40"])
                .prop_map(str::to_owned);
        let token = prop_oneof![corner, number];
        (key, prop::collection::vec(token, 0..7)).prop_map(|(k, t)| format!("{k} {}", t.join(" ")))
    }
}

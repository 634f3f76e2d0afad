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
//! image file.

use std::cell::RefCell;
use std::io::Cursor;
use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use zline_scene::{Mesh, TextureMap};
use zline_shading::{Material, Sampler, Wrap};

use crate::error::SceneError;
use crate::texture_file::TextureCache;
use check::{check_obj_text, quote, truncate};

mod check;
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
    parse_obj(path, &read_text(path)?)
}

/// Loads OBJ text read from `path` (which names the file in messages and
/// locates MTL files).
fn parse_obj(path: &Path, text: &str) -> Result<(Vec<Mesh>, Vec<String>), SceneError> {
    let (pieces, before) = check_obj_text(path, text)?;
    let warnings = RefCell::new(Vec::new());
    // The MTL file each material came from, in the order libraries are
    // read (their materials are appended as each `mtllib` comes).
    let material_files = RefCell::new(Vec::new());
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let loaded = read::read_models(&pieces, &before, |mtl| {
        let mtl_path = dir.join(mtl);
        let result = load_mtl(&mtl_path, &mut warnings.borrow_mut());
        if let Ok((materials, _)) = &result {
            material_files.borrow_mut().extend(std::iter::repeat_n(mtl_path, materials.len()));
        }
        result
    });
    let (models, materials) = loaded.map_err(|e| SceneError::File {
        path: path.to_path_buf(),
        message: format!("cannot load OBJ: {e}"),
    })?;
    let mut warnings = warnings.into_inner();
    let material_files = material_files.into_inner();
    let materials: Vec<ObjMaterial> = materials
        .unwrap_or_default()
        .iter()
        .enumerate()
        .map(|(i, m)| {
            ObjMaterial::from_mtl(m, material_files.get(i).unwrap_or(&path.to_path_buf()), &mut warnings)
        })
        .collect();
    let meshes = meshes_from_models(path, models, &materials, &mut warnings)?;
    Ok((meshes, warnings))
}

/// An MTL material: the lighting coefficients and the diffuse map's file,
/// read when a mesh uses it.
struct ObjMaterial {
    material: Material,
    diffuse_map: Option<MapStatement>,
}

impl ObjMaterial {
    /// `mtl` is the MTL file the material came from: texture files are
    /// relative to it.
    fn from_mtl(m: &tobj::Material, mtl: &Path, warnings: &mut Vec<String>) -> ObjMaterial {
        let diffuse_map = m.diffuse_texture.as_deref().and_then(|value| {
            let map = parse_map_statement(value, mtl, warnings, &m.name);
            if map.is_none() {
                warnings.push(format!(
                    "{}: material '{}': map_Kd {} names no file; drawn untextured",
                    mtl.display(),
                    m.name,
                    quote(value)
                ));
            }
            map
        });
        ObjMaterial { material: material_from_mtl(m), diffuse_map }
    }
}

/// A texture statement of an MTL file (`map_Kd [options] file`): the file,
/// relative to the MTL file, and the sampler its options ask for.
#[derive(Debug, PartialEq)]
struct MapStatement {
    file: PathBuf,
    sampler: Sampler,
}

/// Parses `[options] file` of a `map_Kd` statement. `-clamp on` selects
/// clamp-to-edge; every other option (`-o`, `-s`, `-t`, `-mm`, `-bm`,
/// `-blendu`, …) is skipped with its arguments and a warning. The rest of
/// the line, spaces included, is the file name; `None` when it is empty.
/// `mtl` is the MTL file, for messages and as the base of the file name.
fn parse_map_statement(
    value: &str,
    mtl: &Path,
    warnings: &mut Vec<String>,
    material: &str,
) -> Option<MapStatement> {
    let mut sampler = Sampler::default();
    let mut rest = value.trim();
    while rest.starts_with('-') {
        let option;
        (option, rest) = next_word(rest);
        let arity = match option {
            "-o" | "-s" | "-t" => 3,
            "-mm" => 2,
            _ => 1,
        };
        let mut args = Vec::new();
        while args.len() < arity && !rest.is_empty() {
            let (word, after) = next_word(rest);
            // Numeric options take 1 to `arity` numbers; others one word.
            if arity > 1 && word.parse::<f32>().is_err() {
                break;
            }
            args.push(word);
            rest = after;
        }
        if option == "-clamp" && args.len() == 1 {
            let wrap = if args[0] == "on" { Wrap::ClampToEdge } else { Wrap::Repeat };
            sampler.wrap_s = wrap;
            sampler.wrap_t = wrap;
        } else {
            warnings.push(format!(
                "{}: material '{material}': map_Kd option '{} {}' is not supported; ignored",
                mtl.display(),
                truncate(option),
                truncate(&args.join(" "))
            ));
        }
    }
    // MTL files written on Windows use `\` as the separator (`.\tex.jpg`);
    // a backslash is never part of a portable file name, so read it as `/`.
    let file = rest.replace('\\', "/");
    let dir = mtl.parent().unwrap_or(Path::new(""));
    (!file.is_empty()).then(|| MapStatement { file: dir.join(&file), sampler })
}

/// The first word of a trimmed string and the trimmed rest.
fn next_word(s: &str) -> (&str, &str) {
    let end = s.find(char::is_whitespace).unwrap_or(s.len());
    (&s[..end], s[end..].trim_start())
}

/// Reads a text file; bytes that are not UTF-8 (Latin-1 comments, say)
/// become U+FFFD rather than an error.
pub(crate) fn read_text(path: &Path) -> Result<String, SceneError> {
    let bytes = std::fs::read(path).map_err(|source| SceneError::Io { path: path.to_path_buf(), source })?;
    // Valid UTF-8 (nearly every file) is taken as it is, without a copy.
    Ok(String::from_utf8(bytes).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned()))
}

fn meshes_from_models(
    path: &Path,
    models: Vec<tobj::Model>,
    materials: &[ObjMaterial],
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
                if !materials.is_empty() {
                    warnings.push(format!("{}: mesh '{name}' has no known material", path.display()));
                }
                None
            }
        };
        let mesh =
            mesh_from_tobj(path, name, model.mesh, material.map_or(Material::DEFAULT, |m| m.material))?;
        let map = material.and_then(|m| m.diffuse_map.as_ref());
        meshes.push(attach_diffuse_map(path, mesh, map, &mut textures, warnings)?);
    }
    if meshes.is_empty() {
        return Err(SceneError::NoTriangles { path: path.to_path_buf() });
    }
    Ok(meshes)
}

/// The mesh with its material's diffuse map, when it has one, the mesh
/// has texture coordinates and the image can be read (see the module doc
/// for the fallbacks).
fn attach_diffuse_map(
    path: &Path,
    mesh: Mesh,
    map: Option<&MapStatement>,
    textures: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> Result<Mesh, SceneError> {
    let Some(map) = map else { return Ok(mesh) };
    if mesh.uvs.is_empty() {
        warnings.push(format!(
            "{}: mesh '{}' has a diffuse map but no texture coordinates (vt); drawn untextured",
            path.display(),
            mesh.name
        ));
        return Ok(mesh);
    }
    Ok(match textures.file(&map.file, warnings)? {
        Some(texture) => mesh.with_diffuse_map(TextureMap {
            texture,
            sampler: map.sampler,
            alpha_blend: false,
            alpha_cutoff: None,
        }),
        None => mesh,
    })
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

/// Converts a tobj material (see the module doc for the defaults).
fn material_from_mtl(m: &tobj::Material) -> Material {
    let d = Material::DEFAULT;
    let kd = m.diffuse.map_or(d.kd, Vec3::from);
    let tr = m.unknown_param.get("Tr").and_then(|v| v.split_whitespace().next()?.parse::<f32>().ok());
    let opacity = m.dissolve.or(tr.map(|t| 1.0 - t)).unwrap_or(1.0);
    Material {
        ke: m.emissive.map_or(d.ke, Vec3::from),
        ka: m.ambient.map_or(kd, Vec3::from),
        kd,
        ks: m.specular.map_or(d.ks, Vec3::from),
        ns: m.shininess.unwrap_or(d.ns),
        opacity,
    }
    .sanitized()
}

/// The material loader handed to tobj: reads and checks an MTL file,
/// turning every failure into a warning (tobj then uses no material).
fn load_mtl(path: &Path, warnings: &mut Vec<String>) -> tobj::MTLLoadResult {
    let fail = |warnings: &mut Vec<String>, why: String| {
        warnings.push(format!("{why}; using the default material"));
        Err(tobj::LoadError::OpenFileFailed)
    };
    let text = match std::fs::read(path) {
        Ok(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
        Err(e) => return fail(warnings, format!("{}: cannot read material library: {e}", path.display())),
    };
    let text = match check_mtl_text(&text) {
        Ok(text) => text,
        Err((line, why)) => return fail(warnings, format!("{}: line {line}: {why}", path.display())),
    };
    tobj::load_mtl_buf(&mut Cursor::new(text.as_bytes()))
        .or_else(|e| fail(warnings, format!("{}: cannot load material library: {e}", path.display())))
}

/// Checks the MTL statements that tobj would reject without saying where,
/// or panic on, and expands the one-number colour form `Kd 0.5` (which
/// means `Kd 0.5 0.5 0.5`) that tobj does not know. Returns the text to
/// hand to tobj, or the 1-based line and what is wrong with it.
fn check_mtl_text(text: &str) -> Result<String, (usize, String)> {
    let mut out = String::with_capacity(text.len() + 64);
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        let args: Vec<&str> = words.collect();
        let bad = |what: &str| Err((i + 1, format!("{what} in {}", quote(line))));
        match key {
            "Ka" | "Kd" | "Ks" | "Ke" => match args.len() {
                1 => {
                    let v = args[0];
                    if v.parse::<f32>().is_err() {
                        return bad("cannot parse colour");
                    }
                    out.push_str(&format!("{key} {v} {v} {v}\n"));
                    continue;
                }
                0 | 2 => return bad("a colour needs 3 numbers"),
                _ if args[..3].iter().any(|a| a.parse::<f32>().is_err()) => {
                    return bad("cannot parse colour (only 'r g b' is supported)")
                }
                _ => {}
            },
            "Ns" | "Ni" | "d" if args.first().and_then(|a| a.parse::<f32>().ok()).is_none() => {
                return bad("cannot parse number")
            }
            "illum" if args.first().and_then(|a| a.parse::<u8>().ok()).is_none() => {
                return bad("cannot parse illumination model")
            }
            "newmtl" if args.is_empty() => return bad("material without a name"),
            k if (k.starts_with("map_") || k == "bump") && args.is_empty() => {
                return bad("texture map without a file name")
            }
            _ => {}
        }
        out.push_str(line);
        out.push('\n');
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::check::{check_obj_text_in, CHECK_PIECE};
    use super::*;

    #[test]
    fn mtl_one_number_colours_are_expanded_and_two_rejected() {
        let text = check_mtl_text("newmtl a\nKd 0.5\nKs 1 1 1\n").unwrap();
        assert_eq!(text, "newmtl a\nKd 0.5 0.5 0.5\nKs 1 1 1\n");
        assert_eq!(check_mtl_text("newmtl a\n\nKd 0.5 0.5\n").unwrap_err().0, 3);
        assert!(check_mtl_text("Ns high").unwrap_err().1.contains("cannot parse number in 'Ns high'"));
        assert!(check_mtl_text("Kd spectral x.rfl").is_err());
    }

    #[test]
    fn map_statements_keep_spaces_in_file_names_and_read_clamp() {
        let mut warnings = Vec::new();
        let mtl = Path::new("models/a.mtl");
        let map = parse_map_statement("-clamp on -mm 0 1 my  texture.png", mtl, &mut warnings, "m").unwrap();
        assert_eq!(map.file, Path::new("models/my  texture.png"), "the name as written");
        assert_eq!(map.sampler.wrap_s, Wrap::ClampToEdge);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(warnings[0].contains("models/a.mtl: material 'm': map_Kd option '-mm 0 1'"), "{warnings:?}");
        let map = parse_map_statement("-clamp off t.jpg", mtl, &mut warnings, "m").unwrap();
        assert_eq!(map, MapStatement { file: "models/t.jpg".into(), sampler: Sampler::default() });
        assert_eq!(parse_map_statement("-blendu on", mtl, &mut warnings, "m"), None);
        let windows = parse_map_statement(".\\textures\\Spider Tex.jpg", mtl, &mut warnings, "m").unwrap();
        assert_eq!(windows.file, Path::new("models/textures/Spider Tex.jpg"), "backslashes are separators");
    }

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

    proptest::proptest! {
        #![proptest_config(proptest::test_runner::Config { cases: 512, ..Default::default() })]

        /// Whatever the text, loading returns, never panics: the scanner
        /// keeps from tobj what it would trip over.
        #[test]
        fn arbitrary_obj_text_never_panics(lines in proptest::collection::vec(obj_line(), 0..12)) {
            let text = lines.join("\n");
            if let Ok((meshes, _)) = parse_obj(Path::new("fuzz.obj"), &text) {
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
        let loader = |mtl: &Path| load_mtl(&dir.join(mtl), &mut Vec::new());
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
            let text = read_text(&path).unwrap();
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

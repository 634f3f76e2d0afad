//! MTL materials as the OBJ loader uses them: the statements of a
//! material's texture maps (`map_Kd`, `bump`, `norm` and their options) and
//! attaching the diffuse and bump maps to a mesh.

use std::path::{Path, PathBuf};

use glam::Vec3;
use zline_scene::{Mesh, NormalEncoding, NormalMap, TextureMap};
use zline_shading::{Distribution, Material, Microfacet, Model, Sampler, Wrap};

use crate::error::SceneError;
use crate::files::{resolve, LoadOptions};
use crate::texture_file::TextureCache;

use super::check::{quote, truncate};

/// An MTL material: the lighting coefficients and the diffuse map's file,
/// read when a mesh uses it.
pub(super) struct ObjMaterial {
    pub(super) name: String,
    pub(super) material: Material,
    pub(super) diffuse_map: Option<MapStatement>,
    /// `bump`/`map_bump`: a height map ([`attach_bump_map`]).
    pub(super) bump_map: Option<MapStatement>,
}

impl ObjMaterial {
    /// `mtl` is the MTL file the material came from: texture files are
    /// relative to it, and must lie in its folder unless the options allow
    /// otherwise (an error naming the MTL file).
    pub(super) fn from_mtl(
        m: &tobj::Material,
        mtl: &Path,
        options: LoadOptions,
        warnings: &mut Vec<String>,
    ) -> Result<ObjMaterial, SceneError> {
        let mut diffuse_map = None;
        if let Some(value) = m.diffuse_texture.as_deref() {
            match parse_map_statement(value, mtl, warnings, &m.name) {
                Some(map) => {
                    let file = resolve(mtl, &map.file, options).map_err(|why| SceneError::File {
                        path: mtl.to_path_buf(),
                        message: format!("material '{}': map_Kd: {why}", m.name),
                    })?;
                    diffuse_map = Some(MapStatement { file, ..map });
                }
                None => warnings.push(format!(
                    "{}: material '{}': map_Kd {} names no file; drawn untextured",
                    mtl.display(),
                    m.name,
                    quote(value)
                )),
            }
        }
        let bump_map = bump_statement(m, mtl, options, warnings)?;
        Ok(ObjMaterial { name: m.name.clone(), material: material_from_mtl(m), diffuse_map, bump_map })
    }
}

/// A texture statement of an MTL file (`map_Kd [options] file`): the file
/// (as written, then resolved against the MTL file's folder) and the
/// sampler its options ask for.
#[derive(Debug, PartialEq)]
pub(super) struct MapStatement {
    file: PathBuf,
    sampler: Sampler,
    /// `-bm mult`, the bump multiplier (bump maps only).
    bump_multiplier: Option<f32>,
}

/// Parses `[options] file` of a `map_Kd` or `bump` statement. `-clamp on`
/// selects clamp-to-edge, `-bm mult` sets the bump multiplier (used by
/// bump maps only); every other option (`-o`, `-s`, `-t`, `-mm`, `-bm`,
/// `-blendu`, …) is skipped with its arguments and a warning. The rest of
/// the line, spaces included, is the file name; `None` when it is empty.
/// `mtl` is the MTL file, for messages.
pub(super) fn parse_map_statement(
    value: &str,
    mtl: &Path,
    warnings: &mut Vec<String>,
    material: &str,
) -> Option<MapStatement> {
    let mut sampler = Sampler::default();
    let mut bump_multiplier = None;
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
        } else if let ("-bm", [Ok(mult)]) =
            (option, args.iter().map(|a| a.parse::<f32>()).collect::<Vec<_>>().as_slice())
        {
            bump_multiplier = Some(*mult);
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
    (!file.is_empty()).then(|| MapStatement { file: file.into(), sampler, bump_multiplier })
}

/// The first word of a trimmed string and the trimmed rest.
pub(super) fn next_word(s: &str) -> (&str, &str) {
    let end = s.find(char::is_whitespace).unwrap_or(s.len());
    (&s[..end], s[end..].trim_start())
}

/// The mesh with its material's diffuse map, when it has one, the mesh
/// has texture coordinates and the image can be read (see the module doc
/// for the fallbacks).
pub(super) fn attach_diffuse_map(
    path: &Path,
    mesh: Mesh,
    material: Option<&ObjMaterial>,
    textures: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> Result<Mesh, SceneError> {
    let Some((map, name)) = material.and_then(|m| Some((m.diffuse_map.as_ref()?, &m.name))) else {
        return Ok(mesh);
    };
    if mesh.uvs.is_empty() {
        warnings.push(format!(
            "{}: mesh '{}' has a diffuse map but no texture coordinates (vt); drawn untextured",
            path.display(),
            mesh.name
        ));
        return Ok(mesh);
    }
    let mut texture_warnings = Vec::new();
    let texture = textures.file(&map.file, &mut texture_warnings).map_err(|e| SceneError::Texture {
        model: path.to_path_buf(),
        material: name.clone(),
        source: Box::new(e),
    })?;
    // A texture that cannot be used is named with the model and the
    // material that use it, like a texture error.
    warnings
        .extend(texture_warnings.into_iter().map(|w| format!("{}: material '{name}': {w}", path.display())));
    Ok(match texture {
        Some(texture) => mesh.with_diffuse_map(TextureMap {
            texture,
            sampler: map.sampler,
            alpha_blend: false,
            alpha_cutoff: None,
        }),
        None => mesh,
    })
}

/// The `bump`/`map_bump` statement of an MTL material (tobj's
/// `normal_texture`), its file resolved like `map_Kd`'s.
pub(super) fn bump_statement(
    m: &tobj::Material,
    mtl: &Path,
    options: LoadOptions,
    warnings: &mut Vec<String>,
) -> Result<Option<MapStatement>, SceneError> {
    let Some(value) = m.normal_texture.as_deref() else {
        return Ok(None);
    };
    let Some(map) = parse_map_statement(value, mtl, warnings, &m.name) else {
        let (path, name) = (mtl.display(), &m.name);
        warnings.push(format!("{path}: material '{name}': bump {} names no file; ignored", quote(value)));
        return Ok(None);
    };
    let file = resolve(mtl, &map.file, options).map_err(|why| SceneError::File {
        path: mtl.to_path_buf(),
        message: format!("material '{}': bump: {why}", m.name),
    })?;
    Ok(Some(MapStatement { file, ..map }))
}

/// The mesh with its material's bump map (`bump`/`map_bump`, a height in
/// the red channel; `-bm mult` is the scale k, default 1: see
/// `zline_scene::NormalMap`), with MikkTSpace tangents, when it has texture
/// coordinates and the image can be read; otherwise the mesh as it was,
/// with a warning.
pub(super) fn attach_bump_map(
    path: &Path,
    mesh: Mesh,
    material: Option<&ObjMaterial>,
    textures: &mut TextureCache,
    warnings: &mut Vec<String>,
) -> Result<Mesh, SceneError> {
    let Some((map, name)) = material.and_then(|m| Some((m.bump_map.as_ref()?, &m.name))) else {
        return Ok(mesh);
    };
    let mesh_name = mesh.name.clone();
    let without =
        |why: &str| format!("{}: mesh '{mesh_name}' {why}; drawn without its bump map", path.display());
    if mesh.uvs.is_empty() {
        warnings.push(without("has a bump map but no texture coordinates (vt)"));
        return Ok(mesh);
    }
    let scale = map.bump_multiplier.unwrap_or(1.0);
    if !scale.is_finite() {
        warnings.push(without(&format!("has a non-finite bump multiplier -bm {scale}")));
        return Ok(mesh);
    }
    let mut texture_warnings = Vec::new();
    let texture = textures.file(&map.file, &mut texture_warnings).map_err(|e| SceneError::Texture {
        model: path.to_path_buf(),
        material: name.clone(),
        source: Box::new(e),
    })?;
    warnings
        .extend(texture_warnings.into_iter().map(|w| format!("{}: material '{name}': {w}", path.display())));
    let Some(texture) = texture else {
        return Ok(mesh);
    };
    let mesh = mesh.with_generated_tangents();
    if mesh.tangents.is_empty() {
        warnings.push(without("has texture coordinates MikkTSpace cannot make tangents from"));
        return Ok(mesh);
    }
    let map = TextureMap { texture, sampler: map.sampler, alpha_blend: false, alpha_cutoff: None };
    Ok(mesh.with_normal_map(NormalMap { map, encoding: NormalEncoding::Height, scale }))
}

/// Converts a tobj material (see the module doc for the defaults).
pub(super) fn material_from_mtl(m: &tobj::Material) -> Material {
    let d = Material::DEFAULT;
    let kd = m.diffuse.map_or(d.kd, Vec3::from);
    let tr = m.unknown_param.get("Tr").and_then(|v| v.split_whitespace().next()?.parse::<f32>().ok());
    let opacity = m.dissolve.or(tr.map(|t| 1.0 - t)).or_else(|| filter(m).map(|t| 1.0 - t)).unwrap_or(1.0);
    Material {
        ke: m.emissive.map_or(d.ke, Vec3::from),
        ka: m.ambient.map_or(kd, Vec3::from),
        kd,
        ks: m.specular.map_or(d.ks, Vec3::from),
        ns: m.shininess.unwrap_or(d.ns),
        opacity,
        model: pbr_model(m),
        kr: mirror(m),
        ior: m.optical_density.unwrap_or(d.ior),
    }
    .sanitized()
}

/// The mirror coefficient kr of the Whitted model: `Ks` for the `illum`
/// modes with ray-traced reflection (3 reflection, 4 glass, 5 Fresnel
/// reflection, 6 refraction, 7 Fresnel refraction), else 0.
fn mirror(m: &tobj::Material) -> Vec3 {
    match m.illumination_model {
        Some(3..=7) => m.specular.map_or(Material::DEFAULT.ks, Vec3::from),
        _ => Vec3::ZERO,
    }
}

/// The share of light `Tf` (the transmission filter) passes under the
/// `illum` modes with refraction (4 glass, 6 refraction, 7 Fresnel
/// refraction): its largest channel, in [0, 1], so that d = 1 − it when
/// the material gives neither `d` nor `Tr`. `Tf r`, `Tf r g b`; the
/// `xyz` and `spectral` forms are not read.
fn filter(m: &tobj::Material) -> Option<f32> {
    if !matches!(m.illumination_model, Some(4 | 6 | 7)) {
        return None;
    }
    let values: Vec<f32> =
        m.unknown_param.get("Tf")?.split_whitespace().map_while(|v| v.parse::<f32>().ok()).take(3).collect();
    let largest = values.into_iter().fold(f32::NAN, f32::max);
    (largest.is_finite()).then(|| largest.clamp(0.0, 1.0))
}

/// Cook–Torrance (GGX) when the material carries the PBR extension's
/// scalar keys `Pr` (roughness, default 1) or `Pm` (metallic, default 0);
/// else the basic model. Values that do not parse count as absent (the
/// MTL check reports them).
fn pbr_model(m: &tobj::Material) -> Model {
    let value =
        |key: &str| m.unknown_param.get(key).and_then(|v| v.split_whitespace().next()?.parse::<f32>().ok());
    let (roughness, metallic) = (value("Pr"), value("Pm"));
    if roughness.is_none() && metallic.is_none() {
        return Model::Basic;
    }
    Model::CookTorrance(Microfacet {
        metallic: metallic.unwrap_or(0.0),
        roughness: roughness.unwrap_or(1.0),
        distribution: Distribution::Ggx,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_statements_keep_spaces_in_file_names_and_read_clamp() {
        let mut warnings = Vec::new();
        let mtl = Path::new("models/a.mtl");
        let map = parse_map_statement("-clamp on -mm 0 1 my  texture.png", mtl, &mut warnings, "m").unwrap();
        assert_eq!(map.file, Path::new("my  texture.png"), "the name as written");
        assert_eq!(map.sampler.wrap_s, Wrap::ClampToEdge);
        assert_eq!(warnings.len(), 1, "{warnings:?}");
        assert!(warnings[0].contains("models/a.mtl: material 'm': map_Kd option '-mm 0 1'"), "{warnings:?}");
        let map = parse_map_statement("-clamp off t.jpg", mtl, &mut warnings, "m").unwrap();
        assert_eq!(
            map,
            MapStatement { file: "t.jpg".into(), sampler: Sampler::default(), bump_multiplier: None }
        );
        assert_eq!(parse_map_statement("-blendu on", mtl, &mut warnings, "m"), None);
        let windows = parse_map_statement(".\\textures\\Spider Tex.jpg", mtl, &mut warnings, "m").unwrap();
        assert_eq!(windows.file, Path::new("./textures/Spider Tex.jpg"), "backslashes are separators");
    }
}

//! 3MF (3D Manufacturing Format, the files of 3D-printing slicers and CAD
//! tools): a ZIP archive of XML parts, read through the `zip` and
//! `quick-xml` crates.
//!
//! **Package.** The 3D model part is the one `_rels/.rels` names (the
//! relationship of type `…/2013/01/3dmodel`), else `3D/3dmodel.model`
//! (part names match without regard to case). Entries stored or deflated
//! are read; other compression methods and encrypted entries are errors.
//! The objects that components and build items name with the production
//! extension's `p:path` are read from those parts of the archive (as
//! Bambu Studio and OrcaSlicer write them).
//!
//! **Geometry.** Every `<object>` with a `<mesh>` (`<vertex x y z>`,
//! `<triangle v1 v2 v3>`) is drawn where the `<build>`'s `<item>`s place
//! it, through any `<components>` (`<component objectid transform>`)
//! between. A `transform` is the 3MF affine matrix, 12 numbers
//! `m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32` in row-vector form: a
//! point p maps to p·M, so x' = m00·x + m10·y + m20·z + m30 (and likewise
//! for y', z'); the four triples are the images of the x, y and z axes and
//! the translation (the columns of a `glam` affine). A component's transform
//! applies before its parent's: p·C·I. Transforms are composed in f64 and
//! baked into the positions: every placed object becomes its own meshes in
//! build coordinates. Under a mirroring transform (negative determinant)
//! the triangles are reversed, so that front faces stay front. Triangles
//! that repeat a vertex are dropped (as the STL loader drops them); vertex
//! normals are computed as for every mesh without them (SPEC §6).
//!
//! **Colours.** The core `<basematerials>` (`<base displaycolor>`) and the
//! materials extension's `<m:colorgroup>` (`<m:color color>`), "#RRGGBB" or
//! "#RRGGBBAA" (sRGB bytes / 255, used as stored, like every colour
//! zline reads), referenced by the object's `pid`/`pindex` or a triangle's
//! `pid`/`p1`. A triangle takes the colour of its first corner (`p1`; a
//! colour group's gradient through `p2`, `p3` is not drawn). The scene
//! model has one material per mesh, and vertex colours are not shown under
//! Phong shading (zline's default), so an object whose triangles differ in
//! colour is split into one mesh per colour: material ka = kd = the colour,
//! opacity = its alpha, the default specular. Triangles without a property,
//! or whose property group zline does not read (textures, composites,
//! multiproperties), take the default material. A mesh is named after its
//! object (`name`, else `object ID`), with the colour's name or value in
//! parentheses when the object is split.
//!
//! **Units.** Coordinates are kept as written, in the model's `unit`
//! (millimetres by default), not scaled: an STL of the same part, also in
//! millimetres by convention, loads at the same size. The unit must be one
//! of the six the specification names (micron, millimeter, centimeter,
//! inch, foot, meter).
//!
//! **Refused, with an error naming the file and the part:** a file that is
//! not a ZIP archive, an archive without the model part, malformed XML, a
//! root element other than `<model>`, an extension the file requires and
//! zline does not read (anything but materials and production), a
//! non-finite or non-numeric coordinate, index or transform, a vertex or
//! property index out of range, a `pid` that names no property group, an
//! `objectid` that names no object, two resources with one id, components
//! that contain themselves or nest deeper than [`MAX_COMPONENT_DEPTH`], and
//! a transform that collapses everything to a point.
//!
//! **Limits.** The archive is at most
//! [`MAX_MODEL_FILE_BYTES`](zline_scene::MAX_MODEL_FILE_BYTES) and holds at
//! most [`MAX_ARCHIVE_ENTRIES`] entries (counted before the `zip` crate
//! reads its directory); the model parts decompress to at most
//! `MAX_MODEL_FILE_BYTES` in all, checked against each entry's declared
//! size before it is read and against the bytes actually inflated while it
//! is parsed (a zip bomb stops there). The XML is parsed as it is inflated,
//! never held whole: no text or tag may be longer than 16 MiB, elements
//! nest at most 64 deep, and the parts hold at most as many elements as
//! the largest file within the limits (so that elements zline reads past
//! cost no more time than triangles would). The file may hold
//! at most [`MAX_TRIANGLES`] triangles and [`MAX_VERTICES`] vertices, and
//! so may the objects as placed (every object counted as often as it is
//! placed, counted before any is built), in at most [`MAX_3MF_MESHES`]
//! meshes and [`MAX_PLACEMENTS`] placed objects.

mod assembly;
mod model;
mod part;
#[cfg(test)]
mod tests;

use std::io::{BufReader, Cursor};

use zip::ZipArchive;
use zline_scene::{MAX_MODEL_FILE_BYTES, MAX_TEXT_FILE_BYTES};

use crate::files::{read_limited, FileKind};
use model::*;
pub use model::{MAX_3MF_MESHES, MAX_ARCHIVE_ENTRIES, MAX_COMPONENT_DEPTH, MAX_PLACEMENTS};

/// Loads a 3MF file: every object its build places, as meshes in build
/// coordinates (see the module documentation).
pub fn load_3mf(path: &Path) -> Result<Vec<Mesh>, SceneError> {
    let bytes = read_limited(path, FileKind::Model).map_err(|e| e.into_error(path))?;
    parse_3mf(path, &bytes)
}

/// Parses 3MF bytes read from `path` (which names the file in messages).
pub(crate) fn parse_3mf(path: &Path, bytes: &[u8]) -> Result<Vec<Mesh>, SceneError> {
    parse_within(path, bytes, MAX_MODEL_FILE_BYTES)
}

/// [`parse_3mf`] with `limit` bytes for the model parts once inflated.
fn parse_within(path: &Path, bytes: &[u8], limit: u64) -> Result<Vec<Mesh>, SceneError> {
    let error = |message: String| SceneError::File { path: path.to_path_buf(), message };
    if !bytes.starts_with(b"PK\x03\x04") && !bytes.starts_with(b"PK\x05\x06") {
        return Err(error("not a 3MF file: not a ZIP archive".into()));
    }
    let entries = central_headers(bytes);
    if entries > MAX_ARCHIVE_ENTRIES {
        return Err(error(format!(
            "ZIP archive of more than {MAX_ARCHIVE_ENTRIES} entries, more than the limit for a 3MF file"
        )));
    }
    let archive = ZipArchive::new(Cursor::new(bytes))
        .map_err(|e| error(format!("not a 3MF file: bad ZIP archive: {e}")))?;
    let mut package =
        Package { archive, limit, parts: Vec::new(), part_index: HashMap::new(), totals: Totals::default() };
    let named = package.relationship_target();
    let entry = named.as_deref().and_then(|n| package.find_entry(n));
    let Some(entry) = entry.or_else(|| package.find_entry(DEFAULT_MODEL_PART)) else {
        let root = named.unwrap_or_else(|| DEFAULT_MODEL_PART.to_owned());
        return Err(error(format!("not a 3MF file: the archive has no 3D model part ('{}')", quote(&root))));
    };
    package.read_part(entry, true).map_err(error)?;
    // The parts that production-extension paths name, each read once.
    let mut next = 0;
    while next < package.parts.len() {
        let paths: Vec<String> = package.parts[next].paths().map(str::to_owned).collect();
        for name in paths {
            let key = name.to_ascii_lowercase();
            if !package.part_index.contains_key(&key) {
                let part = &package.parts[next].name;
                let Some(entry) = package.find_entry(&name) else {
                    return Err(error(format!(
                        "{part}: p:path '{}' names no part of the archive",
                        quote(&name)
                    )));
                };
                let index = match package.parts.iter().position(|p| p.entry == entry) {
                    Some(index) => index,
                    None => package.read_part(entry, false).map_err(error)?,
                };
                package.part_index.insert(key, index);
            }
        }
        next += 1;
    }
    Assembly::new(path, &package.parts, &package.part_index).meshes()
}

/// The number of central directory headers the archive can hold: the
/// occurrences of their signature, an upper bound on the entries the `zip`
/// crate reads (a chance match inside compressed data is one in 2³²
/// positions).
fn central_headers(bytes: &[u8]) -> usize {
    let mut count = 0;
    let mut at = 0;
    while let Some(found) = bytes[at..].windows(4).position(|w| w == b"PK\x01\x02") {
        count += 1;
        at += found + 4;
        if count > MAX_ARCHIVE_ENTRIES {
            break;
        }
    }
    count
}

/// A limit in bytes as messages give it.
fn bytes_limit(limit: u64) -> String {
    match limit {
        l if l >= 1 << 30 && l.is_multiple_of(1 << 30) => format!("{} GiB ({l} bytes)", l >> 30),
        l => format!("{l} bytes"),
    }
}

/// Longest run of XML without a `<`: the longest text or tag, which the
/// streaming parser holds whole (16 MiB).
const MAX_XML_TOKEN: u64 = 16 << 20;

/// Refuses XML with a run of more than [`MAX_XML_TOKEN`] bytes without a
/// `<`, so that a zip bomb of text cannot make the parser hold it.
struct TokenGuard<R> {
    inner: R,
    /// Bytes since the last `<`.
    run: u64,
}

impl<R: Read> Read for TokenGuard<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        let chunk = &buf[..n];
        // The run up to the chunk's first `<` (a run between two `<` of
        // one chunk is shorter than the chunk: the `BufReader`'s 8 KiB).
        let first = chunk.iter().position(|&b| b == b'<').unwrap_or(n);
        let longest = self.run + first as u64;
        self.run = match chunk.iter().rposition(|&b| b == b'<') {
            Some(last) => (n - last - 1) as u64,
            None => longest,
        };
        if longest > MAX_XML_TOKEN {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!("a text or tag longer than {} MiB", MAX_XML_TOKEN >> 20),
            ));
        }
        Ok(n)
    }
}

// ---- The package: the archive and its model parts ----------------------------

struct Package<'a> {
    archive: ZipArchive<Cursor<&'a [u8]>>,
    /// Most bytes the model parts may inflate to, in all.
    limit: u64,
    /// The model parts read, the root first.
    parts: Vec<Part>,
    /// The index in `parts` of each part a `p:path` names (in lower case,
    /// the leading `/` removed).
    part_index: HashMap<String, usize>,
    totals: Totals,
}

impl Package<'_> {
    /// The target of the package's 3D model relationship, if `_rels/.rels`
    /// is there, readable and names one.
    fn relationship_target(&mut self) -> Option<String> {
        let index = self.find_entry("_rels/.rels")?;
        let entry = self.archive.by_index(index).ok()?;
        if entry.size() > MAX_TEXT_FILE_BYTES {
            return None;
        }
        let mut xml = NsReader::from_reader(BufReader::new(entry.take(MAX_TEXT_FILE_BYTES)));
        let mut buf = Vec::new();
        loop {
            buf.clear();
            match xml.read_event_into(&mut buf).ok()? {
                Event::Start(e) | Event::Empty(e) if e.local_name().as_ref() == "Relationship" => {
                    let (mut kind, mut target) = (None, None);
                    for attribute in e.attributes() {
                        let attribute = attribute.ok()?;
                        match attribute.key.as_ref() {
                            "Type" => {
                                kind = Some(
                                    attribute.normalized_value(XmlVersion::Implicit1_0).ok()?.into_owned(),
                                )
                            }
                            "Target" => {
                                target = Some(
                                    attribute.normalized_value(XmlVersion::Implicit1_0).ok()?.into_owned(),
                                )
                            }
                            _ => {}
                        }
                    }
                    if kind.as_deref().map(str::trim) == Some(MODEL_RELATIONSHIP) {
                        return target.map(|t| t.trim().trim_start_matches('/').to_owned());
                    }
                }
                Event::Eof => return None,
                _ => {}
            }
        }
    }

    /// The index of the archive entry named `name` (a leading `/` and case
    /// ignored).
    fn find_entry(&self, name: &str) -> Option<usize> {
        let name = name.trim_start_matches('/');
        self.archive.index_for_name(name).or_else(|| {
            let found = self.archive.file_names().find(|n| n.eq_ignore_ascii_case(name))?;
            self.archive.index_for_name(found)
        })
    }

    /// Reads and parses the model part at entry `index`; its index in
    /// `parts`.
    fn read_part(&mut self, index: usize, root: bool) -> Result<usize, String> {
        let budget = self.limit - self.totals.bytes.min(self.limit);
        let name = self.archive.name_for_index(index).unwrap_or_default().to_owned();
        let entry =
            self.archive.by_index(index).map_err(|e| format!("{name}: cannot read the model part: {e}"))?;
        if entry.is_dir() {
            return Err(format!("{name}: is a folder of the archive, not a 3D model part"));
        }
        if entry.size() > budget {
            return Err(format!(
                "{name}: declares {} bytes uncompressed, more than the limit of {} for model parts",
                entry.size(),
                bytes_limit(self.limit)
            ));
        }
        let mut limited = BufReader::new(TokenGuard { inner: entry.take(budget + 1), run: 0 });
        let parsed = part::parse_part(&mut limited, &name, root, &mut self.totals);
        let left = limited.get_ref().inner.limit();
        if left == 0 {
            return Err(format!(
                "{name}: inflates to more than the limit of {} for model parts",
                bytes_limit(self.limit)
            ));
        }
        self.totals.bytes += budget + 1 - left;
        let mut part = parsed.map_err(|message| format!("{name}: {message}"))?;
        part.entry = index;
        self.parts.push(part);
        Ok(self.parts.len() - 1)
    }
}

//! The 3MF loader's model: its limits and names, a model part as read
//! (resources, objects, build items) and the assembly's bookkeeping.

pub(super) use std::borrow::Cow;
pub(super) use std::collections::HashMap;
pub(super) use std::io::{BufRead, Read};
pub(super) use std::path::Path;

pub(super) use glam::{DAffine3, DMat3, Vec3};
pub(super) use quick_xml::events::{BytesStart, Event};
pub(super) use quick_xml::name::{Namespace, NamespaceResolver, ResolveResult};
pub(super) use quick_xml::{NsReader, XmlVersion};
pub(super) use zline_scene::{Material, Mesh, MAX_TRIANGLES, MAX_VERTICES};

pub(super) use crate::error::SceneError;

/// Most entries a 3MF archive may hold (a slicer's project file has a few
/// dozen): the `zip` crate keeps a record of every entry in memory.
pub const MAX_ARCHIVE_ENTRIES: usize = 10_000;

/// Deepest nesting of components below a build item: a component inside
/// an object inside a component … at most this many levels.
pub const MAX_COMPONENT_DEPTH: usize = 16;

/// Most objects one 3MF file may place, counting every component of every
/// build item (each placement is walked and becomes its own meshes).
pub const MAX_PLACEMENTS: u64 = 1 << 20;

/// Most meshes one 3MF file may become: one per placed mesh object and
/// colour.
pub const MAX_3MF_MESHES: u64 = 1 << 16;

/// Deepest nesting of XML elements.
pub(super) const MAX_XML_DEPTH: usize = 64;

/// Most XML elements (comments and processing instructions included) the
/// model parts may hold in all: those of the largest file within the
/// limits, plus room for the rest, so that elements zline reads past cost
/// no more time than a valid file of [`MAX_TRIANGLES`] triangles.
pub(super) const MAX_XML_NODES: usize = MAX_VERTICES + MAX_TRIANGLES + (1 << 20);

pub(super) const CORE_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
pub(super) const MATERIAL_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/material/2015/02";
pub(super) const PRODUCTION_NS: &str = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";
pub(super) const MODEL_RELATIONSHIP: &str = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";
pub(super) const DEFAULT_MODEL_PART: &str = "3D/3dmodel.model";
pub(super) const UNITS: [&str; 6] = ["micron", "millimeter", "centimeter", "inch", "foot", "meter"];

/// "No value" in the compact triangle and object records.
pub(super) const NONE: u32 = u32::MAX;

/// `value` for a message, cut to 60 characters.
pub(super) fn quote(value: &str) -> Cow<'_, str> {
    match value.char_indices().nth(60) {
        Some((end, _)) => Cow::Owned(format!("{}…", &value[..end])),
        None => Cow::Borrowed(value),
    }
}

/// What the parts read so far hold, for the file's limits.
#[derive(Default)]
pub(super) struct Totals {
    /// Bytes inflated from model parts.
    pub(super) bytes: u64,
    pub(super) vertices: usize,
    pub(super) triangles: usize,
    /// Property group entries, components and build items.
    pub(super) entries: usize,
    /// XML elements, comments and processing instructions.
    pub(super) nodes: usize,
}

// ---- One model part, as read ---------------------------------------------------

/// A model part's resources and build.
pub(super) struct Part {
    /// The entry's name in the archive.
    pub(super) name: String,
    /// The entry's index in the archive.
    pub(super) entry: usize,
    pub(super) resources: HashMap<u32, Resource>,
    pub(super) objects: Vec<ObjectDef>,
    pub(super) groups: Vec<Group>,
    /// The build items (of the root part only).
    pub(super) build: Vec<Placement>,
}

impl Part {
    /// The parts that this part's components and build items name.
    pub(super) fn paths(&self) -> impl Iterator<Item = &str> {
        let components = self.objects.iter().flat_map(|o| &o.components);
        components.chain(&self.build).filter_map(|p| p.path.as_deref())
    }
}

/// What a resource id names.
#[derive(Clone, Copy)]
pub(super) enum Resource {
    /// An object: its index in `Part::objects`.
    Object(usize),
    /// A base material or colour group: its index in `Part::groups`.
    Group(usize),
    /// A resource zline does not read (textures, composite materials …):
    /// triangles that take their property from it get the default material.
    Other,
}

/// A `<basematerials>` or `<m:colorgroup>`.
pub(super) struct Group {
    pub(super) id: u32,
    pub(super) kind: &'static str,
    pub(super) entries: Vec<Swatch>,
}

/// One entry of a property group: its colour and (base materials) name.
#[derive(Clone)]
pub(super) struct Swatch {
    pub(super) rgba: [u8; 4],
    pub(super) name: Option<Box<str>>,
}

/// An `<object>`.
pub(super) struct ObjectDef {
    pub(super) id: u32,
    pub(super) name: Option<String>,
    /// The object-level property group and index, or [`NONE`].
    pub(super) pid: u32,
    pub(super) pindex: u32,
    pub(super) positions: Vec<Vec3>,
    pub(super) triangles: Vec<Triangle>,
    pub(super) components: Vec<Placement>,
}

/// A `<triangle>`: its vertices, and its own property group and first
/// corner's index, or [`NONE`].
pub(super) struct Triangle {
    pub(super) v: [u32; 3],
    pub(super) pid: u32,
    pub(super) p1: u32,
}

/// A `<component>` or build `<item>`.
pub(super) struct Placement {
    pub(super) object: u32,
    /// The production extension's `p:path`, without its leading `/`.
    pub(super) path: Option<String>,
    pub(super) transform: DAffine3,
    /// Its position among its siblings, for messages.
    pub(super) ordinal: usize,
}

/// Where the parser is.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Tag {
    Model,
    Resources,
    Object,
    Mesh,
    Vertices,
    Triangles,
    Components,
    BaseMaterials,
    ColorGroup,
    Build,
    /// An element zline reads past (with everything inside it), or one
    /// already handled (a vertex, a triangle …).
    Other,
}

// ---- Assembly: placements → meshes ---------------------------------------------

/// An object of a part: (part index, object index).
pub(super) type ObjectKey = (usize, usize);

/// One colour's triangles of an object, before placement.
pub(super) struct ColorMesh {
    pub(super) name: String,
    pub(super) material: Material,
    pub(super) positions: Vec<Vec3>,
    pub(super) triangles: Vec<[u32; 3]>,
}

/// What placing an object once brings, its components included.
#[derive(Clone, Copy, Default)]
pub(super) struct Counts {
    pub(super) triangles: u64,
    pub(super) vertices: u64,
    pub(super) meshes: u64,
    pub(super) placements: u64,
    /// Levels of components below it (0 for an object without any).
    pub(super) height: usize,
}

impl Counts {
    /// `self + other`, saturating (the height is `self`'s).
    pub(super) fn add(self, other: Counts) -> Counts {
        Counts {
            triangles: self.triangles.saturating_add(other.triangles),
            vertices: self.vertices.saturating_add(other.vertices),
            meshes: self.meshes.saturating_add(other.meshes),
            placements: self.placements.saturating_add(other.placements),
            height: self.height,
        }
    }
}

/// A count as `usize`, saturating.
pub(super) fn clamp(n: u64) -> usize {
    usize::try_from(n).unwrap_or(usize::MAX)
}

pub(super) struct Assembly<'a> {
    pub(super) path: &'a Path,
    pub(super) parts: &'a [Part],
    /// Part indices by lower-case name.
    pub(super) part_index: &'a HashMap<String, usize>,
    /// The colour meshes of each object reached.
    pub(super) colored: HashMap<ObjectKey, Vec<ColorMesh>>,
    /// What placing each object reached brings.
    pub(super) counts: HashMap<ObjectKey, Counts>,
}

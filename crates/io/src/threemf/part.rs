//! One model part of a 3MF package parsed into a [`Part`](super::Part).

use super::model::*;

/// The parser of one model part.
struct PartParser<'t> {
    root: bool,
    part: Part,
    object: Option<ObjectDef>,
    totals: &'t mut Totals,
}

/// Parses a model part from `reader`.
pub(super) fn parse_part(
    reader: impl BufRead,
    name: &str,
    root: bool,
    totals: &mut Totals,
) -> Result<Part, String> {
    let part = Part {
        name: name.to_owned(),
        entry: 0,
        resources: HashMap::new(),
        objects: Vec::new(),
        groups: Vec::new(),
        build: Vec::new(),
    };
    let mut parser = PartParser { root, part, object: None, totals };
    let mut xml = NsReader::from_reader(reader);
    let mut buf = Vec::new();
    let mut stack: Vec<Tag> = Vec::new();
    let mut seen_model = false;
    loop {
        buf.clear();
        let event = match xml.read_event_into(&mut buf) {
            Ok(event) => event,
            Err(quick_xml::Error::Io(e)) => return Err(format!("cannot read the part: {e}")),
            Err(e) => return Err(format!("malformed XML at byte {}: {e}", xml.error_position())),
        };
        if !matches!(event, Event::Text(_) | Event::End(_) | Event::Eof) {
            parser.totals.nodes += 1;
            if parser.totals.nodes > MAX_XML_NODES {
                return Err(format!("more than {MAX_XML_NODES} XML elements in the model parts"));
            }
        }
        match event {
            Event::Start(_) | Event::Empty(_) if stack.is_empty() && seen_model => {
                return Err("more than one root element".into());
            }
            Event::Start(e) => {
                if stack.len() >= MAX_XML_DEPTH {
                    return Err(format!("elements nested more than {MAX_XML_DEPTH} deep"));
                }
                let tag = parser.open(xml.resolver(), &e, stack.last().copied())?;
                seen_model = true;
                stack.push(tag);
            }
            Event::Empty(e) => {
                let tag = parser.open(xml.resolver(), &e, stack.last().copied())?;
                seen_model = true;
                parser.close(tag);
            }
            Event::End(_) => {
                if let Some(tag) = stack.pop() {
                    parser.close(tag);
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if !stack.is_empty() {
        return Err("the XML ends before </model>: the part is cut short".into());
    }
    if !seen_model {
        return Err("no <model> element".into());
    }
    Ok(parser.part)
}

/// Whether the element's namespace is `ns` (`None`: the core namespace,
/// which unprefixed elements without a default namespace are taken to be
/// in too).
fn in_namespace(ns: &ResolveResult, want: Option<&str>) -> bool {
    match (ns, want) {
        (ResolveResult::Unbound, None) => true,
        (ResolveResult::Bound(Namespace(n)), None) => *n == CORE_NS,
        (ResolveResult::Bound(Namespace(n)), Some(want)) => *n == want,
        _ => false,
    }
}

/// The values of an element's attributes named in `names` (unprefixed),
/// in that order, and its production `p:path`.
type Attributes<'e, const N: usize> = ([Option<Cow<'e, str>>; N], Option<Cow<'e, str>>);

fn attributes<'e, const N: usize>(
    resolver: &NamespaceResolver,
    e: &'e BytesStart<'_>,
    names: [&str; N],
) -> Result<Attributes<'e, N>, String> {
    let mut values: [Option<Cow<'e, str>>; N] = std::array::from_fn(|_| None);
    let mut path = None;
    for attribute in e.attributes() {
        let attribute = attribute.map_err(|e| format!("malformed attribute: {e}"))?;
        let key = attribute.key;
        let value = || {
            attribute
                .normalized_value(XmlVersion::Implicit1_0)
                .map_err(|e| format!("attribute '{}': {e}", key.as_ref()))
        };
        if key.prefix().is_none() {
            if let Some(k) = names.iter().position(|n| *n == key.as_ref()) {
                values[k] = Some(value()?);
            }
        } else {
            let (ns, local) = resolver.resolve_attribute(key);
            if local.as_ref() == "path"
                && matches!(ns, ResolveResult::Bound(Namespace(n)) if n == PRODUCTION_NS)
            {
                path = Some(value()?);
            }
        }
    }
    Ok((values, path))
}

/// A whole number ≥ 0 (below [`NONE`]).
fn index(what: &str, value: &str) -> Result<u32, String> {
    value
        .trim()
        .parse::<u32>()
        .ok()
        .filter(|&i| i != NONE)
        .ok_or_else(|| format!("{what} '{}' is not a whole number (0 or more)", quote(value)))
}

/// A finite number that fits f32 (coordinates).
fn coordinate(what: &str, value: &str) -> Result<f32, String> {
    let v = value.trim().parse::<f64>().map(|v| v as f32);
    match v {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("{what} '{}' is not a finite number", quote(value))),
        Err(_) => Err(format!("{what} '{}' is not a number", quote(value))),
    }
}

/// A `transform` attribute: 12 finite numbers, the 3MF matrix (see the
/// module documentation).
pub(super) fn transform(value: &str) -> Result<DAffine3, String> {
    let bad = || format!("transform '{}' is not 12 finite numbers", quote(value));
    let mut m = [0.0f64; 12];
    let mut numbers = value.split_whitespace();
    for slot in &mut m {
        *slot =
            numbers.next().and_then(|n| n.parse::<f64>().ok()).filter(|n| n.is_finite()).ok_or_else(bad)?;
    }
    if numbers.next().is_some() {
        return Err(bad());
    }
    let affine = DAffine3::from_cols_array(&m);
    if affine.matrix3 == DMat3::ZERO {
        return Err(format!("transform '{}' collapses everything to a point", quote(value)));
    }
    Ok(affine)
}

/// A colour "#RRGGBB" or "#RRGGBBAA" (alpha 255 when absent).
pub(super) fn color(what: &str, value: &str) -> Result<[u8; 4], String> {
    let bad = || format!("{what} '{}' is not a colour #RRGGBB or #RRGGBBAA", quote(value));
    let hex = value.trim().strip_prefix('#').ok_or_else(bad)?;
    if !(hex.len() == 6 || hex.len() == 8) || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Err(bad());
    }
    let byte = |k: usize| u8::from_str_radix(&hex[2 * k..2 * k + 2], 16).map_err(|_| bad());
    Ok([byte(0)?, byte(1)?, byte(2)?, if hex.len() == 8 { byte(3)? } else { 255 }])
}

impl PartParser<'_> {
    /// An element opens (or an empty one appears) inside `parent`: its tag,
    /// after reading what it defines.
    fn open(
        &mut self,
        resolver: &NamespaceResolver,
        e: &BytesStart,
        parent: Option<Tag>,
    ) -> Result<Tag, String> {
        let (ns, local) = resolver.resolve_element(e.name());
        let core = in_namespace(&ns, None);
        let materials = in_namespace(&ns, Some(MATERIAL_NS));
        Ok(match (parent, local.as_ref()) {
            (None, "model") if core => {
                self.model(e)?;
                Tag::Model
            }
            (None, _) => {
                return Err(format!("the root element is <{}>, not a 3MF <model>", quote(e.name().as_ref())))
            }
            (Some(Tag::Model), "resources") if core => Tag::Resources,
            (Some(Tag::Model), "build") if core => Tag::Build,
            (Some(Tag::Resources), "object") if core => {
                self.object(resolver, e)?;
                Tag::Object
            }
            (Some(Tag::Resources), "basematerials") if core => {
                self.group(resolver, e, "basematerials")?;
                Tag::BaseMaterials
            }
            (Some(Tag::Resources), "colorgroup") if materials => {
                self.group(resolver, e, "colorgroup")?;
                Tag::ColorGroup
            }
            (Some(Tag::Resources), _) => {
                // Any other resource with an id: a property group zline
                // does not read, or another extension's resource.
                if let ([Some(id)], _) = attributes(resolver, e, ["id"])? {
                    let id = index("resource id", &id)?;
                    self.define(id, Resource::Other)?;
                }
                Tag::Other
            }
            (Some(Tag::Object), "mesh") if core => Tag::Mesh,
            (Some(Tag::Object), "components") if core => Tag::Components,
            (Some(Tag::Mesh), "vertices") if core => Tag::Vertices,
            (Some(Tag::Mesh), "triangles") if core => Tag::Triangles,
            (Some(Tag::Vertices), "vertex") if core => {
                self.vertex(resolver, e)?;
                Tag::Other
            }
            (Some(Tag::Triangles), "triangle") if core => {
                self.triangle(resolver, e)?;
                Tag::Other
            }
            (Some(Tag::Components), "component") if core => {
                let placement = self.placement(resolver, e, "component")?;
                if let Some(object) = &mut self.object {
                    object.components.push(placement);
                }
                Tag::Other
            }
            (Some(Tag::BaseMaterials), "base") if core => {
                let ([name, value], _) = attributes(resolver, e, ["name", "displaycolor"])?;
                let at = self.entry_name();
                let value = value.ok_or_else(|| format!("{at}: no displaycolor"))?;
                let rgba = color(&format!("{at}: displaycolor"), &value)?;
                let name = name.map(|n| quote(&n).into_owned().into_boxed_str());
                self.add_entry(Swatch { rgba, name })?;
                Tag::Other
            }
            (Some(Tag::ColorGroup), "color") if materials => {
                let ([value], _) = attributes(resolver, e, ["color"])?;
                let at = self.entry_name();
                let value = value.ok_or_else(|| format!("{at}: no color"))?;
                let rgba = color(&format!("{at}: color"), &value)?;
                self.add_entry(Swatch { rgba, name: None })?;
                Tag::Other
            }
            (Some(Tag::Build), "item") if core => {
                let placement = self.placement(resolver, e, "build item")?;
                if self.root {
                    self.part.build.push(placement);
                }
                Tag::Other
            }
            _ => Tag::Other,
        })
    }

    /// An element closes.
    fn close(&mut self, tag: Tag) {
        if tag == Tag::Object {
            if let Some(object) = self.object.take() {
                self.part.objects.push(object);
            }
        }
    }

    /// `<model>`: its unit and required extensions.
    fn model(&mut self, e: &BytesStart) -> Result<(), String> {
        let mut prefixes = HashMap::new();
        let (mut unit, mut required) = (None, None);
        for attribute in e.attributes() {
            let attribute = attribute.map_err(|e| format!("<model>: malformed attribute: {e}"))?;
            let value = attribute
                .normalized_value(XmlVersion::Implicit1_0)
                .map_err(|e| format!("<model>: attribute '{}': {e}", attribute.key.as_ref()))?
                .into_owned();
            match attribute.key.as_ref() {
                "unit" => unit = Some(value),
                "requiredextensions" => required = Some(value),
                key => {
                    if let Some(prefix) = key.strip_prefix("xmlns:") {
                        prefixes.insert(prefix.to_owned(), value);
                    }
                }
            }
        }
        if let Some(unit) = unit {
            if !UNITS.contains(&unit.trim()) {
                return Err(format!("unit '{}' is not one of {}", quote(&unit), UNITS.join(", ")));
            }
        }
        for prefix in required.as_deref().unwrap_or("").split_whitespace() {
            let ns = prefixes.get(prefix).map(String::as_str);
            let known = ns.is_some_and(|ns| [MATERIAL_NS, PRODUCTION_NS, CORE_NS].contains(&ns));
            if !known {
                return Err(format!(
                    "requires the 3MF extension '{}' ({}), which zline does not read",
                    quote(prefix),
                    ns.map_or("no namespace declared for it".into(), quote)
                ));
            }
        }
        Ok(())
    }

    /// Records resource `id`; two resources may not share one.
    fn define(&mut self, id: u32, resource: Resource) -> Result<(), String> {
        if self.part.resources.insert(id, resource).is_some() {
            return Err(format!("two resources have the id {id}"));
        }
        Ok(())
    }

    /// `<object>`.
    fn object(&mut self, resolver: &NamespaceResolver, e: &BytesStart) -> Result<(), String> {
        let ([id, name, pid, pindex], _) = attributes(resolver, e, ["id", "name", "pid", "pindex"])?;
        let id = index("object id", &id.ok_or("an <object> has no id")?)?;
        let at = |what: &str| format!("object {id}: {what}");
        let pid = pid.map(|p| index(&at("pid"), &p)).transpose()?.unwrap_or(NONE);
        let pindex = pindex.map(|p| index(&at("pindex"), &p)).transpose()?.unwrap_or(NONE);
        self.define(id, Resource::Object(self.part.objects.len()))?;
        self.object = Some(ObjectDef {
            id,
            name: name.map(|n| quote(&n).into_owned()),
            pid,
            pindex,
            positions: Vec::new(),
            triangles: Vec::new(),
            components: Vec::new(),
        });
        Ok(())
    }

    /// `<basematerials>` or `<m:colorgroup>`.
    fn group(
        &mut self,
        resolver: &NamespaceResolver,
        e: &BytesStart,
        kind: &'static str,
    ) -> Result<(), String> {
        let ([id], _) = attributes(resolver, e, ["id"])?;
        let id = index(&format!("{kind} id"), &id.ok_or_else(|| format!("a <{kind}> has no id"))?)?;
        self.define(id, Resource::Group(self.part.groups.len()))?;
        self.part.groups.push(Group { id, kind, entries: Vec::new() });
        Ok(())
    }

    /// The next entry of the open group, for messages.
    fn entry_name(&self) -> String {
        match self.part.groups.last() {
            Some(g) => format!("{} {}: entry {}", g.kind, g.id, g.entries.len()),
            None => "property group entry".into(),
        }
    }

    /// Adds an entry to the open group.
    fn add_entry(&mut self, swatch: Swatch) -> Result<(), String> {
        self.count_entry()?;
        if let Some(group) = self.part.groups.last_mut() {
            group.entries.push(swatch);
        }
        Ok(())
    }

    /// Counts a property group entry, component or build item against the
    /// file's limit.
    fn count_entry(&mut self) -> Result<(), String> {
        self.totals.entries += 1;
        if self.totals.entries > MAX_VERTICES {
            return Err(format!(
                "more than {MAX_VERTICES} property group entries, components and build items in all"
            ));
        }
        Ok(())
    }

    /// `<vertex>`.
    fn vertex(&mut self, resolver: &NamespaceResolver, e: &BytesStart) -> Result<(), String> {
        let Some(object) = &mut self.object else { return Ok(()) };
        let at = format!("object {}: vertex {}", object.id, object.positions.len());
        let ([x, y, z], _) = attributes(resolver, e, ["x", "y", "z"])?;
        let mut p = [0.0f32; 3];
        for (k, (value, axis)) in [x, y, z].into_iter().zip(["x", "y", "z"]).enumerate() {
            let value = value.ok_or_else(|| format!("{at}: no {axis}"))?;
            p[k] = coordinate(&format!("{at}: {axis}"), &value)?;
        }
        self.totals.vertices += 1;
        if self.totals.vertices > MAX_VERTICES {
            return Err(format!("{at}: more than the limit of {MAX_VERTICES} vertices"));
        }
        object.positions.push(Vec3::from(p));
        Ok(())
    }

    /// `<triangle>`.
    fn triangle(&mut self, resolver: &NamespaceResolver, e: &BytesStart) -> Result<(), String> {
        let Some(object) = &mut self.object else { return Ok(()) };
        let at = format!("object {}: triangle {}", object.id, object.triangles.len());
        let ([v1, v2, v3, pid, p1], _) = attributes(resolver, e, ["v1", "v2", "v3", "pid", "p1"])?;
        let mut v = [0u32; 3];
        for (k, value) in [v1, v2, v3].into_iter().enumerate() {
            let value = value.ok_or_else(|| format!("{at}: no v{}", k + 1))?;
            v[k] = index(&format!("{at}: v{}", k + 1), &value)?;
            if v[k] as usize >= object.positions.len() {
                return Err(format!(
                    "{at}: vertex index {} is outside 0..{} (the object's vertices)",
                    v[k],
                    object.positions.len()
                ));
            }
        }
        let pid = pid.map(|p| index(&format!("{at}: pid"), &p)).transpose()?.unwrap_or(NONE);
        let p1 = p1.map(|p| index(&format!("{at}: p1"), &p)).transpose()?.unwrap_or(NONE);
        self.totals.triangles += 1;
        if self.totals.triangles > MAX_TRIANGLES {
            return Err(format!("{at}: more than the limit of {MAX_TRIANGLES} triangles"));
        }
        object.triangles.push(Triangle { v, pid, p1 });
        Ok(())
    }

    /// `<component>` or build `<item>`.
    fn placement(
        &mut self,
        resolver: &NamespaceResolver,
        e: &BytesStart,
        what: &str,
    ) -> Result<Placement, String> {
        let ordinal = match (&self.object, what) {
            (Some(object), "component") => object.components.len(),
            _ => self.part.build.len(),
        };
        let at = match (&self.object, what) {
            (Some(object), "component") => format!("object {}: component {ordinal}", object.id),
            _ => format!("{what} {ordinal}"),
        };
        self.count_entry()?;
        let ([object, matrix], path) = attributes(resolver, e, ["objectid", "transform"])?;
        let object = index(&format!("{at}: objectid"), &object.ok_or_else(|| format!("{at}: no objectid"))?)?;
        let transform = match matrix {
            Some(m) => transform(&m).map_err(|m| format!("{at}: {m}"))?,
            None => DAffine3::IDENTITY,
        };
        let path = path.map(|p| p.trim().trim_start_matches('/').to_owned());
        Ok(Placement { object, path, transform, ordinal })
    }
}

//! Placements → meshes: the build items and components of the parts
//! placed, counted and baked into meshes.

use super::model::*;

impl<'a> Assembly<'a> {
    pub(super) fn new(
        path: &'a Path,
        parts: &'a [Part],
        part_index: &'a HashMap<String, usize>,
    ) -> Assembly<'a> {
        Assembly { path, parts, part_index, colored: HashMap::new(), counts: HashMap::new() }
    }

    /// The meshes of the build: counted first, within the limits, then
    /// built.
    pub(super) fn meshes(mut self) -> Result<Vec<Mesh>, SceneError> {
        let path = self.path;
        let error = |message: String| SceneError::File { path: path.to_path_buf(), message };
        let root = &self.parts[0];
        let mut total = Counts::default();
        let mut items = Vec::with_capacity(root.build.len());
        for item in &root.build {
            let at = |m: String| error(format!("{}: build item {}: {m}", root.name, item.ordinal));
            let key = self.resolve(0, item).map_err(at)?;
            total = total.add(self.count(key, 0, &mut Vec::new()).map_err(at)?);
            items.push((key, item.transform));
        }
        SceneError::check_size(path, clamp(total.triangles), clamp(total.vertices))?;
        if total.placements > MAX_PLACEMENTS {
            return Err(error(format!(
                "the build places {} objects, more than the limit of {MAX_PLACEMENTS}",
                total.placements
            )));
        }
        if total.meshes > MAX_3MF_MESHES {
            return Err(error(format!(
                "the build makes {} meshes (objects placed × colours), more than the limit of {MAX_3MF_MESHES}",
                total.meshes
            )));
        }
        let mut meshes = Vec::with_capacity(clamp(total.meshes));
        for (key, transform) in items {
            self.place(key, transform, &mut meshes)?;
        }
        if meshes.is_empty() {
            return Err(SceneError::NoTriangles { path: path.to_path_buf() });
        }
        Ok(meshes)
    }

    /// The object that a placement in part `part` names.
    fn resolve(&self, part: usize, placement: &Placement) -> Result<ObjectKey, String> {
        let part = match &placement.path {
            Some(path) => *self
                .part_index
                .get(&path.to_ascii_lowercase())
                .ok_or_else(|| format!("p:path '{}' names no part that was read", quote(path)))?,
            None => part,
        };
        let id = placement.object;
        match self.parts[part].resources.get(&id) {
            Some(Resource::Object(index)) => Ok((part, *index)),
            Some(_) => Err(format!("objectid {id} names a property group, not an object")),
            None if part == 0 => Err(format!("objectid {id} names no object")),
            None => Err(format!("objectid {id} names no object in {}", self.parts[part].name)),
        }
    }

    /// What placing `key` once brings (memoized), refusing components that
    /// contain themselves or nest deeper than [`MAX_COMPONENT_DEPTH`];
    /// `depth` is its level below the build item, `trail` the objects above
    /// it.
    fn count(&mut self, key: ObjectKey, depth: usize, trail: &mut Vec<ObjectKey>) -> Result<Counts, String> {
        let parts = self.parts;
        let object = &parts[key.0].objects[key.1];
        let ids = |trail: &[ObjectKey]| {
            trail.iter().map(|&(p, o)| parts[p].objects[o].id.to_string()).collect::<Vec<_>>().join(" → ")
        };
        if trail.contains(&key) {
            trail.push(key);
            return Err(format!("object {} contains itself (objects {})", object.id, ids(trail)));
        }
        let known = self.counts.get(&key).copied();
        if depth + known.map_or(0, |c| c.height) > MAX_COMPONENT_DEPTH {
            return Err(format!(
                "components nest more than {MAX_COMPONENT_DEPTH} deep (objects {} …)",
                ids(&trail[..trail.len().min(4)])
            ));
        }
        if let Some(counts) = known {
            return Ok(counts);
        }
        let colored = self.colored(key)?;
        let mut counts = Counts {
            triangles: colored.iter().map(|m| m.triangles.len() as u64).sum(),
            vertices: colored.iter().map(|m| m.positions.len() as u64).sum(),
            meshes: colored.len() as u64,
            placements: 1,
            height: 0,
        };
        trail.push(key);
        for component in &object.components {
            let at = |m: String| format!("object {}: component {}: {m}", object.id, component.ordinal);
            let child = self.resolve(key.0, component).map_err(at)?;
            let below = self.count(child, depth + 1, trail)?;
            counts = counts.add(below);
            counts.height = counts.height.max(below.height + 1);
        }
        trail.pop();
        self.counts.insert(key, counts);
        Ok(counts)
    }

    /// The colour meshes of `key`, made on first use.
    fn colored(&mut self, key: ObjectKey) -> Result<&[ColorMesh], String> {
        if !self.colored.contains_key(&key) {
            let part = &self.parts[key.0];
            let meshes = color_meshes(part, &part.objects[key.1])?;
            self.colored.insert(key, meshes);
        }
        Ok(&self.colored[&key])
    }

    /// Places `key` (counted, so its colour meshes are made) with
    /// `transform`, appending its meshes and its components' to `out`.
    fn place(&self, key: ObjectKey, transform: DAffine3, out: &mut Vec<Mesh>) -> Result<(), SceneError> {
        let mirrored = transform.matrix3.determinant() < 0.0;
        for colored in self.colored.get(&key).map_or(&[][..], Vec::as_slice) {
            let positions = colored
                .positions
                .iter()
                .map(|p| transform.transform_point3(p.as_dvec3()).as_vec3())
                .collect();
            let triangles = match mirrored {
                true => colored.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
                false => colored.triangles.clone(),
            };
            let mesh = Mesh::new(colored.name.clone(), positions, None, triangles, colored.material)
                .map_err(|source| SceneError::Mesh {
                    path: self.path.to_path_buf(),
                    mesh: colored.name.clone(),
                    source,
                })?;
            out.push(mesh);
        }
        for component in &self.parts[key.0].objects[key.1].components {
            // Resolved when counted.
            if let Ok(child) = self.resolve(key.0, component) {
                self.place(child, transform * component.transform, out)?;
            }
        }
        Ok(())
    }
}

/// The property (colour) of a triangle: its own `pid` or the object's,
/// and its `p1` or the object's `pindex` (0 when neither is given); `None`
/// for the default material.
fn property<'p>(
    part: &'p Part,
    object: &ObjectDef,
    triangle: &Triangle,
) -> Result<Option<&'p Swatch>, String> {
    let (pid, whose) = match triangle.pid {
        NONE => (object.pid, "the object's pid"),
        pid => (pid, "pid"),
    };
    if pid == NONE {
        return Ok(None);
    }
    let index = [triangle.p1, object.pindex, 0].into_iter().find(|&i| i != NONE).unwrap_or(0);
    match part.resources.get(&pid) {
        None => Err(format!("{whose} {pid} names no property group")),
        Some(Resource::Object(_)) => Err(format!("{whose} {pid} names an object, not a property group")),
        Some(Resource::Other) => Ok(None),
        Some(Resource::Group(g)) => {
            let group = &part.groups[*g];
            group.entries.get(index as usize).map(Some).ok_or_else(|| {
                format!("property index {index} is outside 0..{} ({} {pid})", group.entries.len(), group.kind)
            })
        }
    }
}

/// An object's triangles as one mesh per colour (vertices renumbered per
/// mesh), in the order the colours first appear; triangles that repeat a
/// vertex are dropped.
fn color_meshes(part: &Part, object: &ObjectDef) -> Result<Vec<ColorMesh>, String> {
    let mut index_of: HashMap<Option<[u8; 4]>, usize> = HashMap::new();
    let mut colors: Vec<(Option<&Swatch>, Vec<u32>)> = Vec::new();
    for (t, triangle) in object.triangles.iter().enumerate() {
        let [a, b, c] = triangle.v;
        if a == b || b == c || a == c {
            continue;
        }
        let swatch = property(part, object, triangle)
            .map_err(|m| format!("object {}: triangle {t}: {m}", object.id))?;
        let k = *index_of.entry(swatch.map(|s| s.rgba)).or_insert_with(|| {
            colors.push((swatch, Vec::new()));
            colors.len() - 1
        });
        if colors.len() as u64 > MAX_3MF_MESHES {
            return Err(format!("object {}: more than {MAX_3MF_MESHES} colours", object.id));
        }
        colors[k].1.push(t as u32);
    }
    let base = object.name.clone().unwrap_or_else(|| format!("object {}", object.id));
    let split = colors.len() > 1;
    let mut new_index = vec![NONE; object.positions.len()];
    let mut meshes = Vec::with_capacity(colors.len());
    for (swatch, triangles) in colors {
        let mut positions = Vec::new();
        let mut used = Vec::new();
        let mut renumbered = Vec::with_capacity(triangles.len());
        for t in triangles {
            renumbered.push(object.triangles[t as usize].v.map(|v| {
                let v = v as usize;
                if new_index[v] == NONE {
                    new_index[v] = positions.len() as u32;
                    positions.push(object.positions[v]);
                    used.push(v);
                }
                new_index[v]
            }));
        }
        for v in used {
            new_index[v] = NONE;
        }
        let name = if split { format!("{base} ({})", label(swatch)) } else { base.clone() };
        meshes.push(ColorMesh { name, material: material(swatch), positions, triangles: renumbered });
    }
    Ok(meshes)
}

/// A colour's name in mesh names: the base material's name, else its value.
fn label(swatch: Option<&Swatch>) -> String {
    match swatch {
        None => "default".into(),
        Some(Swatch { name: Some(name), .. }) => name.to_string(),
        Some(Swatch { rgba: [r, g, b, 255], .. }) => format!("#{r:02X}{g:02X}{b:02X}"),
        Some(Swatch { rgba: [r, g, b, a], .. }) => format!("#{r:02X}{g:02X}{b:02X}{a:02X}"),
    }
}

/// The material of a colour: ka = kd = its RGB, opacity its alpha, the
/// default specular; the default material for none.
fn material(swatch: Option<&Swatch>) -> Material {
    match swatch {
        None => Material::DEFAULT,
        Some(s) => {
            let [r, g, b, a] = s.rgba.map(|c| f32::from(c) / 255.0);
            let color = Vec3::new(r, g, b);
            Material { ka: color, kd: color, opacity: a, ..Material::DEFAULT }
        }
    }
}

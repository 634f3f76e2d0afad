//! A solution kept in a file, so that the turns of a turntable or the next
//! render of the same scene are not solved again. The file holds the
//! radiosities only, after a fingerprint of what they were solved from
//! (every patch's corners, ρ, E and the lights' first reflection D, and
//! the solver's options, FNV-1a over their bits): meshing again is quick
//! and gives the same patches, and a fingerprint that differs means a
//! stale file, solved again.
//!
//! Layout: `zline radiosity 1\n`, the fingerprint and the patch count as
//! little-endian u64, then R, G, B as little-endian f32 for every patch.

use std::path::Path;

use glam::Vec3;

use crate::patch::Patches;
use crate::Options;

const MAGIC: &[u8] = b"zline radiosity 1\n";

/// The fingerprint of `patches` solved with `options`.
pub fn fingerprint(patches: &Patches, options: &Options) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325u64;
    let mut eat = |bits: u64| {
        for byte in bits.to_le_bytes() {
            hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    for p in &patches.patches {
        for v in p.corners.iter().chain([&p.reflectance, &p.emission, &p.direct]) {
            v.to_array().iter().for_each(|c| eat(u64::from(c.to_bits())));
        }
    }
    eat(options.resolution as u64);
    eat(options.method as u64);
    eat(options.tolerance.to_bits());
    eat(options.max_steps as u64);
    eat(u64::from(options.area_shooting));
    eat(u64::from(options.lights));
    eat(u64::from(options.analytic_near));
    hash
}

/// Writes `radiosity` with its fingerprint.
pub fn save(path: &Path, fingerprint: u64, radiosity: &[Vec3]) -> std::io::Result<()> {
    let mut bytes = Vec::with_capacity(MAGIC.len() + 16 + 12 * radiosity.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&fingerprint.to_le_bytes());
    bytes.extend_from_slice(&(radiosity.len() as u64).to_le_bytes());
    for b in radiosity {
        b.to_array().iter().for_each(|c| bytes.extend_from_slice(&c.to_le_bytes()));
    }
    std::fs::write(path, bytes)
}

/// The radiosities of `count` patches kept at `path` under `fingerprint`:
/// `Ok(None)` when there is no file, `Err` saying why a file is not
/// usable (not one of these files, stale, cut short, not finite).
pub fn load(path: &Path, fingerprint: u64, count: usize) -> Result<Option<Vec<Vec3>>, String> {
    let bytes = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e.to_string()),
    };
    let rest = bytes.strip_prefix(MAGIC).ok_or("not a zline radiosity file")?;
    if rest.len() < 16 {
        return Err("cut short".into());
    }
    let word = |k: usize| u64::from_le_bytes(rest[8 * k..8 * k + 8].try_into().expect("8 bytes"));
    if word(0) != fingerprint || word(1) != count as u64 {
        return Err("solved from another scene or other settings".into());
    }
    let values = &rest[16..];
    if values.len() != 12 * count {
        return Err(format!("{} bytes of radiosity for {count} patches", values.len()));
    }
    let f = |k: usize| f32::from_le_bytes(values[4 * k..4 * k + 4].try_into().expect("4 bytes"));
    let radiosity: Vec<Vec3> = (0..count).map(|i| Vec3::new(f(3 * i), f(3 * i + 1), f(3 * i + 2))).collect();
    if radiosity.iter().any(|b| !b.is_finite()) {
        return Err("a radiosity that is not finite".into());
    }
    Ok(Some(radiosity))
}

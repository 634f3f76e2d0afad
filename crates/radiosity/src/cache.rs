//! A solution kept in a file, so that the turns of a turntable or the next
//! render of the same scene are not solved again. The file holds the
//! radiosities and the subdivision's cuts, after a fingerprint of what
//! they were solved from (every patch's corners, ρ, E and the lights'
//! first reflection D, and the solver's options, FNV-1a over their bits):
//! meshing again and replaying the cuts is quick and gives the same
//! patches, and a fingerprint that differs means a stale file, solved
//! again.
//!
//! Layout, little-endian: `zline radiosity 2\n`; the fingerprint, the
//! number of subdivision levels and the final patch count as u64; each
//! level's count of cut patches as u64 and their indices as u32; then R,
//! G, B as f32 for every final patch.

use std::path::Path;

use glam::Vec3;

use crate::patch::Patches;
use crate::Options;

const MAGIC: &[u8] = b"zline radiosity 2\n";

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
    eat(u64::from(options.subdivide));
    hash
}

/// What a cache file holds: the cuts of each subdivision level and the
/// final patches' radiosities.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Kept {
    /// The patches cut at each level ([`crate::Solution::splits`]).
    pub splits: Vec<Vec<u32>>,
    /// The final patches' radiosities.
    pub radiosity: Vec<Vec3>,
}

/// Writes `kept` under its fingerprint.
pub fn save(path: &Path, fingerprint: u64, kept: &Kept) -> std::io::Result<()> {
    let cuts: usize = kept.splits.iter().map(Vec::len).sum();
    let mut bytes =
        Vec::with_capacity(MAGIC.len() + 24 + 8 * kept.splits.len() + 4 * cuts + 12 * kept.radiosity.len());
    bytes.extend_from_slice(MAGIC);
    for word in [fingerprint, kept.splits.len() as u64, kept.radiosity.len() as u64] {
        bytes.extend_from_slice(&word.to_le_bytes());
    }
    for cut in &kept.splits {
        bytes.extend_from_slice(&(cut.len() as u64).to_le_bytes());
        cut.iter().for_each(|i| bytes.extend_from_slice(&i.to_le_bytes()));
    }
    for b in &kept.radiosity {
        b.to_array().iter().for_each(|c| bytes.extend_from_slice(&c.to_le_bytes()));
    }
    std::fs::write(path, bytes)
}

/// Reads little-endian words off the front of a byte slice.
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let (head, rest) = self.0.split_first_chunk::<N>().ok_or("cut short")?;
        self.0 = rest;
        Ok(*head)
    }
    fn u64(&mut self) -> Result<u64, String> {
        self.take().map(u64::from_le_bytes)
    }
    fn u32(&mut self) -> Result<u32, String> {
        self.take().map(u32::from_le_bytes)
    }
    fn f32(&mut self) -> Result<f32, String> {
        self.take().map(f32::from_le_bytes)
    }
}

/// What is kept at `path` under `fingerprint`: `Ok(None)` when there is
/// no file, `Err` saying why a file is not usable (not one of these
/// files, stale, cut short, not finite). The caller checks the radiosity
/// count against the patches the splits give.
pub fn load(path: &Path, fingerprint: u64) -> Result<Option<Kept>, String> {
    let bytes = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(e.to_string()),
    };
    let mut r = Reader(bytes.strip_prefix(MAGIC).ok_or("not a zline radiosity file")?);
    if r.u64()? != fingerprint {
        return Err("solved from another scene or other settings".into());
    }
    let (levels, count) = (r.u64()?, r.u64()?);
    if levels > u64::from(crate::subdivide::MAX_LEVELS) || count > crate::MAX_PATCHES as u64 {
        return Err(format!("{levels} levels and {count} patches: more than a solve makes"));
    }
    let mut kept = Kept::default();
    for _ in 0..levels {
        let n = r.u64()?;
        if n > (r.0.len() / 4) as u64 {
            return Err("cut short".into());
        }
        kept.splits.push((0..n).map(|_| r.u32()).collect::<Result<_, _>>()?);
    }
    if r.0.len() != 12 * count as usize {
        return Err(format!("{} bytes of radiosity for {count} patches", r.0.len()));
    }
    for _ in 0..count {
        let b = Vec3::new(r.f32()?, r.f32()?, r.f32()?);
        if !b.is_finite() {
            return Err("a radiosity that is not finite".into());
        }
        kept.radiosity.push(b);
    }
    Ok(Some(kept))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kept_solution_reads_back_and_damaged_files_say_why() {
        let dir = std::env::temp_dir().join(format!("zline-cache-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("kept.radiosity");
        let kept =
            Kept { splits: vec![vec![0, 3], vec![]], radiosity: vec![Vec3::ONE, Vec3::new(0.5, 0.25, 0.0)] };
        save(&path, 42, &kept).unwrap();
        assert_eq!(load(&path, 42).unwrap(), Some(kept.clone()));
        assert!(load(&path, 43).unwrap_err().contains("another scene"));
        assert_eq!(load(&dir.join("missing"), 42).unwrap(), None);
        // Cut anywhere: an error, never a panic or a huge allocation.
        let bytes = std::fs::read(&path).unwrap();
        for end in 0..bytes.len() {
            std::fs::write(&path, &bytes[..end]).unwrap();
            assert!(load(&path, 42).is_err(), "cut at {end}");
        }
        // A level claiming 2⁶⁰ cuts.
        let mut huge = MAGIC.to_vec();
        for word in [42u64, 1, 2, 1 << 60] {
            huge.extend_from_slice(&word.to_le_bytes());
        }
        std::fs::write(&path, &huge).unwrap();
        assert!(load(&path, 42).unwrap_err().contains("cut short"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

//! The built-in room: the graphics course's realistic scene, a room lit by
//! a lamp, with the objects' shadows cast onto the floor by the seed's
//! planar shadow matrix.
//!
//! Contract: [`room_scene`] returns a 960 × 540 scene inside a closed box
//! room (x and z in [−[`ROOM_HALF_WIDTH`], +[`ROOM_HALF_WIDTH`]], y in
//! [0, [`ROOM_HEIGHT`]]): a wood-plank floor, four striped-wallpaper walls
//! (all three textures procedural, made here) and a plain ceiling; a table
//! on four legs carrying a textured globe (latitude–longitude grid and
//! invented continents) on a brass stand, and a crate on the floor; a
//! pendant lamp — a cord, a four-sided pyramid shade open at the bottom and
//! an emissive bulb — with an attenuated warm point light just below the
//! bulb and a dim cool point light in a corner as fill. The camera stands
//! inside the room looking at the table, the globe and the lamp.
//!
//! Shadows are [`ShadowMode::Planar`] with the floor, object 0, as the one
//! receiving plane. Every other object casts, from both lights, but only
//! its part between the floor and a light casts (SPEC's planar shadows),
//! which the layout relies on:
//! - both lights are strictly inside the room, so a floor point and a
//!   light are joined by a segment inside the box: the walls (their
//!   projections land outside the floor, or on its edge for their bottom
//!   edge) and the ceiling (above both lights) darken nothing;
//! - the lamp's light is below the bulb and the shade's rim, so the lamp
//!   itself casts no shadow from its own light (a caster around the light
//!   would shadow the whole floor); it does cast one from the fill light;
//! - the table, its legs, the globe, its stand and the crate cast from both
//!   lights: a strong warm-light shadow and a faint fill-light one.

use std::f32::consts::{FRAC_PI_2, PI, TAU};
use std::sync::Arc;

use glam::{Mat4, Quat, Vec2, Vec3};
use zline_scene::{
    cube, uv_sphere, Camera, Interpolation, Mesh, Object, Projection, RenderSettings, Scene, ShadowMode,
    ShadowPlane, Shadows, TextureMap,
};
use zline_shading::{Attenuation, Light, Material, Sampler, ShadingMode, Texture};

/// Half the room's width and depth: the floor spans x, z in [−4, 4].
pub const ROOM_HALF_WIDTH: f32 = 4.0;
/// The room's height: the floor is at y = 0, the ceiling at y = 3.
pub const ROOM_HEIGHT: f32 = 3.0;

/// Where the lamp hangs (x, z).
const LAMP_XZ: Vec2 = Vec2::new(-1.5, -0.6);
/// The bulb's centre height and radius.
const BULB_Y: f32 = 2.42;
const BULB_RADIUS: f32 = 0.09;
/// The shade: apex and rim heights, half the rim's side.
const SHADE_APEX_Y: f32 = 2.78;
const SHADE_RIM_Y: f32 = 2.35;
const SHADE_HALF_WIDTH: f32 = 0.4;
/// The lamp's light, below the bulb's lowest point and the shade's rim.
const LAMP_LIGHT_Y: f32 = 2.30;

/// The table: centre of its footprint (x, z), top size (x, z), top height.
const TABLE_XZ: Vec2 = Vec2::new(0.4, -1.0);
const TABLE_TOP: Vec2 = Vec2::new(1.6, 1.0);
const TABLE_HEIGHT: f32 = 0.78;
const TABLE_THICKNESS: f32 = 0.06;

/// The globe's radius and its centre's height.
const GLOBE_RADIUS: f32 = 0.32;
const GLOBE_Y: f32 = 1.34;

/// The room scene (see the module doc).
pub fn room_scene() -> Scene {
    let (h, y) = (ROOM_HALF_WIDTH, ROOM_HEIGHT);
    let wallpaper = Arc::new(striped_wallpaper());
    let wall = |origin: Vec3, u: Vec3| {
        let mesh = panel("wall", origin, u, Vec3::new(0.0, y, 0.0), 8, Vec2::new(u.length(), y));
        let mesh = mesh.with_diffuse_map(map(&wallpaper));
        object(mesh, Mat4::IDENTITY, Material::plastic(Vec3::splat(0.88), 0.03, 4.0))
    };
    let floor = panel(
        "floor",
        Vec3::new(-h, 0.0, h),
        Vec3::new(2.0 * h, 0.0, 0.0),
        Vec3::new(0.0, 0.0, -2.0 * h),
        16,
        Vec2::splat(h),
    )
    .with_diffuse_map(map(&Arc::new(wood_planks())));
    let mut objects = vec![
        object(floor, Mat4::IDENTITY, Material::plastic(Vec3::splat(0.9), 0.2, 24.0)),
        // Back, front, left and right walls, each facing into the room.
        wall(Vec3::new(-h, 0.0, -h), Vec3::new(2.0 * h, 0.0, 0.0)),
        wall(Vec3::new(h, 0.0, h), Vec3::new(-2.0 * h, 0.0, 0.0)),
        wall(Vec3::new(-h, 0.0, h), Vec3::new(0.0, 0.0, -2.0 * h)),
        wall(Vec3::new(h, 0.0, -h), Vec3::new(0.0, 0.0, 2.0 * h)),
        object(
            panel(
                "ceiling",
                Vec3::new(-h, y, -h),
                Vec3::new(2.0 * h, 0.0, 0.0),
                Vec3::new(0.0, 0.0, 2.0 * h),
                4,
                Vec2::ONE,
            ),
            Mat4::IDENTITY,
            Material::plastic(Vec3::new(0.92, 0.9, 0.86), 0.0, 1.0),
        ),
    ];
    objects.extend(table());
    objects.extend(globe());
    objects.push(object(
        cube(0.6),
        Mat4::from_rotation_translation(
            Quat::from_rotation_y(25f32.to_radians()),
            Vec3::new(-2.6, 0.3, -2.3),
        ),
        Material::plastic(Vec3::new(0.55, 0.36, 0.2), 0.1, 10.0),
    ));
    objects.extend(lamp());

    let floor_plane = ShadowPlane::of_object(0, &objects[0]).expect("the floor is flat");
    Scene {
        environment: None,
        shadows: Shadows { mode: ShadowMode::Planar, planes: vec![floor_plane], ..Default::default() },
        camera: Camera {
            eye: Vec3::new(-2.0, 1.95, 3.0),
            target: Vec3::new(-0.1, 1.0, -1.0),
            up: Vec3::Y,
            projection: Projection::Perspective { fovy_degrees: 56.0, near: 0.1, far: 20.0 },
        },
        background: Vec3::splat(0.02),
        ambient: Vec3::splat(0.14),
        lights: vec![
            Light::Point {
                position: Vec3::new(LAMP_XZ.x, LAMP_LIGHT_Y, LAMP_XZ.y),
                color: Vec3::new(1.0, 0.86, 0.62) * 1.6,
                attenuation: Attenuation::new(1.0, 0.1, 0.05),
            },
            Light::Point {
                position: Vec3::new(3.2, 2.7, 3.0),
                color: Vec3::new(0.3, 0.34, 0.42),
                attenuation: Attenuation::new(1.0, 0.05, 0.02),
            },
        ],
        objects,
        settings: RenderSettings {
            width: 960,
            height: 540,
            shading: ShadingMode::Phong,
            interpolation: Interpolation::PerspectiveCorrect,
            texture_filter: None,
            ..RenderSettings::default()
        },
        fog: None,
    }
}

/// A table: a top on four legs, plain varnished wood.
fn table() -> Vec<Object> {
    let wood = Material::plastic(Vec3::new(0.42, 0.26, 0.14), 0.3, 40.0);
    let centre = Vec3::new(TABLE_XZ.x, 0.0, TABLE_XZ.y);
    let top = TABLE_TOP.extend(TABLE_THICKNESS);
    let mut parts = vec![boxed(
        Vec3::new(top.x, top.z, top.y),
        centre + Vec3::Y * (TABLE_HEIGHT - TABLE_THICKNESS / 2.0),
        wood,
    )];
    let leg = 0.07;
    let legs_height = TABLE_HEIGHT - TABLE_THICKNESS;
    let inset = TABLE_TOP / 2.0 - Vec2::splat(leg / 2.0 + 0.06);
    for (sx, sz) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let at = centre + Vec3::new(sx * inset.x, legs_height / 2.0, sz * inset.y);
        parts.push(boxed(Vec3::new(leg, legs_height, leg), at, wood));
    }
    parts
}

/// The globe on its brass stand (a foot and a pole) in the middle of the
/// table, tilted 23.4° like the Earth's axis.
fn globe() -> Vec<Object> {
    let brass = Material::plastic(Vec3::new(0.78, 0.6, 0.28), 0.8, 70.0);
    let centre = Vec3::new(TABLE_XZ.x, 0.0, TABLE_XZ.y);
    let foot = 0.04;
    let pole_bottom = TABLE_HEIGHT + foot;
    let pole_top = GLOBE_Y - GLOBE_RADIUS + 0.02;
    let mesh = globe_mesh(24, 48, GLOBE_RADIUS).with_diffuse_map(map(&Arc::new(globe_texture())));
    let tilt = Quat::from_rotation_y(-0.6) * Quat::from_rotation_z(23.4f32.to_radians());
    vec![
        boxed(Vec3::new(0.3, foot, 0.3), centre + Vec3::Y * (TABLE_HEIGHT + foot / 2.0), brass),
        boxed(
            Vec3::new(0.04, pole_top - pole_bottom, 0.04),
            centre + Vec3::Y * ((pole_bottom + pole_top) / 2.0),
            brass,
        ),
        Object {
            mesh: Arc::new(mesh),
            world_from_object: Mat4::from_rotation_translation(tilt, centre + Vec3::Y * GLOBE_Y),
            material: Some(Material::plastic(Vec3::ONE, 0.35, 40.0)),
            shading: None,
            // Closed, though its seam duplicates vertices (Mesh::is_closed
            // goes by indices).
            cull_back_faces: true,
        },
    ]
}

/// The pendant lamp: a cord from the ceiling, the pyramid shade and the
/// bulb, all above the lamp's light.
fn lamp() -> Vec<Object> {
    let at = Vec3::new(LAMP_XZ.x, 0.0, LAMP_XZ.y);
    let cord = ROOM_HEIGHT - SHADE_APEX_Y + 0.02;
    let shade = Material {
        ke: Vec3::new(0.3, 0.22, 0.1),
        ..Material::plastic(Vec3::new(0.85, 0.72, 0.5), 0.05, 8.0)
    };
    let bulb = Material { ke: Vec3::new(1.0, 0.95, 0.82), ..Material::plastic(Vec3::splat(0.3), 0.0, 1.0) };
    vec![
        boxed(
            Vec3::new(0.02, cord, 0.02),
            at + Vec3::Y * (ROOM_HEIGHT - cord / 2.0),
            Material::plastic(Vec3::splat(0.08), 0.2, 20.0),
        ),
        object(
            pyramid(SHADE_HALF_WIDTH, SHADE_APEX_Y - SHADE_RIM_Y),
            Mat4::from_translation(at + Vec3::Y * SHADE_RIM_Y),
            shade,
        ),
        object(uv_sphere(8, 12, BULB_RADIUS), Mat4::from_translation(at + Vec3::Y * BULB_Y), bulb),
    ]
}

/// A four-sided pyramid open at the bottom: its rim a square of side
/// 2·`half_width` in the XZ plane around the origin, its apex at height
/// `height` above the origin. Each side has its own vertices, so its flat
/// normal; front faces point outwards.
fn pyramid(half_width: f32, height: f32) -> Mesh {
    let w = half_width;
    let apex = Vec3::new(0.0, height, 0.0);
    let rim = [Vec3::new(-w, 0.0, -w), Vec3::new(w, 0.0, -w), Vec3::new(w, 0.0, w), Vec3::new(-w, 0.0, w)];
    let (mut positions, mut triangles) = (Vec::new(), Vec::new());
    for k in 0..4 {
        let (mut a, mut b) = (rim[k], rim[(k + 1) % 4]);
        // Outwards: the face normal points away from the axis.
        if (b - a).cross(apex - a).dot(a + b) < 0.0 {
            std::mem::swap(&mut a, &mut b);
        }
        let base = positions.len() as u32;
        positions.extend([a, b, apex]);
        triangles.push([base, base + 1, base + 2]);
    }
    Mesh::new("lamp shade", positions, None, triangles, Material::DEFAULT).expect("a valid pyramid")
}

/// A flat rectangle from `origin` spanning the edges `u` and `v` (front
/// face towards u × v), cut into `n` × `n` cells, with texture coordinates
/// running from (0, 0) at `origin` to `repeats` at the far corner.
fn panel(name: &str, origin: Vec3, u: Vec3, v: Vec3, n: u32, repeats: Vec2) -> Mesh {
    let (mut positions, mut uvs, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..=n {
        for i in 0..=n {
            let f = Vec2::new(i as f32, j as f32) / n as f32;
            positions.push(origin + u * f.x + v * f.y);
            uvs.push(f * repeats);
        }
    }
    let index = |i: u32, j: u32| j * (n + 1) + i;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    let normal = u.cross(v).normalize();
    let normals = vec![normal; positions.len()];
    Mesh::new(name, positions, Some(normals), triangles, Material::DEFAULT)
        .and_then(|m| m.with_uvs(uvs))
        .expect("a valid panel")
}

/// A sphere whose seam has its own vertices, so texture coordinates run
/// from s = 0 to s = 1 around it without wrapping back inside a triangle:
/// s follows the longitude (east to the right seen from outside), t the
/// latitude (t = 1 at the north pole, +y).
fn globe_mesh(rings: u32, segments: u32, radius: f32) -> Mesh {
    let (mut positions, mut normals, mut uvs) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..=rings {
        let theta = PI * i as f32 / rings as f32;
        for j in 0..=segments {
            let phi = TAU * j as f32 / segments as f32;
            let d = Vec3::new(theta.sin() * phi.sin(), theta.cos(), theta.sin() * phi.cos());
            positions.push(d * radius);
            normals.push(d);
            uvs.push(Vec2::new(j as f32 / segments as f32, 1.0 - i as f32 / rings as f32));
        }
    }
    let index = |i: u32, j: u32| i * (segments + 1) + j;
    let mut triangles = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            let (a, b, c, d) = (index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
            // The rows at the poles are one point: leave out the triangles
            // of no area there.
            if i + 1 < rings {
                triangles.push([a, b, c]);
            }
            if i > 0 {
                triangles.push([a, c, d]);
            }
        }
    }
    Mesh::new("globe", positions, Some(normals), triangles, Material::DEFAULT)
        .and_then(|m| m.with_uvs(uvs))
        .expect("a valid sphere")
}

/// A 128 × 128 texture of wooden floor boards, eight rows of boards along
/// s, each board half the texture long, the rows' joints staggered, each
/// board its own shade with a wavy grain.
fn wood_planks() -> Texture {
    let side = 128u32;
    let board_width = side / 8;
    texture(side, side, |x, y| {
        let row = y / board_width;
        let shift = (row * 37) % side;
        let along = (x + shift) % side;
        let board = row * 2 + along / (side / 2);
        let tone = 0.78 + 0.22 * hash(board);
        let (xf, yf) = (x as f32, y as f32);
        let grain = 0.9 + 0.1 * (xf * 0.21 + 2.5 * (yf * 0.55 + board as f32).sin()).sin();
        let joint = y.is_multiple_of(board_width) || along.is_multiple_of(side / 2);
        let k = if joint { 0.45 } else { tone * grain };
        [0.68 * k, 0.45 * k, 0.26 * k]
    })
}

/// A 64 × 64 wallpaper of vertical cream stripes with thin lines between
/// them and a small dot in the light ones.
fn striped_wallpaper() -> Texture {
    texture(64, 64, |x, y| {
        let (sx, sy) = (x % 16, y % 16);
        if sx == 0 {
            [0.62, 0.5, 0.36]
        } else if sx < 8 {
            let dot = (sx as i32 - 4).abs() + (sy as i32 - 8).abs() <= 1;
            if dot {
                [0.7, 0.55, 0.42]
            } else {
                [0.9, 0.84, 0.7]
            }
        } else {
            [0.82, 0.74, 0.6]
        }
    })
}

/// A 128 × 64 latitude–longitude globe texture: a blue ocean, invented
/// green and brown continents (a sum of waves periodic in longitude, so
/// the seam does not show), white polar caps and a 30° grid.
fn globe_texture() -> Texture {
    let (w, h) = (128u32, 64u32);
    texture(w, h, |x, y| {
        let lon = (x as f32 + 0.5) / w as f32 * TAU - PI;
        let lat = FRAC_PI_2 - (y as f32 + 0.5) / h as f32 * PI;
        let land = (2.0 * lon + 0.5).sin() * (2.0 * lat).cos()
            + 0.6 * (3.0 * lon - 1.3 * lat + 1.0).sin()
            + 0.35 * (5.0 * lon + 4.1 * lat).sin()
            + 0.25 * (7.0 * lon - 3.0 * lat + 2.0).cos();
        let step = 30f32.to_radians();
        let near_line = |a: f32, texel: f32| {
            let r = a.rem_euclid(step);
            r.min(step - r) < texel * 0.5
        };
        let (dlon, dlat) = (TAU / w as f32, PI / h as f32);
        if near_line(lon, dlon) || near_line(lat, dlat) {
            [0.78, 0.74, 0.58]
        } else if lat.abs() > 72f32.to_radians() {
            [0.95, 0.96, 0.98]
        } else if land > 0.7 {
            [0.6, 0.48, 0.3]
        } else if land > 0.2 {
            [0.32, 0.56, 0.26]
        } else {
            let deep = 1.0 - 0.25 * (0.2 - land).min(1.0);
            [0.12 * deep, 0.32 * deep, 0.66 * deep]
        }
    })
}

/// A texture of `w` × `h` texels from a colour function of (x, y), rows
/// from the top; channels in [0, 1].
fn texture(w: u32, h: u32, color: impl Fn(u32, u32) -> [f32; 3]) -> Texture {
    let rgba: Vec<u8> = (0..w * h)
        .flat_map(|i| {
            let [r, g, b] = color(i % w, i / w).map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8);
            [r, g, b, 255]
        })
        .collect();
    Texture::from_rgba8(w, h, &rgba).expect("a procedural texture of w·h·4 bytes is valid")
}

/// A number in [0, 1) from `n`, the same every run.
fn hash(n: u32) -> f32 {
    let mut x = n.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
    x ^= x >> 15;
    x = x.wrapping_mul(0x2C1B_3C6D);
    x ^= x >> 12;
    (x >> 8) as f32 / (1u32 << 24) as f32
}

fn map(texture: &Arc<Texture>) -> TextureMap {
    TextureMap {
        texture: Arc::clone(texture),
        sampler: Sampler::default(),
        alpha_blend: false,
        alpha_cutoff: None,
    }
}

/// An axis-aligned box of the given size centred at `at`.
fn boxed(size: Vec3, at: Vec3, material: Material) -> Object {
    object(cube(1.0), Mat4::from_scale_rotation_translation(size, Quat::IDENTITY, at), material)
}

fn object(mesh: Mesh, world_from_object: Mat4, material: Material) -> Object {
    let cull_back_faces = mesh.is_closed();
    Object {
        mesh: Arc::new(mesh),
        world_from_object,
        material: Some(material),
        shading: None,
        cull_back_faces,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn world_points(o: &Object) -> impl Iterator<Item = Vec3> + '_ {
        o.mesh.positions.iter().map(|&p| o.world_from_object.transform_point3(p))
    }

    fn inside_room(p: Vec3, margin: f32) -> bool {
        p.x.abs() <= ROOM_HALF_WIDTH - margin
            && p.z.abs() <= ROOM_HALF_WIDTH - margin
            && p.y >= margin
            && p.y <= ROOM_HEIGHT - margin
    }

    #[test]
    fn the_floor_receives_planar_shadows() {
        let scene = room_scene();
        assert_eq!(scene.shadows.mode, ShadowMode::Planar);
        assert_eq!(scene.shadows.planes.len(), 1);
        let plane = scene.shadows.planes[0];
        assert_eq!(plane.receiver, 0);
        assert_eq!(scene.objects[0].mesh.name, "floor");
        assert!(scene.objects[0].mesh.diffuse_map.is_some(), "a textured floor");
        // y = 0, facing up into the room.
        assert!((plane.plane - glam::Vec4::new(0.0, 1.0, 0.0, 0.0)).abs().max_element() < 1e-6, "{plane:?}");
        assert!(scene.shadows.receives(0));
        assert!((1..scene.objects.len()).all(|i| !scene.shadows.receives(i)));
    }

    #[test]
    fn walls_and_globe_are_textured_and_the_bulb_glows() {
        let scene = room_scene();
        let named = |name: &'static str| scene.objects.iter().filter(move |o| o.mesh.name == name);
        assert_eq!(named("wall").count(), 4);
        assert!(named("wall").all(|o| o.mesh.diffuse_map.is_some() && !o.mesh.uvs.is_empty()));
        let globe = named("globe").next().expect("a globe");
        assert!(globe.mesh.diffuse_map.is_some() && globe.mesh.uvs.len() == globe.mesh.positions.len());
        let bulb =
            scene.objects.iter().find(|o| o.material().ke.min_element() > 0.8).expect("an emissive bulb");
        assert_eq!(bulb.mesh.name, "sphere");
        assert!(named("lamp shade").next().is_some());
    }

    #[test]
    fn the_lights_are_inside_the_room_and_the_lamp_does_not_shadow_its_own_light() {
        let scene = room_scene();
        let positions: Vec<Vec3> = scene
            .lights
            .iter()
            .map(|l| l.position().expect("a directional light would cast the walls' shadows"))
            .collect();
        assert!(positions.iter().all(|&p| inside_room(p, 0.2)), "{positions:?}");
        // The lamp's light is the first; its bulb, shade and cord lie above it.
        let lamp = positions[0];
        for name in ["sphere", "lamp shade"] {
            let o = scene.objects.iter().find(|o| o.mesh.name == name).unwrap();
            assert!(world_points(o).all(|p| p.y > lamp.y), "{name} reaches below the lamp's light");
        }
        let hanging: Vec<_> =
            scene.objects[6..].iter().filter(|o| world_points(o).any(|p| p.y > ROOM_HEIGHT - 0.01)).collect();
        assert_eq!(hanging.len(), 1, "the lamp's cord alone reaches the ceiling");
        assert!(world_points(hanging[0]).all(|p| p.y > lamp.y), "the cord reaches below the lamp's light");
        let bulb = scene.objects.iter().find(|o| o.material().ke.min_element() > 0.8).unwrap();
        assert!(bulb.world_from_object.w_axis.truncate().distance(lamp) < 0.2, "the light is at the bulb");
        // Everything but the room's shell is inside it.
        for o in &scene.objects[6..] {
            assert!(world_points(o).all(|p| inside_room(p, 0.0)), "{} leaves the room", o.mesh.name);
        }
    }

    #[test]
    fn the_camera_is_inside_and_sees_the_globe_and_the_lamp() {
        let scene = room_scene();
        assert!(inside_room(scene.camera.eye, 0.5));
        assert_eq!((scene.settings.width, scene.settings.height), (960, 540));
        let aspect = scene.settings.width as f32 / scene.settings.height as f32;
        let clip_from_world = scene.camera.clip_from_eye(aspect) * scene.camera.eye_from_world();
        // The furniture, the globe and the lamp; not the lamp's cord, which
        // runs up out of the picture to the ceiling.
        let hanging = |o: &&Object| world_points(o).any(|p| p.y > ROOM_HEIGHT - 0.01);
        for o in scene.objects[6..].iter().filter(|o| !hanging(o)) {
            for p in world_points(o) {
                let nc = clip_from_world.project_point3(p);
                assert!(nc.abs().max_element() < 1.0, "{} out of view at {nc}", o.mesh.name);
            }
        }
    }

    #[test]
    fn the_shade_faces_outwards_and_the_globe_is_round() {
        let shade = pyramid(1.0, 1.0);
        for t in 0..shade.triangle_count() {
            let [a, b, c] = shade.triangle(t);
            let n = (b - a).cross(c - a);
            let outward = (a + b + c) / 3.0 * Vec3::new(1.0, 0.0, 1.0);
            assert!(n.dot(outward) > 0.0 && n.y > 0.0, "triangle {t}: {n}");
        }
        let globe = globe_mesh(8, 16, 2.0);
        for t in 0..globe.triangle_count() {
            let [a, b, c] = globe.triangle(t);
            let n = (b - a).cross(c - a);
            assert!(n.length() > 0.0 && n.dot(a + b + c) > 0.0, "triangle {t}");
        }
        assert!(globe.positions.iter().all(|p| (p.length() - 2.0).abs() < 1e-5));
    }
}

"""The zline Python package: its arrays against `zline render`'s PNGs byte
for byte, depth and pixel positions against the pinhole model computed by
hand, meshes from arrays and trimesh, and its errors.

Run by `cargo test` (crates/python/tests/pytest.rs), which builds the module
and sets ZLINE_BIN (the zline command of the same build) and ZLINE_REPO.
"""

import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import zline

REPO = Path(os.environ.get("ZLINE_REPO", Path(__file__).parents[3])).resolve()
BUNNY = REPO / "assets" / "ply" / "bunny_lowres.ply"
SPOT = REPO / "assets" / "obj" / "spot" / "spot.obj"
SCENE = REPO / "examples" / "scene.toml"
ZLINE_BIN = os.environ.get("ZLINE_BIN")

needs_cli = pytest.mark.skipif(not ZLINE_BIN, reason="ZLINE_BIN (the zline command) is not set")


def cli_render(tmp_path, source, *flags):
    """Runs `zline render` with every layer; returns the PNGs as arrays."""
    files = {k: tmp_path / f"{k}.png" for k in ("color", "depth", "normals", "ids")}
    cmd = [ZLINE_BIN, "render", str(source), "-o", str(files["color"]), "--depth-image", str(files["depth"]),
           "--normal-image", str(files["normals"]), "--id-image", str(files["ids"]), *flags]
    run = subprocess.run(cmd, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    out = {k: np.asarray(Image.open(p)) for k, p in files.items()}
    return out


def gray16(depth):
    """The CLI's depth PNG mapping (DepthImage::to_gray16): nearest 65535,
    farthest 1, nothing 0, rounded half up in f64."""
    drawn = ~np.isnan(depth)
    out = np.zeros(depth.shape, dtype=np.uint16)
    if not drawn.any():
        return out
    d = depth.astype(np.float64)
    near, far = d[drawn].min(), d[drawn].max()
    if far <= near:
        out[drawn] = 65535
        return out
    v = 1.0 + np.floor((far - d[drawn]) / (far - near) * 65534.0 + 0.5)
    out[drawn] = np.clip(v, 1, 65535).astype(np.uint16)
    return out


def decode_ids(rgb):
    rgb = rgb.astype(np.int32)
    return rgb[..., 0] + 256 * rgb[..., 1] + 65536 * rgb[..., 2] - 1


CASES = [
    (BUNNY, {}, []),
    (BUNNY, {"view": "iso", "projection": "ortho"}, ["--view", "iso", "--projection", "ortho"]),
    (BUNNY, {"shading": "phong", "ssaa": 2, "azimuth": 30.0}, ["--shading", "phong", "--ssaa", "2", "--azimuth", "30"]),
    (BUNNY, {"transparent": True, "view": "left"}, ["--transparent", "--view", "left"]),
    (SPOT, {"view": "front", "zoom": 1.5}, ["--view", "front", "--zoom", "1.5"]),
    (SCENE, {"allow_paths_outside": True}, ["--allow-paths-outside"]),
    (REPO / "tests" / "scenes" / "camera_orthographic.toml", {}, []),
]


@needs_cli
@pytest.mark.parametrize("source,kwargs,flags", CASES, ids=[f"{c[0].name}-{'-'.join(c[1]) or 'default'}" for c in CASES])
def test_arrays_equal_the_command_lines_pngs(tmp_path, source, kwargs, flags):
    size = (96, 72)
    png = cli_render(tmp_path, source, "--size", f"{size[0]}x{size[1]}", *flags)
    f = zline.render(source, size=size, depth=True, normals=True, ids=True, **kwargs)
    assert f.color.dtype == np.uint8 and f.color.shape == (size[1], size[0], 4 if kwargs.get("transparent") else 3)
    np.testing.assert_array_equal(f.color, png["color"])
    np.testing.assert_array_equal(f.normals_rgb, png["normals"][..., :3])
    np.testing.assert_array_equal(f.ids, decode_ids(png["ids"]))
    np.testing.assert_array_equal(gray16(f.depth), png["depth"])
    assert f.depth.dtype == np.float32 and f.ids.dtype == np.int32
    # One sample a pixel: an ID exactly where a depth is.
    if kwargs.get("ssaa", 1) == 1:
        np.testing.assert_array_equal(f.ids >= 0, ~np.isnan(f.depth))
    assert (f.ids >= 0).any() and (f.ids == -1).any()


def plane(z, half_w, half_h, x0=0.0, y0=0.0):
    """A rectangle facing −z (towards a camera at the origin looking down +z,
    OpenCV's axes), counter-clockwise as that camera sees it."""
    v = np.array([[x0 - half_w, y0 - half_h, z], [x0 + half_w, y0 - half_h, z],
                  [x0 + half_w, y0 + half_h, z], [x0 - half_w, y0 + half_h, z]], dtype=np.float64)
    f = np.array([[0, 2, 1], [0, 3, 2]])
    return v, f


def test_pinhole_depth_and_pixel_positions_by_hand():
    # An off-centre principal point and unequal focal lengths.
    w, h = 80, 60
    fx, fy, cx, cy = 70.0, 64.0, 33.25, 27.5
    K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]
    d = 4.0
    v, f = plane(d, 1.0, 0.75, x0=0.3, y0=-0.2)
    frame = zline.render(vertices=v, faces=f, size=(w, h), camera=zline.Pinhole(K, np.eye(4)), depth=True, ids=True)
    # The rectangle's edges land at u = fx·X/Z + cx, v = fy·Y/Z + cy.
    u0, u1 = fx * (0.3 - 1.0) / d + cx, fx * (0.3 + 1.0) / d + cx
    v0, v1 = fy * (-0.2 - 0.75) / d + cy, fy * (-0.2 + 0.75) / d + cy
    us, vs = np.meshgrid(np.arange(w), np.arange(h))
    inside = (us > u0 + 0.01) & (us < u1 - 0.01) & (vs > v0 + 0.01) & (vs < v1 - 0.01)
    outside = (us < u0 - 0.01) | (us > u1 + 0.01) | (vs < v0 - 0.01) | (vs > v1 + 0.01)
    # The rectangle is 2·fx/d by 1.5·fy/d pixels.
    assert inside.sum() > 700
    assert (frame.ids[inside] == 0).all() and (frame.ids[outside] == -1).all()
    # Depth: the distance to the image plane, Z = d, within f32 rounding.
    np.testing.assert_allclose(frame.depth[inside], d, rtol=2e-6)
    assert np.isnan(frame.depth[outside]).all()


def test_pinhole_depth_of_a_tilted_plane_by_hand():
    w, h = 64, 48
    fx, fy, cx, cy = 50.0, 52.0, 30.5, 25.0
    # The plane Z = 3 + 0.5·X, as a large quad; each pixel's ray (x, y, 1)
    # with x = (u − cx)/fx meets it at Z = 3 / (1 − 0.5·x).
    xs = np.array([-4.0, 4.0])
    zs = 3.0 + 0.5 * xs
    v = np.array([[xs[0], -4, zs[0]], [xs[1], -4, zs[1]], [xs[1], 4, zs[1]], [xs[0], 4, zs[0]]])
    f = np.array([[0, 2, 1], [0, 3, 2]])
    K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]
    frame = zline.render(vertices=v, faces=f, size=(w, h), camera=zline.Pinhole(K, np.eye(4), near=0.5, far=20.0),
                         depth=True)
    us, vs = np.meshgrid(np.arange(w), np.arange(h))
    want = 3.0 / (1.0 - 0.5 * (us - cx) / fx)
    assert not np.isnan(frame.depth).any()
    np.testing.assert_allclose(frame.depth, want, rtol=1e-5)


def test_an_opengl_pose_is_the_same_camera():
    v, f = plane(5.0, 1.0, 1.0)
    K = [[60.0, 0, 31.5], [0, 60.0, 23.5], [0, 0, 1]]
    # A camera turned and moved: the same pose in both conventions.
    a = math.radians(20)
    r = np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])
    cv = np.eye(4)
    cv[:3, :3], cv[:3, 3] = r, [-1.5, 0.2, 0.3]
    gl = cv @ np.diag([1.0, -1.0, -1.0, 1.0])
    a = zline.render(vertices=v, faces=f, size=(64, 48), camera=zline.Pinhole(K, cv), depth=True)
    b = zline.render(vertices=v, faces=f, size=(64, 48), camera=zline.Pinhole(K, gl, convention="opengl"), depth=True)
    np.testing.assert_array_equal(a.color, b.color)
    np.testing.assert_array_equal(a.depth, b.depth)
    assert (~np.isnan(a.depth)).sum() > 300


def test_look_at_depth_is_the_distance_along_the_view_axis():
    # A square facing +z at z = −2, seen from z = 3: depth 5 everywhere on it.
    v = np.array([[-1, -1, -2], [1, -1, -2], [1, 1, -2], [-1, 1, -2]], dtype=np.float32)
    f = np.array([[0, 1, 2], [0, 2, 3]])
    frame = zline.render(vertices=v, faces=f, size=(40, 40), camera=zline.LookAt(eye=(0, 0, 3), target=(0, 0, 0), fov=30),
                         depth=True, ids=True)
    drawn = frame.ids == 0
    assert drawn.sum() > 100
    np.testing.assert_allclose(frame.depth[drawn], 5.0, rtol=2e-6)
    ortho = zline.render(vertices=v, faces=f, size=(40, 40), camera=zline.Ortho(eye=(0, 0, 3), target=(0, 0, 0), height=4.0),
                         ids=True)
    # The square fills half the 4-unit view: rows and columns 10 to 29.
    assert (ortho.ids[10:30, 10:30] == 0).all() and (ortho.ids[:10] == -1).all() and (ortho.ids[30:] == -1).all()


def test_trimesh_meshes_and_scenes():
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box(extents=(1.0, 2.0, 1.0))
    a = zline.render(box, size=(48, 48), ids=True)
    b = zline.render(vertices=box.vertices, faces=box.faces, size=(48, 48), ids=True)
    np.testing.assert_array_equal(a.color, b.color)
    np.testing.assert_array_equal(a.ids, b.ids)
    scene = trimesh.Scene()
    scene.add_geometry(box, node_name="left", transform=trimesh.transformations.translation_matrix((-1.5, 0, 0)))
    scene.add_geometry(trimesh.creation.icosphere(subdivisions=2), node_name="right",
                       transform=trimesh.transformations.translation_matrix((1.5, 0, 0)))
    front = zline.LookAt(eye=(0, 0, 8), target=(0, 0, 0), fov=40)
    s = zline.render(scene, size=(96, 48), camera=front, ids=True)
    assert len(s.names) == 2
    assert set(np.unique(s.ids)) == {-1, 0, 1}
    # Object 0 (the box) is on the left half, object 1 on the right.
    cols = np.nonzero(s.ids == 0)[1]
    assert cols.max() < 48 <= np.nonzero(s.ids == 1)[1].min()
    # Vertex colours are used.
    colored = box.copy()
    colored.visual.vertex_colors = np.tile([255, 0, 0, 255], (len(box.vertices), 1))
    red = zline.render(colored, size=(48, 48), ids=True)
    px = red.color[red.ids >= 0]
    # Red times the light, plus a white specular term (which a vertex
    # colour does not multiply): red everywhere, green and blue only in
    # highlights.
    r, g = px[:, 0].astype(float), px[:, 1].astype(float)
    assert (r > 0).all() and (r >= g).all() and g.mean() < 0.3 * r.mean()
    grey = zline.render(box, size=(48, 48), ids=True).color[red.ids >= 0]
    assert abs(grey[:, 0].astype(float).mean() - grey[:, 1].mean()) < 1.0


def test_threads_do_not_change_the_arrays():
    a = zline.render(BUNNY, size=(96, 72), depth=True, normals=True, ids=True, threads=1)
    b = zline.render(BUNNY, size=(96, 72), depth=True, normals=True, ids=True, threads=2)
    for x, y in [(a.color, b.color), (a.depth, b.depth), (a.normals, b.normals), (a.ids, b.ids)]:
        np.testing.assert_array_equal(x, y)
    # Normals decode to near-unit vectors where something is drawn.
    n = a.normals[a.ids >= 0]
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=0.02)


def test_errors_name_the_file_and_the_problem(tmp_path):
    with pytest.raises(zline.ZlineError, match="missing.obj") as missing:
        zline.render(tmp_path / "missing.obj")
    # One line, as the command line prints it: the operating system's
    # reason once, not once more for the error's source.
    assert str(missing.value).count("os error") == 1, str(missing.value)
    bad = tmp_path / "bad.ply"
    bad.write_text("ply\nformat ascii 1.0\nelement vertex 2\nend_header\n1 2\n")
    with pytest.raises(zline.ZlineError, match="bad.ply"):
        zline.render(bad)
    v, f = plane(2.0, 1.0, 1.0)
    with pytest.raises(zline.ZlineError, match="outside"):
        zline.render(vertices=v, faces=f + 10)
    with pytest.raises(zline.ZlineError):
        zline.render(vertices=np.full((4, 3), np.nan), faces=f)
    with pytest.raises(zline.ZlineError, match="size"):
        zline.render(BUNNY, size=(0, 10))
    with pytest.raises(zline.ZlineError, match="shading"):
        zline.render(BUNNY, shading="toon")
    with pytest.raises(zline.ZlineError, match="view"):
        zline.render(BUNNY, view="sideways")
    with pytest.raises(zline.ZlineError, match="pose"):
        zline.render(BUNNY, camera=zline.Pinhole([[1, 0, 0], [0, 1, 0], [0, 0, 1]], np.diag([2.0, 1, 1, 1])))
    with pytest.raises(zline.ZlineError, match="cannot render"):
        zline.render(42)

"""zline: a CPU renderer for the classical pipeline, from Python.

``zline.render`` draws a model file (OBJ, glTF, GLB, STL, PLY, 3MF), a zline
scene file (TOML), a ``trimesh.Trimesh`` or ``trimesh.Scene``, or plain
vertex and face arrays, and returns numpy arrays: the colour image, and on
request the metric depth, the eye-space normals and an object-ID mask. It
needs no display, no GPU and no OpenGL: the renderer is zline's own
scan-conversion pipeline, compiled into this module, and the arrays are the
same, byte for byte, as the PNGs ``zline render`` writes with the same
settings.

>>> import zline
>>> frame = zline.render("bunny.ply", size=(640, 480), depth=True, ids=True)
>>> frame.color.shape, frame.color.dtype
((480, 640, 3), dtype('uint8'))

Cameras: zline's framing of the model by default (optionally along a named
``view`` with a ``projection``), or ``zline.LookAt``, ``zline.Ortho`` or
``zline.Pinhole`` (intrinsics plus a camera-to-world pose).
"""

from __future__ import annotations

import os
import warnings
from dataclasses import dataclass
from typing import Optional, Sequence, Tuple

import numpy as np

from . import _zline
from ._zline import ZlineError

__all__ = ["render", "Frame", "LookAt", "Ortho", "Pinhole", "ZlineError", "__version__"]
__version__ = _zline.__version__


@dataclass(frozen=True)
class LookAt:
    """A perspective camera at ``eye`` looking at ``target``.

    ``fov`` is the vertical field of view in degrees. ``near`` and ``far``
    (world units) bound the depth range; left out, they are fitted around
    the scene.
    """

    eye: Sequence[float]
    target: Sequence[float]
    up: Sequence[float] = (0.0, 1.0, 0.0)
    fov: float = 45.0
    near: Optional[float] = None
    far: Optional[float] = None


@dataclass(frozen=True)
class Ortho:
    """An orthographic camera at ``eye`` looking at ``target``, its view
    volume ``height`` world units high (the width follows the image's
    aspect ratio)."""

    eye: Sequence[float]
    target: Sequence[float]
    height: float
    up: Sequence[float] = (0.0, 1.0, 0.0)
    near: Optional[float] = None
    far: Optional[float] = None


@dataclass(frozen=True)
class Pinhole:
    """A pinhole camera from its intrinsics and pose.

    ``intrinsics`` is the 3×3 matrix K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]
    in pixels, in OpenCV's convention (pixel centres at integer coordinates,
    y down). ``pose`` is the 4×4 camera-to-world matrix; ``convention`` says
    its camera axes: ``"opencv"`` (x right, y down, z forward) or
    ``"opengl"`` (x right, y up, looking down −z, as pyrender's camera
    poses). A world point (X, Y, Z) in the camera's OpenCV frame lands at
    pixel (fx·X/Z + cx, fy·Y/Z + cy). Skew must be 0.
    """

    intrinsics: Sequence[Sequence[float]]
    pose: Sequence[Sequence[float]]
    convention: str = "opencv"
    near: Optional[float] = None
    far: Optional[float] = None


@dataclass
class Frame:
    """What ``render`` returns.

    - ``color``: uint8, (H, W, 3), or (H, W, 4) with ``transparent=True``
      (alpha is the pixel's coverage).
    - ``depth``: float32, (H, W): the eye-space depth (distance to the
      camera's image plane, in the scene's units) of the nearest opaque
      surface, NaN where there is none. With ``ssaa`` > 1, the nearest of
      the pixel's samples.
    - ``normals``: float32, (H, W, 3): the eye-space shading normal (x
      right, y up, z toward the viewer) decoded from the 8-bit normal image
      as byte/255·2 − 1, so within 1/255 of unit length; the background's
      black bytes decode to (−1, −1, −1). ``normals_rgb`` is the 8-bit
      image itself, as ``zline render --normal-image`` writes it.
    - ``ids``: int32, (H, W): the index of the object seen at the pixel's
      centre (in ``names``' order), −1 for the background; transparent
      objects are left out, as in the depth.
    - ``names``: the objects' names.
    """

    color: np.ndarray
    depth: Optional[np.ndarray]
    normals: Optional[np.ndarray]
    normals_rgb: Optional[np.ndarray]
    ids: Optional[np.ndarray]
    names: list

    @property
    def rgb(self) -> np.ndarray:
        """The colour's RGB channels."""
        return self.color[..., :3]


def _mesh_arrays(mesh, name: str = ""):
    """A mesh-like object as the native module's byte arrays."""
    vertices = np.ascontiguousarray(np.asarray(mesh.vertices, dtype="<f4").reshape(-1, 3))
    faces = np.asarray(mesh.faces)
    if faces.size and (faces.min() < 0 or faces.max() >= len(vertices)):
        raise ZlineError(f"{name or 'mesh'}: a face index is outside the {len(vertices)} vertices")
    faces = np.ascontiguousarray(faces.astype("<u4").reshape(-1, 3))
    normals = getattr(mesh, "_zline_normals", None)
    colors = None
    visual = getattr(mesh, "visual", None)
    if visual is not None and getattr(visual, "kind", None) == "vertex":
        rgba = np.asarray(visual.vertex_colors)
        colors = np.ascontiguousarray((rgba[:, :3].astype(np.float32) / 255.0).astype("<f4"))
    return (
        vertices.tobytes(),
        faces.tobytes(),
        None if normals is None else np.ascontiguousarray(np.asarray(normals, dtype="<f4")).tobytes(),
        None if colors is None else colors.tobytes(),
        name,
    )


class _Arrays:
    """Vertex and face arrays given directly."""

    def __init__(self, vertices, faces, normals=None, colors=None):
        self.vertices = vertices
        self.faces = faces
        self._zline_normals = normals
        if colors is not None:
            self.visual = _VertexColors(colors)


class _VertexColors:
    kind = "vertex"

    def __init__(self, colors):
        c = np.asarray(colors)
        if c.dtype != np.uint8:
            c = np.clip(np.rint(np.asarray(c, dtype=np.float64) * 255.0), 0, 255).astype(np.uint8)
        self.vertex_colors = c


def _source(source, vertices, faces, normals, colors):
    """(path, meshes) for the native call."""
    if source is None:
        if vertices is None or faces is None:
            raise ZlineError("render needs a source (a path, a trimesh object) or vertices and faces")
        return None, [_mesh_arrays(_Arrays(vertices, faces, normals, colors))]
    if vertices is not None or faces is not None:
        raise ZlineError("give a source or vertices and faces, not both")
    if isinstance(source, (str, os.PathLike)):
        return os.fspath(source), None
    # trimesh.Scene: each geometry placed by its node's transform.
    if hasattr(source, "dump") and hasattr(source, "geometry"):
        meshes = []
        for i, mesh in enumerate(source.dump()):
            name = getattr(mesh, "metadata", {}).get("name", "") or f"geometry {i}"
            meshes.append(_mesh_arrays(mesh, str(name)))
        return None, meshes
    if hasattr(source, "vertices") and hasattr(source, "faces"):
        name = getattr(source, "metadata", {}).get("name", "") if hasattr(source, "metadata") else ""
        return None, [_mesh_arrays(source, str(name or ""))]
    raise ZlineError(
        f"cannot render a {type(source).__name__}: expected a path, a trimesh.Trimesh or trimesh.Scene, "
        "or vertices and faces"
    )


_FLIP = np.diag([1.0, -1.0, -1.0, 1.0])


def _camera_args(camera) -> dict:
    if camera is None:
        return {}
    if isinstance(camera, LookAt):
        return dict(eye=tuple(camera.eye), target=tuple(camera.target), up=tuple(camera.up), fov=camera.fov,
                    near=camera.near, far=camera.far)
    if isinstance(camera, Ortho):
        return dict(eye=tuple(camera.eye), target=tuple(camera.target), up=tuple(camera.up),
                    ortho_height=camera.height, near=camera.near, far=camera.far)
    if isinstance(camera, Pinhole):
        k = np.asarray(camera.intrinsics, dtype=np.float64)
        pose = np.asarray(camera.pose, dtype=np.float64)
        if k.shape != (3, 3) or pose.shape != (4, 4):
            raise ZlineError(f"Pinhole: intrinsics must be 3×3 and pose 4×4, got {k.shape} and {pose.shape}")
        if k[0, 1] != 0.0 or k[1, 0] != 0.0 or tuple(k[2]) != (0.0, 0.0, 1.0):
            raise ZlineError("Pinhole: the intrinsic matrix must be [[fx, 0, cx], [0, fy, cy], [0, 0, 1]] (no skew)")
        if camera.convention == "opengl":
            pose = pose @ _FLIP
        elif camera.convention != "opencv":
            raise ZlineError(f"Pinhole: convention must be 'opencv' or 'opengl', got {camera.convention!r}")
        return dict(intrinsics=(k[0, 0], k[1, 1], k[0, 2], k[1, 2]), pose=[list(map(float, row)) for row in pose],
                    near=camera.near, far=camera.far)
    raise ZlineError(f"camera: expected LookAt, Ortho or Pinhole, got {type(camera).__name__}")


def render(
    source=None,
    *,
    vertices=None,
    faces=None,
    normals_in=None,
    colors=None,
    size: Tuple[int, int] = (640, 480),
    camera=None,
    view: Optional[str] = None,
    projection: Optional[str] = None,
    azimuth: Optional[float] = None,
    elevation: Optional[float] = None,
    zoom: Optional[float] = None,
    fov: Optional[float] = None,
    shading: Optional[str] = None,
    ssaa: int = 1,
    background: Optional[Sequence[float]] = None,
    transparent: bool = False,
    depth: bool = False,
    normals: bool = False,
    ids: bool = False,
    threads: Optional[int] = None,
    allow_paths_outside: bool = False,
) -> Frame:
    """Render ``source`` and return a ``Frame`` of numpy arrays.

    source: a path (model or zline scene file), a ``trimesh.Trimesh`` or
        ``trimesh.Scene``; or leave it out and give ``vertices`` (N×3) and
        ``faces`` (M×3, counter-clockwise front faces), with optional unit
        ``normals_in`` (N×3) and vertex ``colors`` (N×3 or N×4, uint8 or
        floats in [0, 1]).
    size: (width, height) in pixels.
    camera: ``LookAt``, ``Ortho`` or ``Pinhole``; by default zline frames
        the model (a scene file keeps its own camera), and ``view``
        (front, back, left, right, top, bottom, iso), ``projection``
        (perspective, ortho), ``azimuth``, ``elevation``, ``zoom`` and
        ``fov`` act as ``zline render``'s flags of the same names.
    shading: flat, gouraud or phong (default: the scene's, Gouraud).
    ssaa: n for n×n supersampling.
    background: RGB in [0, 1]; ``transparent`` gives RGBA with alpha =
        coverage.
    depth, normals, ids: also return those layers (each a frame of its
        own for normals and ids).
    threads: worker threads (default: one per core). The arrays do not
        depend on it.
    allow_paths_outside: let a scene file read models and textures outside
        its folder (``zline render --allow-paths-outside``).
    """
    path, meshes = _source(source, vertices, faces, normals_in, colors)
    width, height = (int(v) for v in size)
    args = _camera_args(camera)
    if camera is not None and any(v is not None for v in (view, projection, azimuth, elevation, zoom, fov)):
        raise ZlineError("view, projection, azimuth, elevation, zoom and fov change zline's framing: "
                         "not with an explicit camera")
    out = _zline.render(
        path, meshes, width=width, height=height, ssaa=int(ssaa), shading_mode=shading,
        background=None if background is None else tuple(float(c) for c in background),
        transparent=bool(transparent), depth=bool(depth), normals=bool(normals), ids=bool(ids),
        threads=threads, allow_paths_outside=bool(allow_paths_outside), view=view, projection=projection, azimuth=azimuth, elevation=elevation, zoom=zoom,
        **({"fov": fov} if fov is not None else {}), **args,
    )
    for w in out.get("warnings", []):
        warnings.warn(w, stacklevel=2)
    h, w, c = out["height"], out["width"], out["channels"]
    color = np.frombuffer(out["color"], dtype=np.uint8).reshape(h, w, c)
    d = np.frombuffer(out["depth"], dtype="<f4").reshape(h, w) if "depth" in out else None
    n_rgb = np.frombuffer(out["normals"], dtype=np.uint8).reshape(h, w, 3) if "normals" in out else None
    n = None if n_rgb is None else (n_rgb.astype(np.float32) / np.float32(255.0)) * np.float32(2.0) - np.float32(1.0)
    i = np.frombuffer(out["ids"], dtype="<i4").reshape(h, w) if "ids" in out else None
    return Frame(color=color, depth=d, normals=n, normals_rgb=n_rgb, ids=i, names=list(out["names"]))

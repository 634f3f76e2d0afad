#!/usr/bin/env python3
"""Writes zline's 3MF samples (this folder) and broken 3MF files (tests/bad/3mf_*.3mf, the bad-input corpus).

Run it in any folder; it writes beside itself. Standard library only.
The archives are reproducible: fixed timestamps, fixed entry order.

Samples (crates/io/tests/it/threemf.rs checks what they hold):
  cube.3mf        a unit cube with a base material, placed by a scaling and
                  translating build item (stored entries)
  assembly.3mf    a tetrahedron coloured per triangle (two base materials
                  and a translucent colour-group colour), placed directly
                  (rotated) and twice through a components object (once
                  mirrored) (deflated entries)
  production.3mf  the production extension: the root model part, named by
                  _rels/.rels as 3D/main.model, places a cube that lives in
                  3D/Objects/part.model
"""

import os
import struct
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
BAD = os.path.join(HERE, "..", "..", "tests", "bad")

CORE = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
MATERIAL = "http://schemas.microsoft.com/3dmanufacturing/material/2015/02"
PRODUCTION = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06"

CONTENT_TYPES = """<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
 <Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
 <Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>
"""


def rels(target):
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
 <Relationship Target="{target}" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>
"""


def write(path, parts, compress=zipfile.ZIP_STORED):
    """A ZIP archive of (name, text) parts, reproducibly."""
    with zipfile.ZipFile(path, "w") as z:
        for name, text in parts:
            info = zipfile.ZipInfo(name, date_time=(2024, 1, 1, 0, 0, 0))
            info.compress_type = compress
            info.external_attr = 0o644 << 16
            z.writestr(info, text)


def package(model, extra=(), target="/3D/3dmodel.model", compress=zipfile.ZIP_STORED):
    """The parts of a 3MF package holding `model` at `target`."""
    return [
        ("[Content_Types].xml", CONTENT_TYPES),
        ("_rels/.rels", rels(target)),
        (target.lstrip("/"), model),
        *extra,
    ]


def model(resources, build, attrs=""):
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xml:lang="en-US" xmlns="{CORE}"{attrs}>
 <resources>
{resources} </resources>
 <build>
{build} </build>
</model>
"""


def mesh(vertices, triangles):
    v = "".join(f'    <vertex x="{x}" y="{y}" z="{z}"/>\n' for x, y, z in vertices)
    t = "".join(
        "    <triangle " + " ".join(f'{k}="{val}"' for k, val in tri.items()) + "/>\n" for tri in triangles
    )
    return f"   <mesh>\n   <vertices>\n{v}   </vertices>\n   <triangles>\n{t}   </triangles>\n   </mesh>\n"


# A unit cube [0, 1]³, triangles counter-clockwise seen from outside.
CUBE_VERTICES = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
CUBE_FACES = [
    (0, 2, 3), (0, 3, 1),  # z = 0
    (4, 5, 7), (4, 7, 6),  # z = 1
    (0, 1, 5), (0, 5, 4),  # y = 0
    (2, 6, 7), (2, 7, 3),  # y = 1
    (0, 4, 6), (0, 6, 2),  # x = 0
    (1, 3, 7), (1, 7, 5),  # x = 1
]
CUBE_TRIANGLES = [dict(v1=a, v2=b, v3=c) for a, b, c in CUBE_FACES]

# A tetrahedron: the origin and the three unit points.
TETRA_VERTICES = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA_FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def cube_object(oid, attrs=""):
    return f'  <object id="{oid}" type="model"{attrs}>\n{mesh(CUBE_VERTICES, CUBE_TRIANGLES)}  </object>\n'


def samples():
    # cube.3mf: bounds x 10..12, y 20..23, z 30..34.
    cube = model(
        '  <basematerials id="1">\n   <base name="Orange" displaycolor="#FF8000"/>\n  </basematerials>\n'
        + cube_object(2, ' name="Cube" pid="1" pindex="0"'),
        '  <item objectid="2" transform="2 0 0 0 3 0 0 0 4 10 20 30"/>\n',
    )
    write(os.path.join(HERE, "cube.3mf"), package(cube))

    # assembly.3mf: the wedge's bottom (z = 0) and back (y = 0) faces take
    # the object's Red, its x = 0 face the translucent green colour, its
    # slanted face Blue.
    tetra = [dict(v1=a, v2=b, v3=c) for a, b, c in TETRA_FACES]
    tetra[2].update(pid=5, p1=0, p2=0, p3=0)
    tetra[3].update(pid=1, p1=1, p2=1, p3=1)
    resources = (
        '  <basematerials id="1">\n'
        '   <base name="Red" displaycolor="#FF0000"/>\n'
        '   <base name="Blue" displaycolor="#0000FFFF"/>\n'
        "  </basematerials>\n"
        '  <m:colorgroup id="5">\n   <m:color color="#00FF0080"/>\n  </m:colorgroup>\n'
        f'  <object id="2" name="Wedge" type="model" pid="1" pindex="0">\n{mesh(TETRA_VERTICES, tetra)}  </object>\n'
        '  <object id="3" name="Pair" type="model">\n'
        "   <components>\n"
        '    <component objectid="2"/>\n'
        '    <component objectid="2" transform="-1 0 0 0 1 0 0 0 1 -2 0 0"/>\n'
        "   </components>\n"
        "  </object>\n"
    )
    build = (
        '  <item objectid="3" transform="1 0 0 0 1 0 0 0 1 0 0 5"/>\n'
        '  <item objectid="2" transform="0 1 0 -1 0 0 0 0 1 10 0 0"/>\n'
    )
    assembly = model(resources, build, f' xmlns:m="{MATERIAL}" requiredextensions="m"')
    write(os.path.join(HERE, "assembly.3mf"), package(assembly), zipfile.ZIP_DEFLATED)

    # production.3mf: the part's cube, moved by (5, 0, 0) by the component
    # and (0, 0, 1) by the item: bounds x 5..6, y 0..1, z 1..2. The root
    # part's relationships name the other part, and every object, component
    # and item has its UUID, as the production extension asks.
    uuid = "00000000-0000-4000-8000-00000000000{}".format
    root = model(
        f'  <object id="1" name="Holder" type="model" p:UUID="{uuid(1)}">\n'
        "   <components>\n"
        '    <component p:path="/3D/Objects/part.model" objectid="7" transform="1 0 0 0 1 0 0 0 1 5 0 0"'
        f' p:UUID="{uuid(2)}"/>\n'
        "   </components>\n"
        "  </object>\n",
        f'  <item objectid="1" transform="1 0 0 0 1 0 0 0 1 0 0 1" p:UUID="{uuid(3)}"/>\n',
        f' xmlns:p="{PRODUCTION}" requiredextensions="p"',
    ).replace("<build>", f'<build p:UUID="{uuid(4)}">')
    part = model(cube_object(7, f' name="Part" p:UUID="{uuid(5)}"'), "", f' xmlns:p="{PRODUCTION}"')
    part_rels = rels("/3D/Objects/part.model")
    extra = [("3D/Objects/part.model", part), ("3D/_rels/main.model.rels", part_rels)]
    parts = package(root, extra, target="/3D/main.model")
    write(os.path.join(HERE, "production.3mf"), parts, zipfile.ZIP_DEFLATED)


TRIANGLE = mesh([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [dict(v1=0, v2=1, v3=2)])


def one_triangle(item='<item objectid="1"/>', vertices=None, triangles=None, attrs="", resources=""):
    m = mesh(vertices, triangles) if vertices else TRIANGLE
    return model(f'{resources}  <object id="1" type="model">\n{m}  </object>\n', f"  {item}\n", attrs)


def bad():
    """The broken files; threemf.rs lists the error each must give."""
    os.makedirs(BAD, exist_ok=True)

    def bad_file(name, parts):
        write(os.path.join(BAD, "3mf_" + name), parts)

    with open(os.path.join(BAD, "3mf_not_a_zip.3mf"), "w") as f:
        f.write("solid cube\nendsolid cube\n")
    bad_file("no_model.3mf", [("[Content_Types].xml", CONTENT_TYPES)])
    bad_file("malformed_xml.3mf", package(one_triangle().replace("</vertices>", "</vertexes>")))
    three = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    bad_file("index_out_of_range.3mf", package(one_triangle(vertices=three, triangles=[dict(v1=0, v2=1, v3=9)])))
    nan = [(0, 0, 0), (1, "NaN", 0), (0, 1, 0)]
    bad_file("nan_coordinate.3mf", package(one_triangle(vertices=nan, triangles=[dict(v1=0, v2=1, v3=2)])))
    bad_file("bad_transform.3mf", package(one_triangle('<item objectid="1" transform="1 0 0 0 1 0 0 0 1 a b c"/>')))
    bad_file("missing_object.3mf", package(one_triangle('<item objectid="7"/>')))
    bad_file(
        "self_component.3mf",
        package(model('  <object id="1">\n   <components><component objectid="1"/></components>\n  </object>\n',
                      '  <item objectid="1"/>\n')),
    )
    # Object 1 holds 2, which holds 3 … which holds 20, a triangle (each
    # defined before it is used, as the specification asks).
    chain = f'  <object id="20" type="model">\n{TRIANGLE}  </object>\n'
    chain += "".join(
        f'  <object id="{i}">\n   <components><component objectid="{i + 1}"/></components>\n  </object>\n'
        for i in range(19, 0, -1)
    )
    bad_file("deep_components.3mf", package(model(chain, '  <item objectid="1"/>\n')))
    bad_file(
        "bad_color.3mf",
        package(one_triangle(resources='  <basematerials id="2"><base name="R" displaycolor="red"/></basematerials>\n')),
    )
    bad_file(
        "property_out_of_range.3mf",
        package(one_triangle(
            vertices=three,
            triangles=[dict(v1=0, v2=1, v3=2, pid=2, p1=5)],
            resources='  <basematerials id="2"><base name="R" displaycolor="#FF0000"/></basematerials>\n',
        )),
    )
    slice_ns = "http://schemas.microsoft.com/3dmanufacturing/slice/2015/07"
    bad_file("unknown_extension.3mf", package(one_triangle(attrs=f' xmlns:s="{slice_ns}" requiredextensions="s"')))

    # A zip bomb's header: the model part declares 4 GiB (just under the
    # ZIP64 marker) uncompressed, in its local header and the central
    # directory alike.
    path = os.path.join(BAD, "3mf_zip_bomb_declared.3mf")
    write(path, package(one_triangle()), zipfile.ZIP_DEFLATED)
    data = bytearray(open(path, "rb").read())
    name = b"3D/3dmodel.model"
    # (signature, offset of the name length, of the name, of the size)
    for signature, length_at, name_at, size_at in ((b"PK\x03\x04", 26, 30, 22), (b"PK\x01\x02", 28, 46, 24)):
        at = data.find(signature)
        while at >= 0:
            (length,) = struct.unpack_from("<H", data, at + length_at)
            if data[at + name_at : at + name_at + length] == name:
                struct.pack_into("<I", data, at + size_at, 0xFFFFFFFE)
            at = data.find(signature, at + 4)
    open(path, "wb").write(bytes(data))


if __name__ == "__main__":
    samples()
    bad()

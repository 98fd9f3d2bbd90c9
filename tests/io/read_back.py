#!/usr/bin/python3
"""Reads written mesh files back with independent tools and checks them.

Every file goes through meshio (node and element counts, quad/quad8 types,
area of the corner quads in the face's plane, points on that plane, mid-side
nodes on their sides); a .msh also through the Gmsh API; an .inp is solved
by CalculiX (plane stress for CPS elements, shells for S elements) and the
node and element counts and element volumes of its .dat are compared.

Run with Debian's /usr/bin/python3, which has python3-meshio and python3-gmsh.

  read_back.py MANIFEST.json       entries written by write_sample_meshes
  read_back.py MESH NODES ELEMENTS AREA [FRAME.json]

From Python (sys.path.insert(0, "tests/io"); from read_back import read_back):
read_back(path, expected_nodes, expected_elements, expected_area, frame) with
expected_area the sum of the corner quads' areas (QualityReport::area) and
frame a dict of origin, x_dir, y_dir, normal (3 numbers each, default the
XY plane); it returns what was checked and raises ReadBackError naming the
file and the mismatch. CalculiX needs CPS elements in the plane z = 0.
"""
import json
import math
import os
import re
import subprocess
import sys
import tempfile

import meshio
import numpy as np

XY_FRAME = {"origin": [0, 0, 0], "x_dir": [1, 0, 0], "y_dir": [0, 1, 0], "normal": [0, 0, 1]}
THICKNESS = 0.1


class ReadBackError(AssertionError):
    pass


# meshio 5.0's Abaqus reader lacks these names; their node order is the
# one it already reads for S8R (corners, then side mid-points).
meshio.abaqus._abaqus.abaqus_to_meshio_type.update({"CPS8": "quad8", "S8": "quad8"})


def read_mesh(path):
    # Named, since meshio would try .msh as ANSYS first; and it ends the
    # process (sys.exit) on a file it cannot read.
    formats = {".inp": "abaqus", ".msh": "gmsh", ".vtu": "vtu"}
    try:
        return meshio.read(path, file_format=formats.get(os.path.splitext(path)[1]))
    except SystemExit:
        raise ReadBackError(f"{path}: meshio cannot read the file")


def check(condition, path, message):
    if not condition:
        raise ReadBackError(f"{path}: {message}")


def close(a, b, rel):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def face_coordinates(points, frame):
    """Points in the frame's 2-D coordinates, and their distances off its plane."""
    rel = points - np.asarray(frame["origin"], dtype=float)
    uv = np.stack([rel @ np.asarray(frame["x_dir"], float), rel @ np.asarray(frame["y_dir"], float)], axis=1)
    return uv, rel @ np.asarray(frame["normal"], float)


def corner_area(uv, corners):
    """Signed shoelace area of every element's corner quad."""
    p = uv[corners]  # elements x 4 x 2
    q = np.roll(p, -1, axis=1)
    return 0.5 * (p[:, :, 0] * q[:, :, 1] - p[:, :, 1] * q[:, :, 0]).sum(axis=1)


GAUSS_3 = (np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)]), np.array([5 / 9, 8 / 9, 5 / 9]))
CORNERS = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float)
MIDSIDES = np.array([[0, -1], [1, 0], [0, 1], [-1, 0]], dtype=float)  # side i: corner i to i + 1


def shape_derivatives(xi, eta, nodes):
    """dN/dxi and dN/deta of the bilinear (4) or serendipity (8) quad at one point."""
    d = np.zeros((2, nodes))
    for i, (a, b) in enumerate(CORNERS):
        if nodes == 4:
            d[:, i] = [a * (1 + eta * b) / 4, b * (1 + xi * a) / 4]
        else:
            d[:, i] = [a / 4 * (1 + eta * b) * (2 * xi * a + eta * b), b / 4 * (1 + xi * a) * (xi * a + 2 * eta * b)]
    if nodes == 8:
        for i, (a, b) in enumerate(MIDSIDES):
            if a == 0:
                d[:, 4 + i] = [-xi * (1 + eta * b), b / 2 * (1 - xi * xi)]
            else:
                d[:, 4 + i] = [a / 2 * (1 - eta * eta), -eta * (1 + xi * a)]
    return d


def isoparametric_areas(uv, connectivity):
    """Each element's area as a solver integrates it (3 x 3 Gauss points), and
    the least Jacobian determinant over the Gauss points."""
    p = uv[connectivity]  # elements x nodes x 2
    area = np.zeros(len(connectivity))
    least = np.full(len(connectivity), np.inf)
    points, weights = GAUSS_3
    for xi, wx in zip(points, weights):
        for eta, we in zip(points, weights):
            j = np.einsum("kn,enc->ekc", shape_derivatives(xi, eta, connectivity.shape[1]), p)
            det = j[:, 0, 0] * j[:, 1, 1] - j[:, 0, 1] * j[:, 1, 0]
            area += wx * we * det
            least = np.minimum(least, det)
    return area, least


def check_meshio(path, expected_nodes, expected_elements, expected_area, frame):
    mesh = read_mesh(path)
    check(len(mesh.points) == expected_nodes, path, f"meshio reads {len(mesh.points)} nodes, expected {expected_nodes}")
    types = {block.type for block in mesh.cells}
    check(types <= {"quad", "quad8"} and len(types) == 1, path, f"meshio reads element types {sorted(types)}")
    connectivity = np.concatenate([block.data for block in mesh.cells])
    check(len(connectivity) == expected_elements, path,
          f"meshio reads {len(connectivity)} elements, expected {expected_elements}")
    points = np.asarray(mesh.points, dtype=float)
    if points.shape[1] == 2:
        points = np.hstack([points, np.zeros((len(points), 1))])
    uv, off_plane = face_coordinates(points, frame)
    size = max(np.ptp(uv[:, 0]), np.ptp(uv[:, 1]), 1e-300)
    check(np.abs(off_plane).max() <= 1e-12 * size + 1e-12 * np.abs(points).max(), path,
          f"points lie up to {np.abs(off_plane).max():.3g} off the face's plane")
    areas = corner_area(uv, connectivity[:, :4])
    # Plane-stress .inp elements of a face seen from below run clockwise in
    # its frame (CalculiX wants them counter-clockwise from +z): one sense for all.
    reversed_ok = path.endswith(".inp") and inp_element_type(path).startswith("CPS") and frame["normal"][2] < 0
    sense = -1.0 if reversed_ok else 1.0
    check((sense * areas).min() > 0, path, f"{int((sense * areas <= 0).sum())} elements run the wrong way round "
          "in the face's plane")
    check(close(sense * areas.sum(), expected_area, 1e-12), path, f"area {areas.sum()!r}, expected {expected_area!r}")
    if connectivity.shape[1] == 8:
        # Node 4 + i sits on side i (corner i to i + 1): near that side's
        # midpoint (a 90 degree arc bulges 0.21 chords), far from the others'.
        c = uv[connectivity[:, :4]]
        side_mid = 0.5 * (c + np.roll(c, -1, axis=1))
        side_length = np.linalg.norm(np.roll(c, -1, axis=1) - c, axis=2)
        offset = np.linalg.norm(uv[connectivity[:, 4:]] - side_mid, axis=2)
        worst = (offset / side_length).max()
        check(worst < 0.4, path, f"a mid-side node lies {worst:.3g} side lengths from its side's midpoint")
    element_areas, least_jacobian = isoparametric_areas(uv, connectivity)
    check((sense * least_jacobian).min() > 0, path,
          f"{int((sense * least_jacobian <= 0).sum())} elements have a Jacobian of the wrong sign")
    return types.pop(), sense * element_areas.sum()


def check_gmsh(path, expected_nodes, expected_elements, order):
    import gmsh

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.open(path)
        tags, _, _ = gmsh.model.mesh.getNodes()
        check(len(tags) == expected_nodes, path, f"Gmsh reads {len(tags)} nodes, expected {expected_nodes}")
        types, element_tags, _ = gmsh.model.mesh.getElements(dim=2)
        want = 3 if order == 1 else 16
        check(list(types) == [want], path, f"Gmsh reads element types {list(types)}, expected [{want}]")
        count = sum(len(t) for t in element_tags)
        check(count == expected_elements, path, f"Gmsh reads {count} elements, expected {expected_elements}")
        check(gmsh.model.getEntities(2) != [], path, "Gmsh finds no surface entity")
    finally:
        gmsh.finalize()


def inp_element_type(path):
    with open(path) as f:
        for line in f:
            m = re.match(r"\*ELEMENT\s*,.*TYPE\s*=\s*(\w+)", line, re.IGNORECASE)
            if m:
                return m.group(1).upper()
    raise ReadBackError(f"{path}: no *ELEMENT card")


def fixed_nodes(path, frame):
    """Nodes within a tenth of the extent of the lowest face x, at least three: a support."""
    mesh = read_mesh(path)
    uv, _ = face_coordinates(np.asarray(mesh.points, float), frame)
    used = np.unique(np.concatenate([block.data for block in mesh.cells]).ravel())
    x = uv[used, 0]
    limit = x.min() + 0.1 * max(np.ptp(x), 1e-300)
    chosen = used[x <= limit]
    if len(chosen) < 3:
        chosen = used[np.argsort(x)[:3]]
    return [int(n) + 1 for n in chosen]


def dat_blocks(dat_path):
    """The rows of each printed block of a CalculiX .dat, keyed by the block's title."""
    blocks, title = {}, None
    with open(dat_path) as f:
        for line in f:
            text = line.strip()
            if not text:
                continue
            if text[0].isalpha():
                title = text.split("(")[0].strip()
                blocks[title] = []
            elif title is not None:
                blocks[title].append(text.split())
    return blocks


def check_calculix(path, expected_nodes, expected_elements, solver_area, frame):
    element_type = inp_element_type(path)
    shell = element_type.startswith("S")
    if not shell:
        normal = np.asarray(frame["normal"], float)
        check(abs(normal[2]) > 1 - 1e-12 and abs(frame["origin"][2]) < 1e-12, path,
              f"{element_type} elements need the global XY plane")
    fix = fixed_nodes(path, frame)
    load = np.asarray(frame["normal"] if shell else frame["x_dir"], float)
    section = (f"*SHELL SECTION, ELSET=EALL, MATERIAL=STEEL\n{THICKNESS}\n" if shell else
               f"*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n{THICKNESS}\n")
    support = "\n".join(", ".join(str(n) for n in fix[i:i + 16]) for i in range(0, len(fix), 16))
    deck = (f"*INCLUDE, INPUT={os.path.abspath(path)}\n"
            "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n*DENSITY\n7.85e-9\n" + section +
            f"*NSET, NSET=NFIX\n{support}\n*BOUNDARY\nNFIX, 1, {6 if shell else 2}\n"
            "*STEP\n*STATIC\n*DLOAD\n"
            f"EALL, GRAV, 9810., {load[0]!r}, {load[1]!r}, {load[2]!r}\n"
            "*NODE PRINT, NSET=NALL\nU\n*EL PRINT, ELSET=EALL\nEVOL\n*END STEP\n")
    with tempfile.TemporaryDirectory() as folder:
        with open(os.path.join(folder, "job.inp"), "w") as f:
            f.write(deck)
        run = subprocess.run(["ccx", "job"], cwd=folder, capture_output=True, text=True, timeout=600)
        log = run.stdout + run.stderr
        check(run.returncode == 0 and "Job finished" in log, path,
              f"CalculiX failed (exit {run.returncode}):\n{log[-2000:]}")
        check("*ERROR" not in log, path, "CalculiX reports an error:\n" +
              "\n".join(l for l in log.splitlines() if "ERROR" in l))
        blocks = dat_blocks(os.path.join(folder, "job.dat"))
    displacements = next((rows for title, rows in blocks.items() if title.startswith("displacements")), None)
    volumes = next((rows for title, rows in blocks.items() if title.startswith("volume")), None)
    check(displacements is not None and volumes is not None, path, "CalculiX printed no displacements or volumes")
    check(len(displacements) == expected_nodes, path,
          f"CalculiX prints {len(displacements)} nodes, expected {expected_nodes}")
    check(len(volumes) == expected_elements, path,
          f"CalculiX prints {len(volumes)} elements, expected {expected_elements}")
    u = np.array([[float(v) for v in row[1:4]] for row in displacements])
    check(np.isfinite(u).all() and np.abs(u).max() > 0, path, "CalculiX displacements are not finite and nonzero")
    volume = np.array([float(row[1]) for row in volumes])
    check(volume.min() > 0, path, "CalculiX finds an element of non-positive volume")
    area = volume.sum() / THICKNESS
    # The .dat prints 7 digits.
    check(close(area, solver_area, 1e-5), path, f"CalculiX area {area!r}, expected {solver_area!r}")
    return element_type


def read_back(path, expected_nodes, expected_elements, expected_area, frame=XY_FRAME):
    """Checks one mesh file with every tool that reads its format; returns what was checked."""
    element_type, solver_area = check_meshio(path, expected_nodes, expected_elements, expected_area, frame)
    checked = [element_type]
    order = 2 if element_type == "quad8" else 1
    if path.endswith(".msh"):
        check_gmsh(path, expected_nodes, expected_elements, order)
        checked.append("gmsh")
    if path.endswith(".inp"):
        checked.append("ccx " + check_calculix(path, expected_nodes, expected_elements, solver_area, frame))
    return checked


def main(argv):
    if len(argv) == 2:
        with open(argv[1]) as f:
            entries = json.load(f)
    elif len(argv) in (5, 6):
        frame = XY_FRAME
        if len(argv) == 6:
            with open(argv[5]) as f:
                frame = json.load(f)
        entries = [{"path": argv[1], "nodes": int(argv[2]), "elements": int(argv[3]), "area": float(argv[4]),
                    "frame": frame}]
    else:
        print(__doc__, file=sys.stderr)
        return 2
    failures = 0
    for e in entries:
        try:
            checked = read_back(e["path"], e["nodes"], e["elements"], e["area"], e.get("frame", XY_FRAME))
            print(f"ok   {e['path']}: {', '.join(checked)}")
        except Exception as error:  # report every file, then fail
            failures += 1
            print(f"FAIL {error}")
    print(f"{len(entries) - failures} of {len(entries)} mesh files read back")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/python3
"""_medialmesh.mesh_faces on the two halves of a plate split through its
hole (tests/data/split_plate_*.brep): one conforming mesh, the cut's nodes
once, the open sides exactly the plate's outline and hole, elements
counter-clockwise seen from their face's normal, order 2 sharing mid-side
nodes, and a clear error for bad arguments.

  test_mesh_faces.py BUILD_DIR SOURCE_DIR
"""
import math
import os
import sys
from collections import Counter

import numpy as np


def sides(elements):
    uses = Counter()
    for e in elements:
        for i in range(4):
            a, b = int(e[i]), int(e[(i + 1) % 4])
            uses[(min(a, b), max(a, b))] += 1
    return uses


def check(condition, message):
    if not condition:
        sys.exit("test_mesh_faces: " + message)


def main(build, source):
    sys.path.insert(0, os.path.join(build, "lib"))
    import _medialmesh

    breps = [open(os.path.join(source, "tests", "data", f"split_plate_{half}.brep")).read()
             for half in ("left", "right")]
    size = 0.15
    m = _medialmesh.mesh_faces(breps, size, names=["left", "right"])
    check(set(m) == {"nodes", "elements", "element_faces", "element_blocks", "element_shape", "report", "faces"},
          f"keys {set(m)}")
    nodes, elements = m["nodes"], m["elements"]
    check(nodes.shape[1] == 3 and elements.shape[1] == 4, f"shapes {nodes.shape} {elements.shape}")
    report = m["report"]
    check(report["shared_edges"] == 2, f"shared_edges {report['shared_edges']}")
    check(report["nodes"] == len(nodes) and report["quads"] == len(elements), "report counts")
    check(report["inverted"] == 0, "inverted elements")
    check(set(m["element_faces"].tolist()) == {0, 1}, "element faces")
    check(len(m["faces"]) == 2 and all(set(f) == {"report", "decomposition"} for f in m["faces"]), "per-face entries")
    check(sum(f["report"]["quads"] for f in m["faces"]) == len(elements), "per-face quads")
    check(all("frame" in f["decomposition"] for f in m["faces"]), "decomposition frames")
    gaps = np.linalg.norm(nodes[:, None, :] - nodes[None, :, :], axis=2) + np.eye(len(nodes))
    check(gaps.min() > 1e-6 * size, f"two nodes {gaps.min()} apart")
    # Counter-clockwise seen from each face's normal; the area adds up; each element's shape as reported.
    area, shapes = 0.0, []
    for e, face in zip(elements, m["element_faces"]):
        normal = np.array(m["faces"][face]["decomposition"]["frame"]["normal"])
        p = nodes[e]
        signed = 0.5 * sum(np.dot(np.cross(p[i], p[(i + 1) % 4]), normal) for i in range(4))
        check(signed > 0, f"element {e} is not counter-clockwise seen from its face's normal")
        area += signed
        # Verdict's quad shape: the least over the corners of 2 x the corner's area / (its sides squared)
        corners = [(p[(i + 1) % 4] - p[i], p[(i + 3) % 4] - p[i]) for i in range(4)]
        shapes.append(min(2 * np.dot(np.cross(a, b), normal) / (a @ a + b @ b) for a, b in corners))
    check(np.allclose(shapes, m["element_shape"], rtol=0, atol=1e-9), "element shapes")
    check(abs(min(shapes) - report["measures"]["shape"]["min"]) < 1e-9, "the least shape as reported")
    faces_area = sum(f["report"]["area"] for f in m["faces"])
    check(abs(area - faces_area) < 1e-9 * faces_area, f"area {area} against {faces_area}")
    check(abs(area - (8 - math.pi / 4)) < 5e-3 * area, f"area {area}")
    open_length = 0.0
    for (a, b), count in sides(elements).items():
        check(count <= 2, f"a side in {count} elements")
        if count == 1:
            x, y, _ = 0.5 * (nodes[a] + nodes[b])
            outer = min(abs(x), abs(x - 4), abs(y), abs(y - 2)) < 1e-9
            check(outer or abs(math.hypot(x - 2, y - 1) - 0.5) < 0.01, f"open side at ({x}, {y})")
            open_length += np.linalg.norm(nodes[a] - nodes[b])
    check(abs(open_length - (12 + math.pi)) < 0.02, f"outline {open_length}")

    q = _medialmesh.mesh_faces(breps, size, order=2)
    corners = set(q["elements"][:, :4].ravel().tolist())
    check(q["elements"].shape[1] == 8, "order 2 elements")
    check(len(q["nodes"]) == len(corners) + len(sides(q["elements"][:, :4])), "mid-side nodes not shared once")

    try:
        _medialmesh.mesh_faces(breps, size, names=["one"])
        check(False, "mismatched names accepted")
    except ValueError as e:
        check("names" in str(e), str(e))
    print(f"mesh_faces: {len(nodes)} nodes, {len(elements)} quads, min scaled Jacobian "
          f"{report['min_scaled_jacobian']:.3f}, {len(report['irregular_interior_nodes'])} irregular interior")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

#!/usr/bin/python3
"""The mesh command's files and _medialmesh.mesh's arrays read back by
independent readers: meshio for .inp, .msh and .vtu, the Gmsh API for .msh,
CalculiX for .inp. Same node and element counts and the same area as the
mesh's own report.

  test_pipeline_files.py BUILD_DIR SHARED_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from read_back import read_back  # noqa: E402


def main(build, shared):
    cli = os.path.join(build, "bin", "medialmesh")
    faces = [os.path.join(shared, "geometry", "plate_with_hole.brep"),
             os.path.join(shared, "geometry", "bracket.brep"),
             os.path.join(shared, "realcad", "faces", "occt_pumpcover_8.brep"),
             # Thin elements along concave arcs: order 2 must bend their sides less.
             os.path.join(shared, "realcad", "faces", "trimesh_featuretype_18.brep")]
    with tempfile.TemporaryDirectory() as scratch:
        for face in faces:
            name = os.path.splitext(os.path.basename(face))[0]
            for order in (1, 2):
                for ext in (".inp", ".msh", ".vtu"):
                    out = os.path.join(scratch, f"{name}.{order}{ext}")
                    run = subprocess.run([cli, "mesh", face, "--order", str(order), "-o", out, "--json"],
                                         capture_output=True, text=True)
                    if run.returncode != 0:
                        sys.exit(f"{face}: mesh failed: {run.stderr.strip()}")
                    report = json.loads(run.stdout)
                    frame = report["frame"]
                    # CalculiX takes plane-stress elements only in the plane z = 0.
                    if ext == ".inp" and (abs(frame["normal"][2]) < 1 - 1e-12 or abs(frame["origin"][2]) > 0):
                        continue
                    checked = read_back(out, report["nodes"], report["quads"], report["area"], frame)
                    print(f"{name} order {order} {ext}: {report['nodes']} nodes, {report['quads']} quads: "
                          f"{', '.join(checked)}")
        # The Python module: arrays that agree with the report.
        sys.path.insert(0, os.path.join(build, "lib"))
        import _medialmesh
        brep = open(faces[0]).read()
        for order in (1, 2):
            result = _medialmesh.mesh(brep, size=1.0, order=order)
            nodes, elements, report = result["nodes"], result["elements"], result["report"]
            assert nodes.shape == (report["nodes"], 3), nodes.shape
            assert elements.shape == (report["quads"], 4 * order), elements.shape
            assert elements.min() >= 0 and elements.max() < len(nodes)
            corners = result["nodes_2d"][elements[:, :4]]
            x, y = corners[..., 0], corners[..., 1]
            area = 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y)
            assert abs(area - report["area"]) < 1e-9 * abs(report["area"]), (area, report["area"])
            print(f"_medialmesh.mesh order {order}: {len(nodes)} nodes, {len(elements)} quads, area {area:.6f}")
        for bad in (-1.0, 0.0, float("nan")):
            try:
                _medialmesh.mesh(brep, size=bad)
            except _medialmesh.InputError as e:
                assert "size" in str(e), e
            else:
                sys.exit(f"_medialmesh.mesh accepted size {bad}")
    print("pipeline files read back")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

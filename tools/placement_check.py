#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Meshes every shared face where it lies and in four other placements
(turned about a skew axis and moved far away; mirrored by FreeCAD's
transformGeometry, which makes its plane a B-spline surface; scaled by 1e3;
converted to NURBS) with the medialmesh CLI at the size the face gets by
default in place (times 1e3 scaled),
and prints the placements whose mesh differs from the face's own: another
element or irregular-node count, or a worst shape off by 0.01 or more.
The same face should give the same mesh wherever it lies (issue 41); the
table says how far that holds. Needs freecadcmd to write the placed faces.
Takes about a minute.

    tools/placement_check.py [--cli build/bin/medialmesh] [--shared ../shared]
"""

import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Run inside freecadcmd: the faces and the folder come in the environment.
WRITE_PLACEMENTS = r'''
import os, random, sys
import FreeCAD as App
import Part
V = App.Vector
out = os.environ["PLACEMENT_OUT"]
random.seed(7)
for path in os.environ["PLACEMENT_FACES"].split(os.pathsep):
    face = Part.read(path).Faces[0]
    name = os.path.basename(path)[:-5]
    diagonal = face.BoundBox.DiagonalLength
    for kind in ("turned", "mirrored", "scaled", "nurbs"):
        axis = V(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1))
        m = App.Rotation(axis, random.uniform(0, 360)).toMatrix()
        if kind == "mirrored":
            flip = App.Matrix()
            flip.scale(-1, 1, 1)
            m = m.multiply(flip)
        if kind == "scaled":
            grow = App.Matrix()
            grow.scale(1e3, 1e3, 1e3)
            m = grow.multiply(m)
        far = 100 * diagonal * (1e3 if kind == "scaled" else 1.0)
        m.move(V(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)) * far)
        if kind == "mirrored":
            placed = face.transformGeometry(m)
        elif kind == "nurbs":
            placed = face.toNurbs()
        else:
            placed = face.copy()
            placed.transformShape(m, True)
        placed.exportBrep(os.path.join(out, f"{name}__{kind}.brep"))
'''


def mesh(cli, path, size=None):
    size_option = ["--size", repr(size)] if size else []
    run = subprocess.run([cli, "mesh", path, "--json"] + size_option, capture_output=True, text=True)
    if run.returncode:
        return {"exit": run.returncode, "error": run.stderr.strip().splitlines()[0][:200]}
    report = json.loads(run.stdout)
    return {"exit": 0, "quads": report["quads"], "irregular": report["irregular_interior"],
            "shape": report["measures"]["shape"]["min"], "size": report["size"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cli", default=os.path.join(ROOT, "build", "bin", "medialmesh"))
    parser.add_argument("--shared", default=os.path.join(ROOT, "..", "shared"))
    args = parser.parse_args()
    faces = (sorted(glob.glob(os.path.join(args.shared, "geometry", "*.brep"))) +
             sorted(glob.glob(os.path.join(args.shared, "realcad", "faces", "*.brep"))))
    with tempfile.TemporaryDirectory() as out:
        script = os.path.join(out, "write_placements.py")
        with open(script, "w") as f:
            f.write(WRITE_PLACEMENTS)
        # freecadcmd takes further arguments for files to open: the faces and
        # the folder go through the environment instead.
        env = dict(os.environ, PLACEMENT_FACES=os.pathsep.join(faces), PLACEMENT_OUT=out)
        subprocess.run(["freecadcmd", script], check=True, capture_output=True, env=env)
        written = len(glob.glob(os.path.join(out, "*__*.brep")))
        if written != 4 * len(faces):
            sys.exit(f"freecadcmd wrote {written} placed faces of {4 * len(faces)}")
        counts = {"same": 0, "counts": 0, "shape": 0, "failed": 0}
        for path in faces:
            name = os.path.basename(path)[:-5]
            own = mesh(args.cli, path)
            for kind in ("turned", "mirrored", "scaled", "nurbs"):
                # At the face's own size (its default in place): the default is a
                # twentieth of the bounding box in the face's plane, which turns with it.
                size = own.get("size", 0) * (1e3 if kind == "scaled" else 1.0)
                placed = mesh(args.cli, os.path.join(out, f"{name}__{kind}.brep"), size)
                if placed["exit"] != own["exit"]:
                    counts["failed"] += 1
                    print(f"{name} {kind}: exit {placed['exit']} where in place {own['exit']}: "
                          f"{placed.get('error', '')}")
                elif own["exit"]:
                    counts["same"] += 1
                elif (placed["quads"], placed["irregular"]) != (own["quads"], own["irregular"]):
                    counts["counts"] += 1
                    print(f"{name} {kind}: {placed['quads']} quads, {placed['irregular']} irregular "
                          f"(in place {own['quads']}, {own['irregular']})")
                elif abs(placed["shape"] - own["shape"]) >= 0.01:
                    counts["shape"] += 1
                    print(f"{name} {kind}: worst shape {placed['shape']:.3f} (in place {own['shape']:.3f})")
                else:
                    counts["same"] += 1
    total = 4 * len(faces)
    print(f"{total} placements of {len(faces)} faces: {counts['same']} mesh as in place, {counts['counts']} with "
          f"other counts, {counts['shape']} with the worst shape 0.01 or more off, {counts['failed']} "
          f"with another exit code")
    return 0


if __name__ == "__main__":
    sys.exit(main())

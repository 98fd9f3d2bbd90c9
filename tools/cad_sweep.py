#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Meshes every planar face of the CAD files this machine's packages bring
(OCCT's sample parts, FreeCAD's IDF library of electronic packages) and of
../shared/realcad/step with the medialmesh CLI at its default size, one
process per face, and prints what failed, the worst meshes (by Verdict's
shape), the counts of needles and poor quads, and the faces that
needed a fallback. Real parts nobody here modelled: run it after changing a
stage. Takes about 20 minutes on one core (big STEP files are read once per
face). With --solids, each solid's planar faces are meshed together instead
(about 10 minutes). With --size-factor F each face is meshed again at H = F x its diagonal
(its default run gives the diagonal) and that run is the one reported.

    tools/cad_sweep.py [--cli build/bin/medialmesh] [--json OUT.json] [--size-factor F | --solids] [FILE...]
"""

import argparse
import glob
import json
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_FILES = (sorted(glob.glob("/usr/share/opencascade/data/occ/*.brep")) +
                 sorted(glob.glob("/usr/share/opencascade/data/step/*")) +
                 sorted(glob.glob("/usr/share/opencascade/data/iges/*")) +
                 sorted(glob.glob("/usr/share/freecad/Mod/Idf/Idflibs/*.stp")) +
                 sorted(glob.glob(os.path.join(ROOT, "..", "shared", "realcad", "step", "*"))))


def planar_faces(cli, path):
    """The planar faces' numbers, from the CLI's own listing ([1] for a one-face file)."""
    run = subprocess.run([cli, "info", path], capture_output=True, text=True, timeout=600)
    listed = re.search(r"planar faces: ([0-9, ]+)\)", run.stderr)
    if listed:
        return [int(n) for n in listed.group(1).split(",")]
    return [1] if run.returncode == 0 else []


def mesh(cli, path, face, size_factor=None):
    """One face at the default size (a twentieth of its diagonal), or at
    size_factor x its diagonal, read off the default run's size."""
    result = mesh_at(cli, path, face, None)
    if size_factor is None or result["exit"] != 0:
        return result
    return mesh_at(cli, path, face, result["size"] / 0.05 * size_factor)


def mesh_at(cli, path, face, size):
    start = time.time()
    command = ["timeout", "300", cli, "mesh", path, "--face", str(face), "--json"]
    run = subprocess.run(command + (["--size", repr(size)] if size else []), capture_output=True, text=True)
    result = {"file": path, "face": face, "exit": run.returncode, "seconds": time.time() - start}
    if run.returncode == 0:
        report = json.loads(run.stdout)
        result.update(quads=report["quads"], min_scaled_jacobian=report["min_scaled_jacobian"],
                      min_shape=report["measures"]["shape"]["min"], mean_shape=report["measures"]["shape"]["mean"],
                      needles=report["counts"]["edge_ratio_above_10"], poor=report["counts"]["shape_below_0.3"],
                      irregular=report["irregular_interior"], notes=report.get("notes", []),
                      fallbacks=report.get("fallbacks", []),
                      size=report["size"])
    else:
        result["error"] = run.stderr.strip()
    return result


def solid_count(cli, path):
    """How many solids the file holds, from the CLI's message for one past the last."""
    run = subprocess.run([cli, "info", path, "--solid", "1000000000"], capture_output=True, text=True, timeout=600)
    held = re.search(r"the file holds ([0-9]+) solids", run.stderr)
    return int(held.group(1)) if held else 0


def mesh_solid(cli, path, solid):
    """Every planar face of one solid meshed together at a twentieth of its
    largest face's diagonal; when that stops, each face alone at that size,
    to tell a failure of meshing together from one of a face."""
    info = subprocess.run([cli, "info", path, "--solid", str(solid), "--json"], capture_output=True, text=True,
                          timeout=600)
    result = {"file": path, "solid": solid}
    if info.returncode != 0:
        # No planar face: nothing to mesh together. A face that cannot be
        # read: a failure of that face, as the face-by-face sweep reports it.
        unreadable = "has no planar face" not in info.stderr
        result.update(exit=info.returncode if unreadable else None, error=info.stderr.strip(), faces=[],
                      failing_alone=["unreadable"] if unreadable else [])
        return result
    faces = json.loads(info.stdout)["faces"]
    numbers = [int(f["face"].rsplit(" ", 1)[1]) for f in faces]
    size = max(f["diagonal"] for f in faces) / 20
    result.update(faces=numbers, size=size)
    if len(numbers) < 2:
        result["exit"] = None
        return result
    start = time.time()
    run = subprocess.run(["timeout", "600", cli, "mesh", path, "--solid", str(solid), "--size", repr(size), "--json"],
                         capture_output=True, text=True)
    result.update(exit=run.returncode, seconds=time.time() - start)
    if run.returncode == 0:
        report = json.loads(run.stdout)
        result.update(quads=report["quads"], min_shape=report["measures"]["shape"]["min"],
                      shared_edges=report["shared_edges"])
    else:
        result["error"] = run.stderr.strip()
        result["failing_alone"] = [f for f in numbers if mesh_at(cli, path, f, size)["exit"] != 0]
    return result


def sweep_solids(args):
    results = []
    for path in args.files:
        for solid in range(1, solid_count(args.cli, path) + 1):
            results.append(mesh_solid(args.cli, path, solid))
            if args.json:
                with open(args.json, "w") as out:
                    json.dump(results, out, indent=0)
    tried = [r for r in results if r["exit"] is not None]
    whole = [r for r in tried if r["exit"] == 0]
    stopped = [r for r in tried if r["exit"] != 0]
    print(f"{len(results)} solids in {len(args.files)} files, {len(tried)} with two or more planar faces: "
          f"{len(whole)} meshed whole ({sum(len(r['faces']) for r in whole)} faces), {len(stopped)} stopped "
          f"({sum(not r.get('failing_alone') for r in stopped)} of them with every face meshing alone)")
    for r in stopped:
        if r["failing_alone"] == ["unreadable"]:
            alone = "a face cannot be read"
        elif r.get("failing_alone"):
            alone = f"{len(r['faces'])} planar faces, failing alone: {r['failing_alone']}"
        else:
            alone = f"{len(r['faces'])} planar faces, each meshing alone"
        print(f"stopped: {os.path.basename(r['file'])} solid {r['solid']} ({alone}): {r['error'].splitlines()[0][:300]}")
    for r in sorted(whole, key=lambda r: r["min_shape"])[:10]:
        print(f"worst: {os.path.basename(r['file'])} solid {r['solid']} ({len(r['faces'])} faces, "
              f"{r['quads']} quads): shape {r['min_shape']:.3f}")
    return 0 if all(r.get("failing_alone") for r in stopped) else 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cli", default=os.path.join(ROOT, "build", "bin", "medialmesh"))
    parser.add_argument("--json", help="write every face's result here")
    parser.add_argument("--size-factor", type=float,
                        help="mesh at this fraction of each face's diagonal (default: 0.05, one run a face)")
    parser.add_argument("files", nargs="*", default=DEFAULT_FILES)
    parser.add_argument("--solids", action="store_true",
                        help="mesh every solid's planar faces together (mesh --solid S) instead of face by face")
    args = parser.parse_args()
    if args.solids:
        return sweep_solids(args)
    if args.size_factor is not None and not args.size_factor > 0:
        parser.error("--size-factor must be a positive number")
    results = []
    for path in args.files:
        for face in planar_faces(args.cli, path):
            results.append(mesh(args.cli, path, face, args.size_factor))
            if args.json:
                with open(args.json, "w") as out:
                    json.dump(results, out, indent=0)
    meshed = [r for r in results if r["exit"] == 0]
    failed = [r for r in results if r["exit"] != 0]
    fallback = [r for r in meshed if r["fallbacks"]]
    print(f"{len(results)} planar faces in {len(args.files)} files: {len(meshed)} meshed "
          f"({len(fallback)} by a fallback), {len(failed)} stopped")
    for bound in (0.1, 0.2, 0.3):
        print(f"min scaled Jacobian below {bound}: {sum(r['min_scaled_jacobian'] < bound for r in meshed)}; "
              f"min shape below {bound}: {sum(r['min_shape'] < bound for r in meshed)}")
    quads = sum(r["quads"] for r in meshed)
    print(f"quads {quads}: with edge ratio over 10 {sum(r['needles'] for r in meshed)}, "
          f"with shape under 0.3 {sum(r['poor'] for r in meshed)}; mean of the faces' mean shape "
          f"{sum(r['mean_shape'] for r in meshed) / max(1, len(meshed)):.3f}")
    for r in failed:
        print(f"stopped: {os.path.basename(r['file'])} face {r['face']}: {r['error'].splitlines()[0][:300]}")
    for r in sorted(meshed, key=lambda r: r["min_shape"])[:10]:
        print(f"worst: {os.path.basename(r['file'])} face {r['face']}: shape {r['min_shape']:.3f}, "
              f"scaled Jacobian {r['min_scaled_jacobian']:.3f}")
    for r in fallback:
        print(f"fallback: {os.path.basename(r['file'])} face {r['face']}: {', '.join(r['fallbacks'])}")
    return 0 if not failed else 1


if __name__ == "__main__":
    sys.exit(main())

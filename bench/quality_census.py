#!/usr/bin/python3
"""Element quality by Verdict's measures over a set of faces, as the CLI
reports it: every shared reference and real face and the single-face files
of tests/data, at 0.05 and 0.01 of each face's diagonal. With --against,
a second medialmesh binary (an older build) is run on the same meshes and
each row shows old -> new.

  quality_census.py BUILD_DIR SHARED_DIR [--against OTHER_MEDIALMESH] [--rows]

Prints the totals (quads, quads with edge ratio over 10 and with shape under
0.3, irregular interior nodes, seconds) and how many meshes' worst shape went
up or down; --rows adds one line a mesh.
"""
import argparse
import glob
import json
import os
import subprocess


def faces(shared, source):
    return (sorted(glob.glob(os.path.join(shared, "geometry", "*.brep"))) +
            sorted(glob.glob(os.path.join(shared, "realcad", "faces", "*.brep"))) +
            sorted(glob.glob(os.path.join(source, "tests", "data", "*.brep"))))


def census(cli, paths):
    rows = {}
    for path in paths:
        name = os.path.splitext(os.path.basename(path))[0]
        first = subprocess.run([cli, "mesh", path, "--json"], capture_output=True, text=True)
        if first.returncode != 0:
            rows[name] = {"error": first.stderr.strip()[-200:]}
            continue
        diagonal = 20.0 * json.loads(first.stdout)["size"]
        for factor in (0.05, 0.01):
            run = subprocess.run([cli, "mesh", path, "--json", "--size", repr(factor * diagonal)],
                                 capture_output=True, text=True)
            key = f"{name}@{factor}"
            if run.returncode != 0:
                rows[key] = {"error": run.stderr.strip()[-200:]}
                continue
            report = json.loads(run.stdout)
            measures, counts = report["measures"], report["counts"]
            rows[key] = {"quads": report["quads"], "irregular": report["irregular_interior"],
                         "scaled_jacobian": report["min_scaled_jacobian"], "shape": measures["shape"]["min"],
                         "mean_shape": measures["shape"]["mean"], "edge_ratio": measures["edge_ratio"]["max"],
                         "needles": counts["edge_ratio_above_10"], "poor": counts["shape_below_0.3"],
                         "sizes": report["relative_sizes"]["in_half_to_one_and_a_half"],
                         "seconds": report["seconds"]}
    return rows


def row_text(r):
    return (f"shape {r['shape']:.3f} mean {r['mean_shape']:.3f} SJ {r['scaled_jacobian']:.3f} "
            f"ER max {r['edge_ratio']:.1f} ER>10 {r['needles']} <0.3 {r['poor']} quads {r['quads']}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build")
    parser.add_argument("shared")
    parser.add_argument("--against")
    parser.add_argument("--rows", action="store_true")
    args = parser.parse_args()
    source = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    paths = faces(args.shared, source)
    new = census(os.path.join(args.build, "bin", "medialmesh"), paths)
    old = census(args.against, paths) if args.against else None
    keys = ("quads", "needles", "poor", "irregular")
    totals = {k: 0 for k in keys}
    old_totals = {k: 0 for k in keys}
    seconds = old_seconds = 0.0
    up = down = errors = 0
    for key, r in new.items():
        o = old.get(key, {"error": "missing"}) if old else None
        if "error" in r or (o is not None and "error" in o):
            errors += 1
            print(f"{key}: error: {r.get('error') or o.get('error')}")
            continue
        for k in keys:
            totals[k] += r[k]
            if o:
                old_totals[k] += o[k]
        seconds += r["seconds"]
        if o:
            old_seconds += o["seconds"]
            up += r["shape"] > o["shape"] + 1e-6
            down += r["shape"] < o["shape"] - 1e-6
        if args.rows:
            print(f"{key:40s} " + (f"{row_text(o)}  ->  " if o else "") + row_text(r))
    print(f"{len(new)} meshes ({errors} errors)")
    for k in keys:
        print(f"{k}: " + (f"{old_totals[k]} -> " if old else "") + f"{totals[k]}")
    print("seconds: " + (f"{old_seconds:.2f} -> " if old else "") + f"{seconds:.2f}")
    if old:
        print(f"worst shape higher on {up} meshes, lower on {down}")


if __name__ == "__main__":
    main()

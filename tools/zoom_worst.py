#!/usr/bin/python3
"""Pictures of a mesh's worst elements, zoomed in: what a FEM engineer looks
at before trusting a mesh. Meshes FILE with the CLI, reads the .vtu back with
meshio, colours every quad by its Verdict shape (from VTK's vtkMeshQuality)
and writes OUT_PREFIX_all.png (the whole face) and OUT_PREFIX_worstK.png
(a window of a few element sizes round each of the K worst elements).

  zoom_worst.py BUILD_DIR FILE OUT_PREFIX [--size H | --factor F] [--face N] [--worst K]
"""
import argparse
import json
import os
import subprocess
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkFiltersVerdict import vtkMeshQuality  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader  # noqa: E402


def shapes(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    quality = vtkMeshQuality()
    quality.SetInputData(reader.GetOutput())
    quality.SetQuadQualityMeasureToShape()
    quality.Update()
    return vtk_to_numpy(quality.GetOutput().GetCellData().GetArray("Quality"))


def draw(points, quads, shape, window, title, out):
    fig, ax = plt.subplots(figsize=(7, 7))
    polys = points[quads]
    collection = PolyCollection(polys, array=shape, cmap="RdYlGn", clim=(0, 1), edgecolors="k", linewidths=0.3)
    ax.add_collection(collection)
    (x0, x1), (y0, y1) = window
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    fig.colorbar(collection, ax=ax, shrink=0.7, label="Verdict shape")
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build")
    parser.add_argument("file")
    parser.add_argument("out")
    parser.add_argument("--size", type=float)
    parser.add_argument("--factor", type=float)
    parser.add_argument("--face")
    parser.add_argument("--worst", type=int, default=2)
    args = parser.parse_args()
    cli = os.path.join(args.build, "bin", "medialmesh")
    face = ["--face", args.face] if args.face else []
    size = args.size
    if args.factor:
        first = subprocess.run([cli, "mesh", args.file, "--json"] + face, capture_output=True, text=True, check=True)
        size = args.factor * 20.0 * json.loads(first.stdout)["size"]
    with tempfile.TemporaryDirectory() as scratch:
        vtu = os.path.join(scratch, "mesh.vtu")
        command = [cli, "mesh", args.file, "-o", vtu, "--json"] + face + (["--size", repr(size)] if size else [])
        report = json.loads(subprocess.run(command, capture_output=True, text=True, check=True).stdout)
        mesh = meshio.read(vtu)
        shape = shapes(vtu)
    # The face's own plane: its frame's axes.
    frame = report["frame"]
    origin, x_dir, y_dir = (np.array(frame[k]) for k in ("origin", "x_dir", "y_dir"))
    points = np.stack([(mesh.points - origin) @ x_dir, (mesh.points - origin) @ y_dir], axis=1)
    quads = mesh.cells_dict["quad"] if "quad" in mesh.cells_dict else mesh.cells_dict["quad8"][:, :4]
    name = os.path.basename(args.file)
    lo, hi = points.min(axis=0), points.max(axis=0)
    pad = 0.03 * (hi - lo).max()
    draw(points, quads, shape, ((lo[0] - pad, hi[0] + pad), (lo[1] - pad, hi[1] + pad)),
         f"{name}: {len(quads)} quads, shape min {shape.min():.3f} mean {shape.mean():.3f}", args.out + "_all.png")
    for k, e in enumerate(np.argsort(shape)[:args.worst]):
        corners = points[quads[e]]
        centre = corners.mean(axis=0)
        reach = max(4.0 * report["size"], 3.0 * np.ptp(corners, axis=0).max())
        sides = np.linalg.norm(corners - np.roll(corners, -1, axis=0), axis=1)
        draw(points, quads, shape, ((centre[0] - reach, centre[0] + reach), (centre[1] - reach, centre[1] + reach)),
             f"{name}: element {e + 1}, shape {shape[e]:.3f}, sides {sides.min():.3g} to {sides.max():.3g}",
             f"{args.out}_worst{k + 1}.png")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Our quality report against VTK's vtkMeshQuality (the Verdict library):
every shared reference and real face meshed by the CLI at 0.05 and 0.01 of
its diagonal, written as .vtu, read back by VTK's own reader and measured by
vtkMeshQuality. The report's least, mean and largest value of each Verdict
measure, its counts of poor elements and its worst element must be VTK's.

  test_verdict_measures.py BUILD_DIR SHARED_DIR
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

# Our JSON name -> vtkMeshQuality's setter.
MEASURES = {
    "scaled_jacobian": "SetQuadQualityMeasureToScaledJacobian",
    "shape": "SetQuadQualityMeasureToShape",
    "edge_ratio": "SetQuadQualityMeasureToEdgeRatio",
    "aspect_ratio": "SetQuadQualityMeasureToAspectRatio",
    "skew": "SetQuadQualityMeasureToSkew",
    "taper": "SetQuadQualityMeasureToTaper",
    "stretch": "SetQuadQualityMeasureToStretch",
    "condition": "SetQuadQualityMeasureToCondition",
}
HIGHER_IS_BETTER = {"scaled_jacobian", "shape", "stretch"}


def vtk_measures(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    values = {}
    for name, setter in MEASURES.items():
        quality = vtkMeshQuality()
        quality.SetInputData(grid)
        getattr(quality, setter)()
        quality.Update()
        values[name] = vtk_to_numpy(quality.GetOutput().GetCellData().GetArray("Quality")).copy()
    return grid.GetNumberOfCells(), values


def close(a, b):
    return abs(a - b) <= 1e-7 * max(1.0, abs(a), abs(b))


def check(face, factor, report, count, values):
    where = f"{face} at {factor} of the diagonal"
    assert count == report["quads"], f"{where}: VTK reads {count} cells, the report says {report['quads']} quads"
    for name, v in values.items():
        ours = report["measures"][name]
        for key, theirs in (("min", v.min()), ("mean", v.mean()), ("max", v.max())):
            assert close(ours[key], float(theirs)), f"{where}: {name} {key}: ours {ours[key]}, VTK {theirs}"
        worst = ours["worst_element"] - 1
        extreme = v.min() if name in HIGHER_IS_BETTER else v.max()
        assert close(float(v[worst]), float(extreme)), f"{where}: {name}'s worst element {worst + 1} is not VTK's"
    counts = report["counts"]
    expected = {"shape_below_0.3": int((values["shape"] < 0.3).sum()),
                "edge_ratio_above_10": int((values["edge_ratio"] > 10).sum()),
                "edge_ratio_above_5": int((values["edge_ratio"] > 5).sum()),
                "scaled_jacobian_below_0.3": int((values["scaled_jacobian"] < 0.3).sum())}
    for key, theirs in expected.items():
        assert counts[key] == theirs, f"{where}: {key}: ours {counts[key]}, VTK {theirs}"


def main(build, shared):
    cli = os.path.join(build, "bin", "medialmesh")
    faces = sorted(glob.glob(os.path.join(shared, "geometry", "*.brep"))) + \
        sorted(glob.glob(os.path.join(shared, "realcad", "faces", "*.brep")))
    assert len(faces) >= 29, f"expected the 29 shared faces, found {len(faces)}"
    checked = 0
    with tempfile.TemporaryDirectory() as scratch:
        for path in faces:
            face = os.path.splitext(os.path.basename(path))[0]
            first = subprocess.run([cli, "mesh", path, "--json"], capture_output=True, text=True, check=True)
            diagonal = 20.0 * json.loads(first.stdout)["size"]  # the default size is a twentieth of it
            for factor in (0.05, 0.01):
                out = os.path.join(scratch, f"{face}.vtu")
                run = subprocess.run([cli, "mesh", path, "--size", repr(factor * diagonal), "-o", out, "--json"],
                                     capture_output=True, text=True)
                if run.returncode != 0:
                    sys.exit(f"{face} at {factor}: mesh failed: {run.stderr.strip()}")
                report = json.loads(run.stdout)
                count, values = vtk_measures(out)
                check(face, factor, report, count, values)
                checked += 1
                print(f"{face} at {factor}: {count} quads, shape min {report['measures']['shape']['min']:.4f} "
                      f"mean {report['measures']['shape']['mean']:.4f}, edge ratio max "
                      f"{report['measures']['edge_ratio']['max']:.2f}: as vtkMeshQuality")
    print(f"{checked} meshes: every Verdict summary, count and worst element as vtkMeshQuality has it")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

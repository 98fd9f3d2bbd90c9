# SPDX-License-Identifier: LGPL-2.1-or-later
"""The compiled boundary model seen from FreeCAD.

Run inside freecadcmd by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh tests/freecad/test_boundary_module.py [BUILD_DIR [SHARED_DIR]]
"""

import glob
import os
import unittest

import numpy

import FreeCAD
import Part

import MedialMesh
import _medialmesh


GAUSS_NODES, GAUSS_WEIGHTS = numpy.polynomial.legendre.leggauss(20)


def reference_faces():
    """Return (name, path) of the shared reference faces, geometry/*.brep."""
    paths = sorted(glob.glob(os.path.join(os.environ["MEDIALMESH_SHARED"], "geometry", "*.brep")))
    return [(os.path.splitext(os.path.basename(path))[0], path) for path in paths]


def wire_circulation(wire):
    """Return the integral of x dy along a wire in the XY plane.

    Gauss-Legendre quadrature on each knot span of each edge, so the result
    is exact to rounding for lines, conics and B-splines alike.
    """
    total = 0.0
    for edge in wire.Edges:
        first, last = edge.FirstParameter, edge.LastParameter
        breaks = [first, last]
        if hasattr(edge.Curve, "getKnots"):
            breaks += [k for k in edge.Curve.getKnots() if first < k < last]
        breaks.sort()
        integral = 0.0
        for u0, u1 in zip(breaks, breaks[1:]):
            half = 0.5 * (u1 - u0)
            for node, weight in zip(GAUSS_NODES, GAUSS_WEIGHTS):
                u = u0 + half * (node + 1.0)
                integral += weight * half * edge.valueAt(u).x * edge.derivative1At(u).y
        total += -integral if edge.Orientation == "Reversed" else integral
    return total


def reference_area(face):
    """Return the area of a face in the XY plane by Green's theorem.

    Face.Area is not good enough as a reference: OCC integrates B-spline
    edges at a fixed order, which is off by 7.5e-5 relative on aerofoil3.
    """
    outer = face.OuterWire
    return sum(
        abs(wire_circulation(wire)) * (1.0 if wire.isSame(outer) else -1.0)
        for wire in face.Wires
    )


class TestCompiledModule(unittest.TestCase):

    def test_module_comes_from_the_build_dir(self):
        lib = os.path.realpath(os.path.join(os.environ["MEDIALMESH_BUILD_DIR"], "lib"))
        self.assertEqual(os.path.dirname(os.path.realpath(MedialMesh.module_path())), lib)

    def test_input_error_is_reexported(self):
        self.assertIs(MedialMesh.InputError, _medialmesh.InputError)
        self.assertTrue(issubclass(MedialMesh.InputError, ValueError))

    def test_self_check_error_is_a_runtime_error(self):
        self.assertIs(MedialMesh.SelfCheckError, _medialmesh.SelfCheckError)
        self.assertTrue(issubclass(MedialMesh.SelfCheckError, RuntimeError))
        self.assertFalse(issubclass(MedialMesh.SelfCheckError, MedialMesh.InputError))


class TestReferenceFaces(unittest.TestCase):

    def test_reference_faces_exist(self):
        self.assertGreater(len(reference_faces()), 0, os.environ["MEDIALMESH_SHARED"])

    def test_reference_area_agrees_with_freecad_on_conics(self):
        # where OCC's Face.Area is exact, it checks reference_area()
        for name, path in reference_faces():
            face = Part.read(path).Faces[0]
            if any(edge.Curve.TypeId == "Part::GeomBSplineCurve" for edge in face.Edges):
                continue
            with self.subTest(face=name):
                self.assertAlmostEqual(reference_area(face), face.Area, delta=1e-12 * face.Area)

    def test_area_and_holes(self):
        for name, path in reference_faces():
            with self.subTest(face=name):
                face = Part.read(path).Faces[0]
                model = _medialmesh.face_model(face.exportBrepToString(), name)
                area = reference_area(face)
                self.assertEqual(model["face"], name)
                self.assertAlmostEqual(model["area"], area, delta=1e-9 * area)
                self.assertEqual(model["holes"], len(face.Wires) - 1)

    def test_package_gives_the_same_model(self):
        for name, path in reference_faces():
            with self.subTest(face=name):
                face = Part.read(path).Faces[0]
                self.assertEqual(
                    MedialMesh.boundary_model(face, name),
                    _medialmesh.face_model(face.exportBrepToString(), name),
                )

    def test_file_reader_gives_the_same_model(self):
        for name, path in reference_faces():
            with self.subTest(face=name):
                face = Part.read(path).Faces[0]
                (model,) = _medialmesh.read_faces(path)
                area = reference_area(face)
                self.assertAlmostEqual(model["area"], area, delta=1e-9 * area)
                self.assertEqual(model["holes"], len(face.Wires) - 1)


class TestBadInput(unittest.TestCase):

    def test_non_planar_face(self):
        cylinder_side = Part.makeCylinder(1, 2).Faces[0]
        with self.assertRaises(MedialMesh.InputError) as caught:
            MedialMesh.boundary_model(cylinder_side, "cylinder_side")
        message = str(caught.exception)
        self.assertIn("planar", message)
        self.assertIn("cylinder_side", message)
        self.assertNotIn("\n", message)

    def test_not_a_shape(self):
        with self.assertRaises(MedialMesh.InputError):
            MedialMesh.boundary_model("not a face")


class TestMedialAxis(unittest.TestCase):
    """The medial axis through the package, on faces FreeCAD made and moved."""

    def test_plate_with_hole_in_a_moved_placement(self):
        path = dict(reference_faces())["plate_with_hole"]
        face = Part.read(path).Faces[0]
        moved = face.copy()
        moved.Placement = FreeCAD.Placement(FreeCAD.Vector(5, -3, 12), FreeCAD.Rotation(30, 40, 50))
        for candidate, name in ((face, "plate"), (moved, "moved plate")):
            axis = MedialMesh.medial_axis(candidate, name)
            junctions = [v for v in axis["vertices"] if v["kind"] == "junction"]
            self.assertEqual(len(junctions), 4)
            self.assertEqual(sum(v["kind"] == "flare" for v in axis["vertices"]), 4)
            for v in junctions:
                self.assertAlmostEqual(v["r"], 2 - 3 / (1 + 2 ** 0.5), places=9)
                # Mapped back to 3-D, every junction lies on the face itself.
                point = FreeCAD.Vector(*MedialMesh.to_3d(axis["frame"], v["x"], v["y"]))
                self.assertLess(candidate.distToShape(Part.Vertex(point))[0], 1e-9)

    def test_circle_is_one_finite_contact_vertex(self):
        face = Part.Face(Part.Wire(Part.makeCircle(2.5, FreeCAD.Vector(1, 2, 0))))
        axis = MedialMesh.medial_axis(face)
        self.assertEqual(len(axis["vertices"]), 1)
        self.assertEqual(axis["vertices"][0]["kind"], "finite_contact")
        self.assertAlmostEqual(axis["vertices"][0]["r"], 2.5, places=12)
        self.assertEqual(axis["edges"], [])

    def test_bad_face_raises_input_error(self):
        with self.assertRaises(MedialMesh.InputError):
            MedialMesh.medial_axis(Part.makeCylinder(1, 2).Faces[0], "cylinder side")

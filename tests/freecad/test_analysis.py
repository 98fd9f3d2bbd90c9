# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Analyse macro API and the parametric analysis object, in freecadcmd.

Run by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh tests/freecad/test_analysis.py [BUILD_DIR [SHARED_DIR]]
"""

import math
import os
import tempfile
import unittest

import FreeCAD
import Part
import Sketcher

import MedialMesh

PLACEMENT = FreeCAD.Placement(FreeCAD.Vector(10, -5, 3), FreeCAD.Rotation(FreeCAD.Vector(1, 2, 3), 40))


def shared_face(name):
    return Part.read(os.path.join(os.environ["MEDIALMESH_SHARED"], "geometry", name + ".brep")).Faces[0]


def junction_x(half_side, hole_radius):
    """Where a square plate's axis meets the hole's: half_side - x = x sqrt 2 - r."""
    return (half_side + hole_radius) / (1 + math.sqrt(2))


def plate_body(doc, hole_radius=1.0):
    """A 4 x 4 plate with a central hole, padded 1 in a rotated, moved body.
    Returns the body, the pad and the sketch's radius constraint index."""
    body = doc.addObject("PartDesign::Body", "Body")
    body.Placement = PLACEMENT
    sketch = body.newObject("Sketcher::SketchObject", "Sketch")
    corners = [FreeCAD.Vector(-2, -2, 0), FreeCAD.Vector(2, -2, 0), FreeCAD.Vector(2, 2, 0), FreeCAD.Vector(-2, 2, 0)]
    for a, b in zip(corners, corners[1:] + corners[:1]):
        sketch.addGeometry(Part.LineSegment(a, b))
    circle = sketch.addGeometry(Part.Circle(FreeCAD.Vector(), FreeCAD.Vector(0, 0, 1), hole_radius))
    radius = sketch.addConstraint(Sketcher.Constraint("Radius", circle, hole_radius))
    pad = body.newObject("PartDesign::Pad", "Pad")
    pad.Profile = sketch
    pad.Length = 1
    doc.recompute()
    return body, pad, radius


def top_face_name(pad):
    """The pad's top face (z = 1 in the body), whose boundary has the hole."""
    for i, face in enumerate(pad.Shape.Faces):
        if len(face.Wires) == 2 and abs(face.CenterOfMass.z - 1.0) < 1e-9:
            return f"Face{i + 1}"
    raise AssertionError("the pad has no top face with a hole")


class TestAnalyseFace(unittest.TestCase):

    def test_plate_with_hole_in_a_moved_face(self):
        face = shared_face("plate_with_hole")
        face.Placement = PLACEMENT
        result = MedialMesh.analyse_face(face)
        self.assertEqual([s.k for s in result.singularities], [1, 1, 1, 1])
        self.assertEqual(result.sum_k, result.predicted_sum_k)
        x = junction_x(2, 1)
        back = PLACEMENT.inverse()
        expected = sorted((sx * x, sy * x) for sx in (-1, 1) for sy in (-1, 1))
        found = sorted((round(p.x, 9), round(p.y, 9)) for p in (back.multVec(s.point) for s in result.singularities))
        for (ex, ey), (fx, fy) in zip(expected, found):
            self.assertAlmostEqual(ex, fx, places=8)
            self.assertAlmostEqual(ey, fy, places=8)
        for s in result.singularities:
            self.assertLess(face.distToShape(Part.Vertex(s.point))[0], 1e-7)
        # The axis lies on the face too, and its runs cover the medial edges.
        self.assertEqual(len(result.edges), 8)  # four to the corners, four round the hole
        for edge in result.edges + [run.shape for run in result.flow]:
            self.assertIsInstance(edge, Part.Edge)
            self.assertLess(face.distToShape(edge)[0], 1e-7)
        self.assertEqual(sorted({run.n for run in result.flow}), [0, 1])

    def test_merging_ellipse_pairs(self):
        face = shared_face("ellipse")
        self.assertEqual([s.k for s in MedialMesh.analyse_face(face).singularities], [-1, -1, -1, -1])
        merged = MedialMesh.analyse_face(face, merge=1.0)
        self.assertEqual([s.k for s in merged.singularities], [-2, -2])
        self.assertEqual([len(s.members) for s in merged.singularities], [2, 2])
        self.assertEqual(len(merged.unmerged), 4)

    def test_bad_input_names_the_problem(self):
        cylinder = Part.makeCylinder(1, 2)
        side = next(f for f in cylinder.Faces if isinstance(f.Surface, Part.Cylinder))
        with self.assertRaisesRegex(MedialMesh.InputError, "side.*planar"):
            MedialMesh.analyse_face(side, name="side")
        with self.assertRaisesRegex(MedialMesh.InputError, "merge factor"):
            MedialMesh.analyse_face(shared_face("square"), merge=3)
        with self.assertRaises(MedialMesh.InputError):
            MedialMesh.analyse_face("not a face")


class TestAnalysisObject(unittest.TestCase):

    def setUp(self):
        self.doc = FreeCAD.newDocument("MedialMeshAnalysis")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def check_plate(self, analysis, hole_radius):
        self.assertEqual(analysis.Status, "ok")
        self.assertEqual(list(analysis.SingularityK), [1, 1, 1, 1])
        self.assertEqual(analysis.SumK, analysis.PredictedSumK)
        self.assertEqual(len(analysis.FlowTypes), len(analysis.Shape.Edges))
        x = junction_x(2, hole_radius)
        for p in analysis.SingularityPositions:
            local = PLACEMENT.inverse().multVec(p)
            self.assertAlmostEqual(abs(local.x), x, places=7)
            self.assertAlmostEqual(abs(local.y), x, places=7)
            self.assertAlmostEqual(local.z, 1.0, places=7)  # on the pad's top face

    def test_recomputes_when_the_hole_changes(self):
        body, pad, radius = plate_body(self.doc)
        analysis = MedialMesh.make_analysis_object(self.doc, pad, top_face_name(pad))
        self.check_plate(analysis, 1.0)
        sketch = self.doc.getObject("Sketch")
        sketch.setDatum(radius, FreeCAD.Units.Quantity("0.5 mm"))
        self.doc.recompute()
        self.check_plate(analysis, 0.5)

    def test_saves_and_reopens(self):
        body, pad, radius = plate_body(self.doc)
        analysis = MedialMesh.make_analysis_object(self.doc, pad, top_face_name(pad), merge=0.5)
        path = os.path.join(tempfile.mkdtemp(), "analysis.FCStd")
        self.doc.saveAs(path)
        name = analysis.Name
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        reopened = self.doc.getObject(name)
        self.assertEqual(reopened.Type, "MedialMesh::Analysis")
        self.assertEqual(reopened.MergeFactor, 0.5)
        self.assertEqual(reopened.Source[0].Name, "Pad")
        self.check_plate(reopened, 1.0)
        reopened.touch()
        self.doc.recompute()  # the proxy came back with the document
        self.check_plate(reopened, 1.0)
        self.assertTrue(reopened.isValid())

    def test_bad_face_reports_and_keeps_freecad_going(self):
        cylinder = self.doc.addObject("Part::Cylinder", "Cylinder")
        self.doc.recompute()
        side = next(f"Face{i + 1}" for i, f in enumerate(cylinder.Shape.Faces)
                    if isinstance(f.Surface, Part.Cylinder))
        analysis = MedialMesh.make_analysis_object(self.doc, cylinder, side)
        self.assertIn("Cylinder." + side, analysis.Status)
        self.assertIn("planar", analysis.Status)
        self.assertTrue(analysis.Shape.isNull())
        self.assertEqual(list(analysis.SingularityK), [])

    def test_sketch_based_face(self):
        sketch = self.doc.addObject("Sketcher::SketchObject", "Profile")
        triangle = [FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(2, 0, 0), FreeCAD.Vector(1, math.sqrt(3), 0)]
        for a, b in zip(triangle, triangle[1:] + triangle[:1]):
            sketch.addGeometry(Part.LineSegment(a, b))
        face = self.doc.addObject("Part::Face", "Face")
        face.Sources = [sketch]
        self.doc.recompute()
        analysis = MedialMesh.make_analysis_object(self.doc, face, "Face1")
        self.assertEqual(list(analysis.SingularityK), [-1])
        centroid = FreeCAD.Vector(1, math.sqrt(3) / 3, 0)
        self.assertLess(analysis.SingularityPositions[0].distanceToPoint(centroid), 1e-9)


if __name__ == "__main__":
    unittest.main()

# SPDX-License-Identifier: LGPL-2.1-or-later
"""The quad-mesh macro API (mesh_face) and the parametric FEM mesh object
(make_mesh_object), in freecadcmd.

Run by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh tests/freecad/test_mesh_object.py [BUILD_DIR [SHARED_DIR]]
"""

import os
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import _medialmesh
import Fem
import FreeCAD
import ObjectsFem
import Part

import MedialMesh
from MedialMesh import analysis, meshing, messages
from test_analysis import PLACEMENT, plate_body, shared_face, top_face_name

TOLERANCE = 1e-7


def element_nodes(femmesh):
    """Node ids of every face element, in the FemMesh's order."""
    return [femmesh.getElementNodes(e) for e in femmesh.Faces]


def max_distance_off(face, femmesh):
    """How far the mesh's nodes stray from the face (its plane and its inside)."""
    return max(face.distToShape(Part.Vertex(p))[0] for p in femmesh.Nodes.values())


class TestMeshFace(unittest.TestCase):

    def check_quads(self, femmesh, order):
        per_element = 4 if order == 1 else 8
        self.assertGreater(femmesh.FaceCount, 0)
        self.assertEqual(femmesh.QuadrangleCount, femmesh.FaceCount)
        self.assertEqual((femmesh.TriangleCount, femmesh.VolumeCount), (0, 0))
        self.assertEqual(sorted(femmesh.Nodes), list(range(1, femmesh.NodeCount + 1)))
        self.assertEqual(sorted(femmesh.Faces), list(range(1, femmesh.FaceCount + 1)))
        for nodes in element_nodes(femmesh):
            self.assertEqual(len(nodes), per_element)

    def check_counter_clockwise(self, face, femmesh):
        """Every quad's corners run counter-clockwise seen from the face's normal."""
        normal = face.normalAt(0, 0)
        for nodes in element_nodes(femmesh):
            p = [femmesh.getNodeById(n) for n in nodes[:4]]
            area = (p[2] - p[0]).cross(p[3] - p[1]).dot(normal) / 2
            self.assertGreater(area, 0)

    def test_plate_first_order_in_a_moved_face(self):
        face = shared_face("plate_with_hole")
        face.Placement = PLACEMENT
        size = 0.2
        result = MedialMesh.mesh_face(face, size=size)
        self.assertIsInstance(result.femmesh, Fem.FemMesh)
        self.check_quads(result.femmesh, 1)
        self.check_counter_clockwise(face, result.femmesh)
        quads = result.femmesh.FaceCount
        # about one quad per size x size of area
        self.assertGreater(quads, 0.5 * face.Area / size ** 2)
        self.assertLess(quads, 2.0 * face.Area / size ** 2)
        self.assertLess(max_distance_off(face, result.femmesh), TOLERANCE)
        # the mesh covers the face: its quads' areas add up to the face's (less the hole's chords)
        total = 0.0
        for nodes in element_nodes(result.femmesh):
            p = [result.femmesh.getNodeById(n) for n in nodes]
            total += (p[2] - p[0]).cross(p[3] - p[1]).Length / 2
        self.assertAlmostEqual(total / face.Area, 1.0, delta=0.01)

        q = result.quality
        self.assertEqual((q["quads"], q["nodes"]), (quads, result.femmesh.NodeCount))
        self.assertGreater(q["min_scaled_jacobian"], 0.5)
        self.assertGreaterEqual(q["mean_scaled_jacobian"], q["min_scaled_jacobian"])
        # the Verdict measures a user reads: the plate's quads are near squares
        self.assertGreater(q["min_shape"], 0.5)
        self.assertGreaterEqual(q["mean_shape"], q["min_shape"])
        self.assertLess(q["max_edge_ratio"], 3.0)
        self.assertEqual((q["poor_shape"], q["needles"]), (0, 0))
        self.assertLess(face.distToShape(Part.Vertex(q["worst_position"]))[0], TOLERANCE)
        self.assertEqual(q["irregular_nodes"], 4)  # the four 5-valent nodes of the k = +1 singularities
        self.assertGreater(q["seconds"], 0.0)
        self.assertEqual(sorted(k for _, k in result.singularities), [1, 1, 1, 1])
        for point, _ in result.singularities:
            self.assertLess(face.distToShape(Part.Vertex(point))[0], TOLERANCE)
        self.assertEqual(len(result.splits), 4)
        for split in result.splits:
            self.assertLess(face.distToShape(split)[0], TOLERANCE)
        # the frame lies on the face, facing its way
        self.assertLess(face.Surface.projectPoint(result.placement.Base, "LowerDistance"), TOLERANCE)
        normal = result.placement.Rotation.multVec(FreeCAD.Vector(0, 0, 1))
        self.assertLess(normal.distanceToPoint(face.normalAt(0, 0)), 1e-9)
        self.assertEqual(len(result.per_face), 1)
        self.assertEqual(result.per_face[0].quality["quads"], quads)

    def test_size_sets_the_count(self):
        face = shared_face("plate_with_hole")
        coarse = MedialMesh.mesh_face(face, size=0.4).femmesh.FaceCount
        fine = MedialMesh.mesh_face(face, size=0.1).femmesh.FaceCount
        self.assertGreater(fine / coarse, 8)  # four times as many per halving of the size
        self.assertLess(fine / coarse, 32)
        automatic = MedialMesh.mesh_face(face).femmesh.FaceCount
        explicit = MedialMesh.mesh_face(face, size=face.BoundBox.DiagonalLength / 20).femmesh.FaceCount
        self.assertEqual(automatic, explicit)

    def test_plate_second_order(self):
        face = shared_face("plate_with_hole")
        first = MedialMesh.mesh_face(face, size=0.2)
        result = MedialMesh.mesh_face(face, size=0.2, order=2)
        femmesh = result.femmesh
        self.check_quads(femmesh, 2)
        self.check_counter_clockwise(face, femmesh)
        self.assertEqual(femmesh.FaceCount, first.femmesh.FaceCount)
        # the corner nodes of the 4-node mesh, and one node per element side, shared by the side's two quads
        sides = {frozenset((nodes[k], nodes[(k + 1) % 4])) for nodes in element_nodes(femmesh) for k in range(4)}
        self.assertEqual(femmesh.NodeCount, first.femmesh.NodeCount + len(sides))
        self.assertLess(max_distance_off(face, femmesh), TOLERANCE)
        # FreeCAD's order: mid-side node k of the side from corner k to corner k + 1
        worst = 0.0
        for nodes in element_nodes(femmesh):
            p = [femmesh.getNodeById(n) for n in nodes]
            for k in range(4):
                side = p[k].distanceToPoint(p[(k + 1) % 4])
                worst = max(worst, p[4 + k].distanceToPoint((p[k] + p[(k + 1) % 4]) * 0.5) / side)
        self.assertLess(worst, 0.05)  # only the hole's sides bow, by far less than this

        # CalculiX's S8 through FreeCAD's writer, read back by meshio as 8-node quads
        import meshio
        import numpy

        folder = tempfile.mkdtemp()
        path = os.path.join(folder, "plate.inp")
        femmesh.write(path)
        with open(path) as f:
            text = f.read()
        self.assertIn("TYPE=S8,", text)
        with open(os.path.join(folder, "plate_s8r.inp"), "w") as f:
            f.write(text.replace("TYPE=S8,", "TYPE=S8R,"))  # meshio knows S8 by its reduced twin only
        read = meshio.read(os.path.join(folder, "plate_s8r.inp"))
        self.assertEqual([block.type for block in read.cells], ["quad8"])
        cells = read.cells[0].data
        self.assertEqual(len(cells), femmesh.FaceCount)
        points = read.points
        middle = (points[cells[:, :4]] + points[numpy.roll(cells[:, :4], -1, axis=1)]) / 2
        offset = numpy.linalg.norm(points[cells[:, 4:]] - middle, axis=2).max()
        self.assertLess(offset, 0.05 * 0.2)

    def test_ninety_thousand_quads_into_a_femmesh(self):
        face = shared_face("plate_with_hole")
        mesh = _medialmesh.mesh(face.exportBrepToString(), 0.0107, order=1)
        start = time.perf_counter()
        femmesh = meshing.build_femmesh(mesh["nodes"], mesh["elements"])
        seconds = time.perf_counter() - start
        sys.__stdout__.write(f"\n{femmesh.FaceCount} quads into a FemMesh in {seconds:.2f} s\n")
        self.assertGreater(femmesh.FaceCount, 85000)
        self.assertEqual(femmesh.NodeCount, len(mesh["nodes"]))
        self.assertLess(seconds, 3.0)

    def test_bad_input_names_the_problem(self):
        cylinder = Part.makeCylinder(1, 2)
        side = next(f for f in cylinder.Faces if isinstance(f.Surface, Part.Cylinder))
        with self.assertRaisesRegex(MedialMesh.InputError, "side.*planar"):
            MedialMesh.mesh_face(side, name="side")
        with self.assertRaisesRegex(MedialMesh.InputError, "order"):
            MedialMesh.mesh_face(shared_face("square"), order=3)
        with self.assertRaisesRegex(MedialMesh.InputError, "merge factor"):
            MedialMesh.mesh_face(shared_face("square"), merge=3)
        with self.assertRaisesRegex(MedialMesh.InputError, "Part.Face"):
            MedialMesh.mesh_face("not a face")

    def test_no_two_nodes_on_one_point(self):
        # The bracket's right hole has its seam vertex at a block corner,
        # where the mesher once put two nodes (CalculiX stops on that).
        import numpy

        femmesh = MedialMesh.mesh_face(shared_face("bracket")).femmesh
        points = numpy.array([[p.x, p.y, p.z] for p in femmesh.Nodes.values()])
        rounded = numpy.round(points / numpy.ptp(points, axis=0).max(), 9)
        self.assertEqual(len(numpy.unique(rounded, axis=0)), len(points))

    def test_two_faces_sharing_an_edge_mesh_as_one(self):
        # Two halves of a rectangle sharing the edge x = 1.
        left, right = Part.makePlane(1, 1), Part.makePlane(1, 1, FreeCAD.Vector(1, 0, 0))
        result = MedialMesh.mesh_face([left, right], size=0.25)
        self.check_quads(result.femmesh, 1)
        self.assertEqual(len(result.per_face), 2)
        check_conforming(self, result.femmesh, Part.makePlane(2, 1).Edges)
        shared = [p for p in result.femmesh.Nodes.values() if abs(p.x - 1) < TOLERANCE]
        self.assertEqual(len(shared), 5)  # 4 intervals along the cut, its nodes once


def check_conforming(test, femmesh, outline):
    """One mesh: no two nodes on one point, every element side in two
    elements or on the `outline` (the edges bounding the faces meshed)."""
    points = list(femmesh.Nodes.values())
    test.assertEqual(len(points), len({(round(p.x, 9), round(p.y, 9), round(p.z, 9)) for p in points}))
    sides = {}
    for element in femmesh.Faces:
        corners = list(femmesh.getElementNodes(element)[:4])
        for a, b in zip(corners, corners[1:] + corners[:1]):
            sides[frozenset((a, b))] = sides.get(frozenset((a, b)), 0) + 1
    outline = Part.Compound(outline)
    for side, count in sides.items():
        a, b = (femmesh.Nodes[n] for n in side)
        on_outline = outline.distToShape(Part.Vertex((a + b) * 0.5))[0] < 1e-6
        test.assertEqual(count, 1 if on_outline else 2, f"side at {(a + b) * 0.5}")


class TestMeshObject(unittest.TestCase):

    def setUp(self):
        self.doc = FreeCAD.newDocument("MedialMeshQuadMesh")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def check(self, mesh_obj, face, order=1):
        """The object is meshed, holds only quads on the face, and its results agree."""
        self.assertEqual(mesh_obj.Status, "ok")
        self.assertEqual(mesh_obj.Type, "MedialMesh::QuadMesh")
        femmesh = mesh_obj.FemMesh
        self.assertEqual(femmesh.QuadrangleCount, femmesh.FaceCount)
        self.assertEqual(femmesh.TriangleCount, 0)
        per_element = 4 if order == 1 else 8
        self.assertTrue(all(len(nodes) == per_element for nodes in element_nodes(femmesh)))
        self.assertEqual((mesh_obj.QuadCount, mesh_obj.NodeCount), (femmesh.FaceCount, femmesh.NodeCount))
        self.assertGreater(mesh_obj.MinScaledJacobian, 0.3)
        self.assertGreaterEqual(mesh_obj.MeanScaledJacobian, mesh_obj.MinScaledJacobian)
        self.assertGreater(mesh_obj.MinShape, 0.0)
        self.assertGreaterEqual(mesh_obj.MeanShape, mesh_obj.MinShape)
        self.assertGreaterEqual(mesh_obj.MaxEdgeRatio, 1.0)
        self.assertLessEqual(mesh_obj.PoorShapeCount, mesh_obj.QuadCount)
        self.assertLessEqual(mesh_obj.NeedleCount, mesh_obj.QuadCount)
        self.assertLess(face.distToShape(Part.Vertex(mesh_obj.WorstElementPosition))[0], TOLERANCE)
        self.assertGreater(mesh_obj.Seconds, 0.0)
        self.assertLess(max_distance_off(face, femmesh), TOLERANCE)
        sketch = mesh_obj.Sketch
        self.assertEqual(sketch.TypeId, "Sketcher::SketchObject")
        for edge in sketch.Shape.Edges:
            self.assertLess(face.distToShape(edge)[0], TOLERANCE)

    def test_in_the_analysis_and_follows_its_parameters(self):
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = shared_face("plate_with_hole")
        fem_analysis = ObjectsFem.makeAnalysis(self.doc, "Analysis")
        self.doc.recompute()
        mesh_obj = MedialMesh.make_mesh_object(self.doc, plate, "Face1", size=0.4)
        self.assertIn(mesh_obj, fem_analysis.Group)  # the document's only analysis
        self.assertEqual(mesh_obj.TypeId, "Fem::FemMeshObjectPython")
        self.assertEqual(mesh_obj.Part, plate)
        face = plate.Shape.Faces[0]
        self.check(mesh_obj, face)
        self.assertEqual(len(mesh_obj.Sketch.Geometry), 4)  # the four straight splits
        self.assertEqual(mesh_obj.IrregularNodes, 4)
        coarse = mesh_obj.QuadCount

        mesh_obj.ElementSize = 0.2
        self.doc.recompute()
        self.check(mesh_obj, face)
        self.assertGreater(mesh_obj.QuadCount, 2 * coarse)
        fine = mesh_obj.QuadCount

        mesh_obj.ElementOrder = "2nd"
        self.doc.recompute()
        self.check(mesh_obj, face, order=2)
        self.assertEqual(mesh_obj.QuadCount, fine)

        mesh_obj.Smoothing = False
        self.doc.recompute()
        self.check(mesh_obj, face, order=2)
        self.assertNotIn("Touched", mesh_obj.State)
        self.assertNotIn("Touched", mesh_obj.Sketch.State)

    def test_analysis_argument_and_several_analyses(self):
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = shared_face("square")
        first = ObjectsFem.makeAnalysis(self.doc, "First")
        second = ObjectsFem.makeAnalysis(self.doc, "Second")
        self.doc.recompute()
        loose = MedialMesh.make_mesh_object(self.doc, plate, "Face1")
        self.assertNotIn(loose, first.Group + second.Group)  # two analyses and none named: neither
        placed = MedialMesh.make_mesh_object(self.doc, plate, "Face1", analysis=second)
        self.assertIn(placed, second.Group)
        self.check(placed, plate.Shape.Faces[0])

    def test_recomputes_when_the_face_changes(self):
        body, pad, radius = plate_body(self.doc)
        subname = top_face_name(pad)
        mesh_obj = MedialMesh.make_mesh_object(self.doc, pad, subname, size=0.25)
        self.check(mesh_obj, analysis.global_face(pad, subname))
        before = mesh_obj.FemMesh.NodeCount
        self.doc.getObject("Sketch").setDatum(radius, FreeCAD.Units.Quantity("0.5 mm"))
        self.doc.recompute()
        self.check(mesh_obj, analysis.global_face(pad, subname))
        self.assertNotEqual(mesh_obj.FemMesh.NodeCount, before)

    def test_body_inside_a_placed_app_part(self):
        container = self.doc.addObject("App::Part", "Assembly")
        container.Placement = FreeCAD.Placement(FreeCAD.Vector(100, -20, 7),
                                                FreeCAD.Rotation(FreeCAD.Vector(0, 1, 1), 70))
        body, pad, radius = plate_body(self.doc)
        container.addObject(body)
        self.doc.recompute()
        subname = top_face_name(pad)
        mesh_obj = MedialMesh.make_mesh_object(self.doc, pad, subname, size=0.4)
        # the face as seen: the container's and the body's placements on the pad's shape
        seen = pad.Shape.getElement(subname).copy()
        seen.Placement = container.Placement.multiply(body.Placement).multiply(seen.Placement)
        self.check(mesh_obj, seen)
        unplaced = pad.Shape.getElement(subname)
        self.assertGreater(max_distance_off(unplaced, mesh_obj.FemMesh), 1.0)

    def test_sketch_face_and_imported_step(self):
        sketch = self.doc.addObject("Sketcher::SketchObject", "Profile")
        corners = [FreeCAD.Vector(x, y, 0) for x, y in ((0, 0), (3, 0), (3, 1), (1, 1), (1, 2), (0, 2))]  # an L
        for a, b in zip(corners, corners[1:] + corners[:1]):
            sketch.addGeometry(Part.LineSegment(a, b))
        sketch.Placement = PLACEMENT
        face = self.doc.addObject("Part::Face", "Face")
        face.Sources = [sketch]
        self.doc.recompute()
        from_sketch = MedialMesh.make_mesh_object(self.doc, face, "Face1", size=0.3)
        self.check(from_sketch, face.Shape.Faces[0])

        path = os.path.join(tempfile.mkdtemp(), "plate.step")
        plate = shared_face("plate_with_hole")
        plate.Placement = PLACEMENT
        plate.exportStep(path)
        import Import

        Import.insert(path, self.doc.Name)
        imported = self.doc.Objects[-1]
        self.doc.recompute()
        from_step = MedialMesh.make_mesh_object(self.doc, imported, "Face1", size=0.3)
        self.check(from_step, analysis.global_face(imported, "Face1"))
        self.assertLess(max_distance_off(plate, from_step.FemMesh), TOLERANCE)

    def test_saves_and_reopens(self):
        body, pad, radius = plate_body(self.doc)
        subname = top_face_name(pad)
        ObjectsFem.makeAnalysis(self.doc, "Analysis")
        mesh_obj = MedialMesh.make_mesh_object(self.doc, pad, subname, size=0.3, order=2, merge=0.5)
        counts = (mesh_obj.QuadCount, mesh_obj.NodeCount)
        name, sketch_name = mesh_obj.Name, mesh_obj.Sketch.Name
        path = os.path.join(tempfile.mkdtemp(), "quadmesh.FCStd")
        self.doc.saveAs(path)
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        reopened = self.doc.getObject(name)
        self.assertEqual(reopened.Type, "MedialMesh::QuadMesh")
        self.assertEqual((reopened.MergeFactor, reopened.ElementOrder), (0.5, "2nd"))
        self.assertEqual(reopened.Sketch.Name, sketch_name)
        self.assertEqual((reopened.FemMesh.FaceCount, reopened.FemMesh.NodeCount), counts)  # the mesh was saved
        self.assertIn(reopened, self.doc.getObject("Analysis").Group)
        face = analysis.global_face(reopened.Source[0][0], subname)
        self.check(reopened, face, order=2)
        reopened.touch()
        self.doc.recompute()  # the proxy came back with the document
        self.check(reopened, face, order=2)
        self.assertEqual((reopened.QuadCount, reopened.NodeCount), counts)
        self.assertTrue(reopened.isValid())

    def test_bad_face_reports_and_keeps_freecad_going(self):
        cylinder = self.doc.addObject("Part::Cylinder", "Cylinder")
        self.doc.recompute()
        side = next(f"Face{i + 1}" for i, f in enumerate(cylinder.Shape.Faces)
                    if isinstance(f.Surface, Part.Cylinder))
        mesh_obj = MedialMesh.make_mesh_object(self.doc, cylinder, side)
        self.assertIn("Cylinder." + side, mesh_obj.Status)
        self.assertIn("planar", mesh_obj.Status)
        self.assertEqual(mesh_obj.FemMesh.NodeCount, 0)
        self.assertEqual(mesh_obj.QuadCount, 0)
        self.assertEqual((mesh_obj.MinShape, mesh_obj.NeedleCount), (0.0, 0))  # no figure left from before
        self.assertEqual(mesh_obj.WorstElementPosition, FreeCAD.Vector())
        self.assertEqual(len(mesh_obj.Sketch.Geometry), 0)
        # a good face again: the object recovers
        top = next(f"Face{i + 1}" for i, f in enumerate(cylinder.Shape.Faces)
                   if isinstance(f.Surface, Part.Plane))
        mesh_obj.Source = [(cylinder, [top])]
        self.doc.recompute()
        self.check(mesh_obj, cylinder.Shape.getElement(top))

    def test_a_mesh_made_by_a_fallback_says_so(self):
        # A fuzz aerofoil whose merged block folds: remeshed with less merging.
        data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "fuzz")
        wing = self.doc.addObject("Part::Feature", "Wing")
        wing.Shape = Part.read(os.path.join(data, "aerofoil_9_293.brep")).Faces[0]
        self.doc.recompute()
        mesh_obj = MedialMesh.make_mesh_object(self.doc, wing, "Face1")
        self.assertEqual(mesh_obj.Status, "ok (fallback: less merging)")
        self.assertGreater(mesh_obj.QuadCount, 0)
        self.assertTrue(any("as a fallback" in note for note in mesh_obj.Notes), mesh_obj.Notes)
        self.assertFalse(any("failed" in note for note in mesh_obj.Notes), mesh_obj.Notes)
        result = meshing.mesh_face(wing.Shape.Faces[0])
        self.assertEqual(result.fallbacks, ["less merging"])
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = shared_face("plate_with_hole")
        self.doc.recompute()
        self.assertEqual(MedialMesh.make_mesh_object(self.doc, plate, "Face1").Status, "ok")

    def test_bad_arguments_raise_before_creating_anything(self):
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = shared_face("square")
        count = len(self.doc.Objects)
        with self.assertRaisesRegex(MedialMesh.InputError, "order"):
            MedialMesh.make_mesh_object(self.doc, plate, "Face1", order=3)
        with self.assertRaisesRegex(MedialMesh.InputError, "no face"):
            MedialMesh.make_mesh_object(self.doc, plate, [])
        self.assertEqual(len(self.doc.Objects), count)

    def test_faces_of_several_objects(self):
        left = self.doc.addObject("Part::Feature", "Left")
        left.Shape = Part.makePlane(1, 1)
        right = self.doc.addObject("Part::Feature", "Right")
        right.Shape = Part.makePlane(1, 1, FreeCAD.Vector(1, 0, 0))
        self.doc.recompute()
        mesh_obj = MedialMesh.make_mesh_object(self.doc, [(left, "Face1"), (right, "Face1")], None, size=0.25)
        self.assertEqual([(o.Name, list(s)) for o, s in mesh_obj.Source], [("Left", ["Face1"]), ("Right", ["Face1"])])
        self.assertEqual(mesh_obj.Status, "ok")
        self.assertEqual(mesh_obj.QuadCount, 32)
        check_conforming(self, mesh_obj.FemMesh, Part.makePlane(2, 1).Edges)

    def test_faces_of_two_planes_meeting_at_an_edge(self):
        # Two sides of a box: x = 0 (Face1) and y = 0 (Face3) meet along the z axis.
        box = self.doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 2, 3, 1
        self.doc.recompute()
        mesh_obj = MedialMesh.make_mesh_object(self.doc, box, ["Face1", "Face3"], size=0.25)
        self.assertEqual(mesh_obj.Status, "ok")
        self.assertEqual(mesh_obj.QuadCount, 3 * 4 * 4 + 2 * 4 * 4)
        faces = [box.Shape.Face1, box.Shape.Face3]
        shared = [e for e in faces[0].Edges if any(e.isSame(f) for f in faces[1].Edges)]
        self.assertEqual(len(shared), 1)
        outline = [e for face in faces for e in face.Edges if not e.isSame(shared[0])]
        check_conforming(self, mesh_obj.FemMesh, outline)
        on_axis = [p for p in mesh_obj.FemMesh.Nodes.values() if abs(p.x) < TOLERANCE and abs(p.y) < TOLERANCE]
        self.assertEqual(len(on_axis), 5)  # the shared edge's 4 intervals, its nodes once
        for face in faces:
            for node in on_axis:
                self.assertLess(face.distToShape(Part.Vertex(node))[0], TOLERANCE)


class TestProgressAndMessages(unittest.TestCase):
    """What the task panel builds on: a run followed and stopped from
    another thread, the notes grouped for people, one wording of a failure,
    the shapes the view colours by, and the meshes Undo and Redo take back."""

    def setUp(self):
        self.doc = FreeCAD.newDocument("ProgressAndMessages")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def test_a_run_followed_and_cancelled_from_another_thread(self):
        face = shared_face("plate_with_hole")
        progress = meshing.Progress()
        seen, outcome = [], {}

        def work():
            try:
                outcome["result"] = meshing.mesh_face(face, size=0.01, progress=progress)
            except MedialMesh.Cancelled as error:
                outcome["error"] = error

        worker = threading.Thread(target=work)
        worker.start()
        while worker.is_alive() and "Building the FEM mesh" not in progress.text():
            seen.append((progress.text(), progress.fraction()))
            time.sleep(0.005)
        progress.cancel()
        worker.join()
        self.assertIn("error", outcome, "the run was not stopped")
        self.assertTrue(progress.cancelled)
        texts = [text for text, _ in seen]
        known = ("Reading the faces", "Meshing: medial axis", "Meshing: decomposition", "Meshing: interval counts",
                 "Meshing: blocks ", "Meshing: smoothing", "Meshing: quality", "Building the FEM mesh")
        self.assertEqual([t for t in texts if not t.startswith(known)], [])
        self.assertTrue(any(text.startswith("Meshing: blocks ") and " of " in text for text in texts), texts)
        fractions = [f for _, f in seen]
        self.assertEqual(fractions, sorted(fractions))  # the bar only moves on
        self.assertLess(fractions[-1], 1.0)
        # the same run to its end: the bar full, the same mesh as without a Progress
        progress = meshing.Progress()
        result = meshing.mesh_face(face, size=0.1, progress=progress)
        self.assertEqual(progress.fraction(), 1.0)
        self.assertEqual(result.quality["quads"], meshing.mesh_face(face, size=0.1).quality["quads"])

    def test_notes_grouped_for_people(self):
        face = Part.read(os.path.join(os.environ["MEDIALMESH_SHARED"], "realcad", "faces",
                                      "trimesh_featuretype_50.brep")).Faces[0]
        notes = meshing.mesh_face(face).notes
        grouped = messages.group_notes(notes)
        self.assertEqual(sum(m.count for m in grouped), len(notes))  # every note in one message
        self.assertLess(len(grouped), len(notes))
        fixed = sum(1 for note in notes if note.startswith("fixed a k = "))
        self.assertIn(f"{fixed} irregular nodes placed at block corners", grouped[0].text)
        for message in grouped:
            self.assertNotIn("k = ", message.text)  # no developer words
        # a fallback is a warning, put first; an unknown note is kept as written, counted
        grouped = messages.group_notes(["fixed a k = 1 singularity: no permitted split",
                                        "meshed with merging 0.5, as a fallback: with merging 0.75 the result did "
                                        "not pass its check (mesh: an element is inverted)",
                                        "something new", "something new"])
        self.assertEqual([m.level for m in grouped], [messages.WARNING, messages.INFO, messages.INFO])
        self.assertTrue(grouped[0].text.startswith("A fallback made this mesh"))
        self.assertEqual(grouped[2].text, "something new (2 times)")

    def test_a_failure_worded_once_the_same_everywhere(self):
        check = _medialmesh.SelfCheckError("Plate.Face1: self-check failed: mesh: an element is inverted")
        text = messages.failure_message(check, "Plate.Face1")
        self.assertTrue(text.startswith("Plate.Face1: MedialMesh could not mesh this: its own check of the result "
                                        "failed (mesh: an element is inverted)"), text)
        self.assertIn("defect of MedialMesh, not of your model", text)
        self.assertIn("Try another element size or merge factor", text)
        self.assertIn("File > Export, save it as a .brep", text)
        self.assertEqual(text.count("Plate.Face1"), 1)
        cylinder = Part.makeCylinder(1, 2)
        side = next(f for f in cylinder.Faces if isinstance(f.Surface, Part.Cylinder))
        with self.assertRaises(MedialMesh.InputError) as raised:
            meshing.mesh_face(side, name="Tube.Face1")
        self.assertEqual(messages.failure_message(raised.exception, "Tube.Face1"), str(raised.exception))
        self.assertEqual(messages.failure_message(MedialMesh.Cancelled("meshing cancelled"), "Tube.Face1"),
                         "Tube.Face1: meshing cancelled")

    def test_element_shapes_read_back_from_the_femmesh(self):
        face = shared_face("bracket")
        face.Placement = PLACEMENT  # turned out of the XY plane
        for order in (1, 2):
            result = meshing.mesh_face(face, order=order)
            shapes = meshing.femmesh_shapes(result.femmesh)
            self.assertEqual(len(shapes), result.quality["quads"])
            self.assertLess(abs(shapes - result.element_shape).max(), 1e-9)
            self.assertAlmostEqual(shapes.min(), result.quality["min_shape"], places=9)

    def test_a_saved_document_reopens_in_a_fresh_freecad_with_the_addon_installed(self):
        # As tools/install.sh installs it: the repository linked into the
        # user's Mod folder. FreeCAD (Debian's 0.20.2+dfsg1-4+deb12u1 and
        # 1.0 with the CVE-2026-34789 fix) restores an object's Python proxy
        # only from a module under an installed addon's folder, as named in
        # FreeCAD.__ModDirs__: through the link, not the folder it points to.
        repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = shared_face("plate_with_hole")
        self.doc.recompute()
        MedialMesh.make_mesh_object(self.doc, plate, "Face1")
        with tempfile.TemporaryDirectory() as home:
            path = os.path.join(home, "saved.FCStd")
            self.doc.saveAs(path)
            mod = os.path.join(home, ".local", "share", "FreeCAD", "Mod")
            os.makedirs(mod)
            os.symlink(repo, os.path.join(mod, "MedialMesh"))
            script = (f"import FreeCAD; doc = FreeCAD.openDocument({path!r}); "
                      "print('proxy:', type(doc.getObject('MedialQuadMesh').Proxy).__name__)")
            env = dict(os.environ, HOME=home,
                       PYTHONPATH=os.path.join(os.environ["MEDIALMESH_BUILD_DIR"], "lib"))
            env.pop("XDG_DATA_HOME", None)
            run = subprocess.run(["freecadcmd", "-c", script], env=env, stdin=subprocess.DEVNULL,
                                 capture_output=True, text=True, timeout=300)
        self.assertIn("proxy: MedialQuadMesh", run.stdout, run.stdout + run.stderr)
        self.assertNotIn("blocked import", run.stdout + run.stderr)

    def test_undo_and_redo_take_the_meshes_back(self):
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = shared_face("plate_with_hole")
        self.doc.UndoMode = 1
        self.doc.recompute()
        self.doc.openTransaction("make")
        mesh_obj = MedialMesh.make_mesh_object(self.doc, plate, "Face1")
        self.doc.commitTransaction()
        coarse = mesh_obj.QuadCount
        self.doc.openTransaction("size")
        mesh_obj.ElementSize = 0.2
        self.doc.recompute()
        self.doc.commitTransaction()
        fine = mesh_obj.QuadCount
        self.assertGreater(fine, coarse)
        calls = []
        original = meshing.mesh_face
        meshing.mesh_face = lambda *a, **k: calls.append(1) or original(*a, **k)
        try:
            self.doc.undo()
            self.assertEqual(mesh_obj.QuadCount, coarse)
            self.doc.recompute()  # FreeCAD's Undo does not restore the FemMesh: the object takes its mesh back
            self.assertEqual(mesh_obj.FemMesh.FaceCount, coarse)
            self.doc.redo()
            self.doc.recompute()
            self.assertEqual((mesh_obj.ElementSize.Value, mesh_obj.FemMesh.FaceCount), (0.2, fine))
        finally:
            meshing.mesh_face = original
        self.assertEqual(calls, [])
        plate.Placement.Base = FreeCAD.Vector(1, 0, 0)  # the face moved: its meshes are for another face
        self.doc.recompute()
        self.assertEqual(mesh_obj.FemMesh.FaceCount, fine)
        self.assertLess(max_distance_off(plate.Shape.Faces[0], mesh_obj.FemMesh), TOLERANCE)


if __name__ == "__main__":
    unittest.main()

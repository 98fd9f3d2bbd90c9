# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Decompose macro API and the parametric decomposition object, in freecadcmd.

Run by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh tests/freecad/test_decomposition.py [BUILD_DIR [SHARED_DIR]]
"""

import os
import tempfile
import unittest

import FreeCAD
import Part

import MedialMesh
from MedialMesh import analysis
from test_analysis import PLACEMENT, junction_x, plate_body, shared_face, top_face_name

TOLERANCE = 1e-7


def split_ends(split):
    """The two ends of a split (a Part.Edge or a Part.Wire)."""
    vertices = split.OrderedVertexes if isinstance(split, Part.Wire) else split.Vertexes
    return vertices[0].Point, vertices[-1].Point


def distance_off(face, shape):
    """How far the shape strays from the face: the largest distance of points along it."""
    points = shape.discretize(Distance=0.05 * face.BoundBox.DiagonalLength)
    return max(face.distToShape(Part.Vertex(p))[0] for p in points)


def cut(face, splits):
    """The faces that the splits (edges or wires lying on the face) cut it into."""
    if not splits:
        return [face]
    return face.generalFuse(splits, 1e-7 * face.BoundBox.DiagonalLength)[0].Faces


def segment_count(result):
    return sum(len(split.Edges) for split in result.splits)


class TestDecomposeFace(unittest.TestCase):

    def check_tiling(self, face, result):
        """Blocks that add up to the face, splits that lie on it and end on
        its boundary or on another split."""
        self.assertAlmostEqual(sum(b.area for b in result.blocks) / face.Area, 1.0, delta=1e-6)
        for block in result.blocks:
            self.assertTrue(block.outline.isClosed())
            # its points are on the face; the chords between them cut across curved sides
            self.assertLess(max(face.distToShape(v)[0] for v in block.outline.Vertexes), TOLERANCE)
        boundary = Part.Compound(face.Edges)
        for i, split in enumerate(result.splits):
            self.assertLess(distance_off(face, split), TOLERANCE)
            others = [s for j, s in enumerate(result.splits) if j != i]
            for end in split_ends(split):
                vertex = Part.Vertex(end)
                distance = min([boundary.distToShape(vertex)[0]] + [s.distToShape(vertex)[0] for s in others])
                self.assertLess(distance, TOLERANCE, f"split {i} ends at {end}, off the boundary and the splits")

    def test_plate_with_hole(self):
        face = shared_face("plate_with_hole")
        result = MedialMesh.decompose_face(face)
        self.assertEqual(len(result.splits), 4)
        self.assertEqual([(b.kind, b.sides, b.k) for b in result.blocks], [("polygon", 5, 1)] * 4)
        self.assertEqual(result.fixed, [])
        self.assertFalse(result.fallback)
        self.check_tiling(face, result)
        x = junction_x(2, 1)
        for block in result.blocks:
            self.assertEqual(len(block.corners), 5)
            # each block holds its own junction's +1
            self.assertAlmostEqual(abs(block.singularity.x), x, places=8)
            self.assertAlmostEqual(abs(block.singularity.y), x, places=8)
            self.assertTrue(Part.Face(block.outline).isInside(block.singularity, 1e-9, False))

    def test_plate_splits_are_straight(self):
        # The best split along the medial edge between two junctions is where
        # the medial angle is pi: the symmetry axis, from a side to the hole.
        result = MedialMesh.decompose_face(shared_face("plate_with_hole"))
        self.assertTrue(all(isinstance(split, Part.Edge) for split in result.splits))
        expected = [(FreeCAD.Vector(sx * 2, sy * 2, 0), FreeCAD.Vector(sx, sy, 0))
                    for sx, sy in ((1, 0), (-1, 0), (0, 1), (0, -1))]
        for split in result.splits:
            a, b = sorted(split_ends(split), key=lambda p: -p.Length)  # on the side first
            self.assertTrue(any(a.distanceToPoint(c) < TOLERANCE and b.distanceToPoint(d) < TOLERANCE
                                for c, d in expected), f"split from {a} to {b}")

    def test_moved_face_gives_the_moved_decomposition(self):
        face = shared_face("plate_with_hole")
        flat = MedialMesh.decompose_face(face)
        face.Placement = PLACEMENT
        moved = MedialMesh.decompose_face(face)
        self.check_tiling(face, moved)
        self.assertEqual(len(moved.splits), len(flat.splits))
        flat_ends = [split_ends(s) for s in flat.splits]
        for split in moved.splits:
            a, b = (PLACEMENT.inverse().multVec(p) for p in split_ends(split))
            self.assertTrue(any(min(max(a.distanceToPoint(c), b.distanceToPoint(d)),
                                    max(a.distanceToPoint(d), b.distanceToPoint(c))) < TOLERANCE
                                for c, d in flat_ends),
                            f"the moved face's split from {a} to {b} (moved back) is not one of the face's own")
        # The face's frame: its origin on the face's plane, its z axis the face normal.
        self.assertLess(face.Surface.projectPoint(moved.placement.Base, "LowerDistance"), TOLERANCE)
        normal = moved.placement.Rotation.multVec(FreeCAD.Vector(0, 0, 1))
        self.assertLess(normal.distanceToPoint(face.normalAt(0, 0)), 1e-9)

    def test_known_answers(self):
        circle = shared_face("circle")
        result = MedialMesh.decompose_face(circle)
        self.assertEqual(len(result.splits), 0)
        self.assertEqual([(b.kind, b.sides, b.k) for b in result.blocks], [("polygon", 0, -4)])
        self.assertLess(result.blocks[0].singularity.distanceToPoint(circle.CenterOfMass), 1e-9)
        self.check_tiling(circle, result)

        triangle = shared_face("triangle")
        result = MedialMesh.decompose_face(triangle)
        self.assertEqual([(b.kind, b.sides, b.k) for b in result.blocks], [("polygon", 3, -1)])
        self.check_tiling(triangle, result)

        for name, splits in (("L_shape", 0), ("annulus", 1)):
            face = shared_face(name)
            result = MedialMesh.decompose_face(face)
            self.assertEqual(len(result.splits), splits, name)
            self.assertEqual([(b.kind, b.singularity) for b in result.blocks], [("submap", None)], name)
            self.check_tiling(face, result)

    def test_splits_cut_every_reference_face_into_its_blocks(self):
        # Part's own boolean cut of the face by the splits must give the blocks.
        folder = os.path.join(os.environ["MEDIALMESH_SHARED"], "geometry")
        for file in sorted(os.listdir(folder)):
            with self.subTest(face=file):
                face = Part.read(os.path.join(folder, file)).Faces[0]
                face.Placement = PLACEMENT
                result = MedialMesh.decompose_face(face, merge=0.75)
                pieces = cut(face, result.splits)
                self.assertEqual(len(pieces), len(result.blocks))
                # FreeCAD's own area of the B-spline aerofoil is 7.5e-5 off (README)
                for piece, block in zip(sorted(f.Area for f in pieces), sorted(b.area for b in result.blocks)):
                    self.assertAlmostEqual(piece, block, delta=1e-4 * face.Area)

    def test_bad_input_names_the_problem(self):
        cylinder = Part.makeCylinder(1, 2)
        side = next(f for f in cylinder.Faces if isinstance(f.Surface, Part.Cylinder))
        with self.assertRaisesRegex(MedialMesh.InputError, "side.*planar"):
            MedialMesh.decompose_face(side, name="side")
        with self.assertRaisesRegex(MedialMesh.InputError, "merge factor"):
            MedialMesh.decompose_face(shared_face("square"), merge=3)
        with self.assertRaises(MedialMesh.InputError):
            MedialMesh.decompose_face("not a face")


class TestCompiledDecompose(unittest.TestCase):
    """_medialmesh.decompose itself, as a macro writer calls it on BREP text."""

    def test_report_of_the_plate(self):
        import _medialmesh

        face = shared_face("plate_with_hole")
        report = _medialmesh.decompose(face.exportBrepToString(), "plate", merge=0.75)
        for key in ("blocks", "splits", "fixed", "singularities", "fallback", "notes", "face_area", "frame"):
            self.assertIn(key, report)
        self.assertEqual(len(report["splits"]), 4)
        self.assertEqual([(b["kind"], b["sides"], b["singularity"]["k"]) for b in report["blocks"]],
                         [("polygon", 5, 1)] * 4)
        self.assertAlmostEqual(sum(b["area"] for b in report["blocks"]) / face.Area, 1.0, delta=1e-9)
        self.assertAlmostEqual(report["face_area"] / face.Area, 1.0, delta=1e-9)
        for block in report["blocks"]:
            outline = block["boundary"]
            twice_area = sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(outline, outline[1:] + outline[:1]))
            self.assertGreater(twice_area, 0.0)  # counter-clockwise
            self.assertEqual(len(block["corners"]), 5)

    def test_merging_is_asked_for(self):
        import _medialmesh

        brep = shared_face("ellipse").exportBrepToString()
        merged = _medialmesh.decompose(brep, "ellipse", merge=1.0)
        self.assertEqual([(b["kind"], b["sides"]) for b in merged["blocks"]], [("polygon", 2)] * 2)
        unmerged = _medialmesh.decompose(brep, "ellipse")  # neither merge nor mesh_size: no merging
        self.assertGreater(len(unmerged["singularities"]), 2)

    def test_bad_face_raises_input_error(self):
        import _medialmesh

        with self.assertRaises(_medialmesh.InputError):
            _medialmesh.decompose(Part.makeCylinder(1, 2).Faces[0].exportBrepToString(), "cylinder side")


class TestDecompositionObject(unittest.TestCase):

    def setUp(self):
        self.doc = FreeCAD.newDocument("MedialMeshDecomposition")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def check(self, decomposition, face, merge=0.75):
        """The object agrees with decompose_face, its splits and its Sketch lie on the face."""
        self.assertEqual(decomposition.Status, "ok")
        result = MedialMesh.decompose_face(face, merge=merge if merge > 0 else None)
        self.assertEqual(decomposition.SplitCount, len(result.splits))
        self.assertEqual(decomposition.BlockCount, len(result.blocks))
        self.assertEqual(decomposition.PolygonBlocks, sum(b.kind == "polygon" for b in result.blocks))
        self.assertEqual(decomposition.SubmapBlocks, sum(b.kind == "submap" for b in result.blocks))
        self.assertEqual(decomposition.FixedCount, len(result.fixed))
        self.assertEqual(decomposition.Notes, result.notes)
        self.assertAlmostEqual(decomposition.Shape.Length, sum(s.Length for s in result.splits), places=9)
        for split in decomposition.Shape.childShapes():
            self.assertLess(distance_off(face, split), TOLERANCE)

        sketch = decomposition.Sketch
        self.assertEqual(sketch.TypeId, "Sketcher::SketchObject")
        self.assertEqual(len(sketch.Geometry), segment_count(result))
        self.assertTrue(all(isinstance(g, Part.LineSegment) for g in sketch.Geometry))
        # on the face's plane, facing its way, and drawing the splits
        self.assertLess(face.Surface.projectPoint(sketch.Placement.Base, "LowerDistance"), TOLERANCE)
        normal = sketch.Placement.Rotation.multVec(FreeCAD.Vector(0, 0, 1))
        self.assertLess(normal.distanceToPoint(face.normalAt(0, 0)), 1e-9)
        for edge in sketch.Shape.Edges:
            self.assertLess(decomposition.Shape.distToShape(edge.Vertexes[0])[0], TOLERANCE)
            self.assertLess(decomposition.Shape.distToShape(edge.Vertexes[-1])[0], TOLERANCE)
        if result.splits:
            self.assertAlmostEqual(sketch.Shape.Length, decomposition.Shape.Length, places=9)
            self.assertEqual(len(cut(face, [sketch.Shape])), decomposition.BlockCount)  # the sketch cuts out the blocks
        return result

    def test_plate_in_a_moved_body(self):
        body, pad, radius = plate_body(self.doc)
        subname = top_face_name(pad)
        decomposition = MedialMesh.make_decomposition_object(self.doc, pad, subname)
        self.doc.recompute()
        self.assertEqual(decomposition.Type, "MedialMesh::Decomposition")
        self.assertEqual(decomposition.MergeFactor, 0.75)
        self.check(decomposition, analysis.global_face(pad, subname))
        self.assertEqual((decomposition.SplitCount, decomposition.PolygonBlocks, decomposition.SubmapBlocks),
                         (4, 4, 0))
        self.assertEqual(len(decomposition.Sketch.Geometry), decomposition.SplitCount)  # each split straight
        self.assertNotIn("Touched", decomposition.Sketch.State)

    def test_recomputes_when_the_hole_changes(self):
        body, pad, radius = plate_body(self.doc)
        subname = top_face_name(pad)
        decomposition = MedialMesh.make_decomposition_object(self.doc, pad, subname)
        self.doc.recompute()
        before = decomposition.Shape.Length
        self.doc.getObject("Sketch").setDatum(radius, FreeCAD.Units.Quantity("0.5 mm"))
        self.doc.recompute()
        self.assertNotAlmostEqual(decomposition.Shape.Length, before, places=3)
        self.check(decomposition, analysis.global_face(pad, subname))
        self.assertEqual(decomposition.SplitCount, 4)

    def test_recomputes_when_the_merge_factor_changes(self):
        ellipse = self.doc.addObject("Part::Feature", "Ellipse")
        ellipse.Shape = shared_face("ellipse")
        ellipse.Placement = PLACEMENT
        self.doc.recompute()
        face = analysis.global_face(ellipse, "Face1")
        # Merged, the ellipse's four -1 become two -2: another decomposition.
        unmerged = MedialMesh.decompose_face(face)
        merged = MedialMesh.decompose_face(face, merge=1.0)
        self.assertEqual((len(unmerged.singularities), len(merged.singularities)), (4, 2))
        decomposition = MedialMesh.make_decomposition_object(self.doc, ellipse, "Face1", merge=0)
        self.doc.recompute()
        self.check(decomposition, face, merge=0)
        decomposition.MergeFactor = 1.0
        self.doc.recompute()
        self.check(decomposition, face, merge=1.0)
        self.assertNotEqual(sorted((b.kind, b.sides) for b in unmerged.blocks),
                            sorted((b.kind, b.sides) for b in merged.blocks))

    def test_saves_and_reopens(self):
        body, pad, radius = plate_body(self.doc)
        subname = top_face_name(pad)
        decomposition = MedialMesh.make_decomposition_object(self.doc, pad, subname, merge=0.5)
        self.doc.recompute()
        path = os.path.join(tempfile.mkdtemp(), "decomposition.FCStd")
        self.doc.saveAs(path)
        name, sketch_name = decomposition.Name, decomposition.Sketch.Name
        FreeCAD.closeDocument(self.doc.Name)
        self.doc = FreeCAD.openDocument(path)
        reopened = self.doc.getObject(name)
        self.assertEqual(reopened.Type, "MedialMesh::Decomposition")
        self.assertEqual(reopened.MergeFactor, 0.5)
        self.assertEqual(reopened.Source[0].Name, "Pad")
        self.assertEqual(reopened.Sketch.Name, sketch_name)
        face = analysis.global_face(reopened.Source[0], subname)
        self.check(reopened, face, merge=0.5)
        reopened.touch()
        self.doc.recompute()  # the proxy came back with the document
        self.check(reopened, face, merge=0.5)
        self.assertTrue(reopened.isValid())

    def test_bad_face_reports_and_keeps_freecad_going(self):
        cylinder = self.doc.addObject("Part::Cylinder", "Cylinder")
        self.doc.recompute()
        side = next(f"Face{i + 1}" for i, f in enumerate(cylinder.Shape.Faces)
                    if isinstance(f.Surface, Part.Cylinder))
        decomposition = MedialMesh.make_decomposition_object(self.doc, cylinder, side)
        self.doc.recompute()
        self.assertIn("Cylinder." + side, decomposition.Status)
        self.assertIn("planar", decomposition.Status)
        self.assertTrue(decomposition.Shape.isNull())
        self.assertEqual((decomposition.SplitCount, decomposition.BlockCount, decomposition.Notes), (0, 0, []))
        self.assertEqual(len(decomposition.Sketch.Geometry), 0)
        self.assertTrue(decomposition.isValid())  # the error is the Status, not a failed recompute


if __name__ == "__main__":
    unittest.main()

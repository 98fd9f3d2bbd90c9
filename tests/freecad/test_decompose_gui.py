# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Decompose command as a user runs it, in the FreeCAD GUI under Xvfb.

Run by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh --gui tests/freecad/test_decompose_gui.py [BUILD_DIR [SHARED_DIR]]
The picture of the 3D view goes to BUILD_DIR/test-output/decompose_gui.png.
"""

import os
import unittest

import FreeCAD
import FreeCADGui
import Part
from qt_compat import QtGui, QtWidgets

from MedialMesh import decomposition
from test_analyse_gui import PLACEMENT, colour_count, says_why_it_cannot_use_a_selection


class TestDecomposeCommand(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        FreeCADGui.activateWorkbench("MedialMeshWorkbench")
        cls.doc = FreeCAD.newDocument("DecomposeGui")
        shape = Part.read(os.path.join(os.environ["MEDIALMESH_SHARED"], "geometry", "plate_with_hole.brep"))
        cls.plate = cls.doc.addObject("Part::Feature", "Plate")
        cls.plate.Shape = shape
        cls.plate.Placement = PLACEMENT
        cylinder = cls.doc.addObject("Part::Cylinder", "Cylinder")
        cylinder.Placement.Base = FreeCAD.Vector(30, 0, 0)
        cls.doc.recompute()
        FreeCADGui.updateGui()

    @classmethod
    def tearDownClass(cls):
        FreeCAD.closeDocument(cls.doc.Name)

    def select(self, obj, subname):
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(self.doc.Name, obj.Name, subname)
        FreeCADGui.updateGui()

    def test_in_toolbar_and_menu(self):
        toolbars = FreeCADGui.getWorkbench("MedialMeshWorkbench").getToolbarItems()
        self.assertIn("MedialMesh_Decompose", toolbars["MedialMesh"])
        pixmap = FreeCADGui.Command.get("MedialMesh_Decompose").getInfo()["pixmap"]
        self.assertTrue(pixmap.endswith("MedialMesh_Decompose.svg") and os.path.isfile(pixmap))
        menus = [m for m in FreeCADGui.getMainWindow().menuBar().findChildren(QtWidgets.QMenu)
                 if m.title() == "MedialMesh"]
        self.assertIn("Decompose face", [a.text() for m in menus for a in m.actions()])

    def test_says_why_it_cannot_use_a_selection(self):
        says_why_it_cannot_use_a_selection(self, "MedialMesh_Decompose")

    def test_decompose_shows_the_splits(self):
        self.select(self.plate, "Face1")
        before = set(o.Name for o in self.doc.Objects)
        FreeCADGui.runCommand("MedialMesh_Decompose")
        FreeCADGui.updateGui()
        made = [self.doc.getObject(name) for name in set(o.Name for o in self.doc.Objects) - before]
        (result,) = [o for o in made if getattr(o, "Type", "") == "MedialMesh::Decomposition"]
        self.assertEqual(result.Status, "ok")
        self.assertEqual((result.SplitCount, result.PolygonBlocks), (4, 4))
        self.assertEqual(sorted(o.Name for o in made), sorted([result.Name, result.Sketch.Name]))
        self.assertEqual(len(result.Sketch.Geometry), len(result.Shape.Edges))
        self.assertEqual(result.ViewObject.Proxy.__class__.__name__, "ViewProviderMedialDecomposition")
        self.assertEqual(result.ViewObject.claimChildren(), [result.Sketch])

        self.doc.getObject("Cylinder").ViewObject.Visibility = False  # only the plate in the picture
        view = FreeCADGui.ActiveDocument.ActiveView
        view.setCameraOrientation(PLACEMENT.Rotation)  # look straight at the face
        # Fit the plate itself: Coin's box round a rotated object and an
        # unrotated one (the splits are placed in 3-D) is larger than both.
        self.select(self.plate, "")
        FreeCADGui.SendMsgToActiveView("ViewSelection")
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.updateGui()
        folder = os.path.join(os.environ["MEDIALMESH_BUILD_DIR"], "test-output")
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, "decompose_gui.png")
        view.saveImage(path, 640, 480, "White")
        image = QtGui.QImage(path)
        self.assertEqual((image.width(), image.height()), (640, 480))
        white = colour_count(image, (1, 1, 1), tolerance=8)
        self.assertLess(white, 0.9 * 640 * 480, "the picture is blank")
        # the four splits, from the hole to the plate's sides
        on_face = colour_count(image, decomposition.SPLIT_COLOUR)
        self.assertGreater(on_face, 200)
        # whole, not in pieces where they fight the face for depth
        self.plate.ViewObject.Visibility = False
        FreeCADGui.updateGui()
        alone = os.path.join(folder, "decompose_gui_splits_alone.png")
        view.saveImage(alone, 640, 480, "White")
        self.plate.ViewObject.Visibility = True
        self.assertGreater(on_face, 0.95 * colour_count(QtGui.QImage(alone), decomposition.SPLIT_COLOUR))


if __name__ == "__main__":
    unittest.main()

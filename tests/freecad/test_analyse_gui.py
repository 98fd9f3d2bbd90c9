# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Analyse command as a user runs it, in the FreeCAD GUI under Xvfb.

Run by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh --gui tests/freecad/test_analyse_gui.py [BUILD_DIR [SHARED_DIR]]
The picture of the 3D view goes to BUILD_DIR/test-output/analyse_gui.png.
"""

import os
import unittest

import FreeCAD
import FreeCADGui
import Part
from qt_compat import QtGui, QtWidgets

from MedialMesh import analysis

PLACEMENT = FreeCAD.Placement(FreeCAD.Vector(10, -5, 3), FreeCAD.Rotation(FreeCAD.Vector(1, 2, 3), 40))


def colour_count(image, rgb, tolerance=40):
    """Pixels within `tolerance` (0-255 per channel) of a colour given in 0-1."""
    target = [round(255 * c) for c in rgb]
    count = 0
    for y in range(0, image.height()):
        for x in range(0, image.width()):
            pixel = QtGui.QColor(image.pixel(x, y))
            if all(abs(a - b) <= tolerance for a, b in zip((pixel.red(), pixel.green(), pixel.blue()), target)):
                count += 1
    return count


def says_why_it_cannot_use_a_selection(test, command_name):
    """A command on one face at a time, grey with nothing selected; pressed
    with a curved face or a whole solid it makes nothing and says why."""
    command = FreeCADGui.Command.get(command_name)
    FreeCADGui.Selection.clearSelection()
    test.assertFalse(command.isActive())  # grey: the tooltip says what to select
    test.assertIn("Select planar faces", command.getInfo()["toolTip"])
    cylinder = test.doc.getObject("Cylinder")
    before = len(test.doc.Objects)
    status_bar = FreeCADGui.getMainWindow().statusBar()
    for obj, subname, why in ((cylinder, "Face1", "Cylinder.Face1 is a curved face (cylinder)"),
                              (cylinder, "", "Cylinder is a whole solid: pick one of its planar faces")):
        test.select(obj, subname)
        test.assertTrue(command.isActive())
        FreeCADGui.runCommand(command_name)
        FreeCADGui.updateGui()
        test.assertEqual(len(test.doc.Objects), before)
        test.assertIn(why, status_bar.currentMessage())
    test.select(test.plate, "Face1")
    test.assertTrue(command.isActive())


class TestAnalyseCommand(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        FreeCADGui.activateWorkbench("MedialMeshWorkbench")
        cls.doc = FreeCAD.newDocument("AnalyseGui")
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
        self.assertIn("MedialMesh_Analyse", toolbars["MedialMesh"])
        self.assertTrue(os.path.isfile(FreeCADGui.Command.get("MedialMesh_Analyse").getInfo()["pixmap"]))
        menus = [m for m in FreeCADGui.getMainWindow().menuBar().findChildren(QtWidgets.QMenu)
                 if m.title() == "MedialMesh"]
        self.assertIn("Analyse face", [a.text() for m in menus for a in m.actions()])

    def test_says_why_it_cannot_use_a_selection(self):
        says_why_it_cannot_use_a_selection(self, "MedialMesh_Analyse")

    def test_analyse_shows_the_overlay(self):
        self.select(self.plate, "Face1")
        before = set(o.Name for o in self.doc.Objects)
        FreeCADGui.runCommand("MedialMesh_Analyse")
        FreeCADGui.updateGui()
        (name,) = set(o.Name for o in self.doc.Objects) - before
        result = self.doc.getObject(name)
        self.assertEqual(result.Status, "ok")
        self.assertEqual(list(result.SingularityK), [1, 1, 1, 1])
        self.assertEqual(result.ViewObject.Proxy.__class__.__name__, "ViewProviderMedialAnalysis")

        FreeCADGui.Selection.clearSelection()
        self.doc.getObject("Cylinder").ViewObject.Visibility = False  # only the plate in the picture
        view = FreeCADGui.ActiveDocument.ActiveView
        view.setCameraOrientation(PLACEMENT.Rotation)  # look straight at the face
        FreeCADGui.SendMsgToActiveView("ViewFit")
        FreeCADGui.updateGui()
        folder = os.path.join(os.environ["MEDIALMESH_BUILD_DIR"], "test-output")
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, "analyse_gui.png")
        view.saveImage(path, 640, 480, "White")
        image = QtGui.QImage(path)
        self.assertEqual((image.width(), image.height()), (640, 480))
        white = colour_count(image, (1, 1, 1), tolerance=8)
        self.assertLess(white, 0.9 * 640 * 480, "the picture is blank")
        # The flow types of the plate's axis (n = 0 round the hole, n = 1 to
        # the corners) and the +1 marks are on screen.
        self.assertGreater(colour_count(image, analysis.flow_colour(0)), 200)
        self.assertGreater(colour_count(image, analysis.flow_colour(1)), 200)
        self.assertGreater(colour_count(image, analysis.POSITIVE_COLOUR, tolerance=60), 50)


if __name__ == "__main__":
    unittest.main()

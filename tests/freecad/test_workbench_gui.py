# SPDX-License-Identifier: LGPL-2.1-or-later
"""The addon as FreeCAD's GUI loads it: package.xml, Init.py, InitGui.py.

Run inside the FreeCAD GUI under Xvfb by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh --gui tests/freecad/test_workbench_gui.py [BUILD_DIR]
"""

import os
import unittest

import FreeCAD
import FreeCADGui


REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class TestPackageMetadata(unittest.TestCase):

    def setUp(self):
        self.metadata = FreeCAD.Metadata(os.path.join(REPO, "package.xml"))

    def test_required_elements(self):
        # the elements the Addon Manager checks in its developer mode
        self.assertEqual(self.metadata.Name, "MedialMesh")
        self.assertNotEqual(self.metadata.Version, "0.0.0")
        self.assertTrue(self.metadata.Description)
        self.assertTrue(all(m["email"] for m in self.metadata.Maintainer))
        self.assertEqual(self.metadata.License[0]["name"], "LGPL-2.1-or-later")
        self.assertTrue(self.metadata.supportsCurrentFreeCAD())
        self.assertTrue(os.path.isfile(os.path.join(REPO, self.metadata.Icon)))

    def test_dependencies_listed(self):
        needed = {"fem", "part", "sketcher", "numpy"}
        self.assertEqual(needed, needed & {d["package"] for d in self.metadata.Depend})

    def test_workbench_content(self):
        (workbench,) = self.metadata.Content["workbench"]
        self.assertEqual(workbench.Classname, "MedialMeshWorkbench")
        self.assertEqual(workbench.Subdirectory, "./")


class TestWorkbench(unittest.TestCase):

    def test_registered(self):
        # InitGui.py runs at start-up, before freecad_runner.py touches
        # sys.path: it finds MedialMesh only if Init.py put <repo>/Mod there.
        self.assertIn("MedialMeshWorkbench", FreeCADGui.listWorkbenches())

    def test_activate(self):
        FreeCADGui.activateWorkbench("MedialMeshWorkbench")
        workbench = FreeCADGui.activeWorkbench()
        self.assertEqual(workbench.name(), "MedialMeshWorkbench")
        self.assertEqual(workbench.MenuText, "MedialMesh")
        self.assertIn("MedialMesh", workbench.listToolbars())

    def test_icon(self):
        icon = FreeCADGui.getWorkbench("MedialMeshWorkbench").Icon
        self.assertEqual(
            os.path.realpath(icon),
            os.path.join(REPO, "Resources", "icons", "MedialMesh.svg"),
        )

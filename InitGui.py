# SPDX-License-Identifier: LGPL-2.1-or-later
"""MedialMesh Gui init script.

FreeCAD exec()s this file after Init.py, which has put <addon>/Mod on
sys.path. As in Init.py, __file__ is not defined here and names assigned at
top level are not visible inside the class body, hence Icon is set after it.
"""

import importlib.util
import os

import FreeCADGui
from FreeCADGui import Workbench


class MedialMeshWorkbench(Workbench):
    """Block-structured quad meshes of planar faces from their medial axis."""

    MenuText = "MedialMesh"
    ToolTip = "Block-structured all-quad meshes of planar faces, built from the medial axis"

    def Initialize(self):
        import FreeCAD

        try:
            import MedialMesh.commands  # registers the commands
        except ImportError as error:  # the compiled core is not built yet
            FreeCAD.Console.PrintError(f"MedialMesh: {error}\n")
            return
        commands = ["MedialMesh_Analyse", "MedialMesh_Decompose", "MedialMesh_QuadMesh"]
        self.appendToolbar("MedialMesh", commands)
        self.appendMenu("MedialMesh", commands)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


# find_spec locates the package without importing it, so the workbench shows
# up even before the compiled core is built.
_addon = os.path.dirname(os.path.dirname(
    importlib.util.find_spec("MedialMesh").submodule_search_locations[0]
))
MedialMeshWorkbench.Icon = os.path.join(_addon, "Resources", "icons", "MedialMesh.svg")

FreeCADGui.addWorkbench(MedialMeshWorkbench())

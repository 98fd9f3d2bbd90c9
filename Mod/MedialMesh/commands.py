# SPDX-License-Identifier: LGPL-2.1-or-later
"""The workbench's commands."""

import os

import FreeCAD
import FreeCADGui
import Part

from . import objects
from .viewproviders import ICON_FOLDER


def selected_faces():
    """(object, 'FaceN', face) for every face picked in the 3D view or tree."""
    faces = []
    for selection in FreeCADGui.Selection.getSelectionEx():
        for subname, shape in zip(selection.SubElementNames, selection.SubObjects):
            if isinstance(shape, Part.Face):
                faces.append((selection.Object, subname, shape))
    return faces


def is_planar(face):
    try:
        return face.findPlane() is not None
    except Exception:  # OCC refuses some degenerate faces: not plane then
        return False


class CommandAnalyse:
    """Analyse the selected planar faces: medial axis, flow types, singularities."""

    def GetResources(self):
        return {
            "Pixmap": os.path.join(ICON_FOLDER, "MedialMesh_Analyse.svg"),
            "MenuText": "Analyse face",
            "ToolTip": "Show the medial axis of the selected planar faces, coloured by mesh flow type, "
            "and their mesh singularities with their k",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and any(is_planar(face) for _, _, face in selected_faces())

    def Activated(self):
        # Runs from a toolbar: nothing may escape into FreeCAD.
        try:
            self.analyse_selection()
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: Analyse failed: {error!r}\n")

    def analyse_selection(self):
        doc = FreeCAD.ActiveDocument
        doc.openTransaction("Analyse face")
        made = []
        for obj, subname, face in selected_faces():
            if not is_planar(face):
                FreeCAD.Console.PrintError(f"MedialMesh: {obj.Label}.{subname}: the face is not planar\n")
                continue
            made.append(objects.make_analysis_object(doc, obj, subname))
        doc.commitTransaction()
        for obj in made:
            if obj.Status == "ok":
                FreeCAD.Console.PrintMessage(
                    f"MedialMesh: {obj.Label}: {len(obj.SingularityK)} singularities, "
                    f"sum of k {obj.SumK} (every quad mesh: {obj.PredictedSumK})\n")
        doc.recompute()


FreeCADGui.addCommand("MedialMesh_Analyse", CommandAnalyse())

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


class PlanarFaceCommand:
    """A command on the selected planar faces, active when there is one;
    subclasses say which faces count as selected and what to do with them."""

    name = ""  # the transaction's name, and the command's in messages

    def selection(self):
        return selected_faces()

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and any(is_planar(face) for _, _, face in self.selection())

    def Activated(self):
        # Runs from a toolbar: nothing may escape into FreeCAD.
        try:
            self.run_on_selection()
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: {self.name} failed: {error!r}\n")


class FaceCommand(PlanarFaceCommand):
    """A command that makes one object per selected planar face, in one
    transaction; subclasses say what to make and what to tell the user."""

    def run_on_selection(self):
        doc = FreeCAD.ActiveDocument
        doc.openTransaction(self.name)
        made = []
        for obj, subname, face in self.selection():
            if not is_planar(face):
                FreeCAD.Console.PrintError(f"MedialMesh: {obj.Label}.{subname}: the face is not planar\n")
                continue
            made.append(self.make(doc, obj, subname))
        doc.commitTransaction()
        for obj in made:
            if obj.Status.startswith("ok"):
                FreeCAD.Console.PrintMessage(f"MedialMesh: {obj.Label}: {self.summary(obj)}\n")
        doc.recompute()


class CommandAnalyse(FaceCommand):
    """Analyse the selected planar faces: medial axis, flow types, singularities."""

    name = "Analyse face"

    def GetResources(self):
        return {
            "Pixmap": os.path.join(ICON_FOLDER, "MedialMesh_Analyse.svg"),
            "MenuText": "Analyse face",
            "ToolTip": "Show the medial axis of the selected planar faces, coloured by mesh flow type, "
            "and their mesh singularities with their k",
        }

    def make(self, doc, obj, subname):
        return objects.make_analysis_object(doc, obj, subname)

    def summary(self, obj):
        return (f"{len(obj.SingularityK)} singularities, "
                f"sum of k {obj.SumK} (every quad mesh: {obj.PredictedSumK})")


class CommandDecompose(FaceCommand):
    """Decompose the selected planar faces into blocks: splits and a Sketch of them."""

    name = "Decompose face"

    def GetResources(self):
        return {
            "Pixmap": os.path.join(ICON_FOLDER, "MedialMesh_Decompose.svg"),
            "MenuText": "Decompose face",
            "ToolTip": "Split the selected planar faces into blocks for quad meshing, "
            "each holding at most one singularity; the splits also go into a Sketch on the face",
        }

    def make(self, doc, obj, subname):
        return objects.make_decomposition_object(doc, obj, subname)

    def summary(self, obj):
        return (f"{obj.SplitCount} splits, {obj.BlockCount} blocks ({obj.PolygonBlocks} polygon, "
                f"{obj.SubmapBlocks} submapped), {obj.FixedCount} fixed singularities")


def selected_faces_and_sheets():
    """selected_faces(), and every face of an object picked whole (in the
    tree) whose shape is faces without a solid: a face made from a sketch, a
    plane, an imported sheet. A solid picked whole gives nothing: which of
    its faces is meant is not known."""
    faces = selected_faces()
    for selection in FreeCADGui.Selection.getSelectionEx():
        shape = getattr(selection.Object, "Shape", None)
        if selection.SubElementNames or not isinstance(shape, Part.Shape) or shape.isNull() or shape.Solids:
            continue
        faces.extend((selection.Object, f"Face{i}", face) for i, face in enumerate(shape.Faces, 1))
    return faces


class CommandQuadMesh(PlanarFaceCommand):
    """Mesh the selected planar faces together into one parametric quad mesh,
    put it into the active FEM Analysis and open its task panel, as FreeCAD's
    Gmsh command does (femcommands/commands.py, _MeshGmshFromShape)."""

    name = "Quad mesh"

    def GetResources(self):
        return {
            "Pixmap": os.path.join(ICON_FOLDER, "MedialMesh_QuadMesh.svg"),
            "MenuText": "Quad mesh",
            "ToolTip": "Mesh the selected planar faces (or face objects picked in the tree) together with "
            "quads into one FEM mesh object, put into the active Analysis; set its parameters in the task panel",
        }

    def selection(self):
        return selected_faces_and_sheets()

    def run_on_selection(self):
        if FreeCADGui.Control.activeDialog():
            FreeCAD.Console.PrintError(f"MedialMesh: {self.name}: close the open task dialog first\n")
            return
        doc = FreeCAD.ActiveDocument
        faces = []
        for obj, subname, face in self.selection():
            if is_planar(face):
                faces.append((obj, subname))
            else:
                FreeCAD.Console.PrintError(f"MedialMesh: {obj.Label}.{subname}: the face is not planar; "
                                           "left out of the quad mesh\n")
        if not faces:
            FreeCAD.Console.PrintError(f"MedialMesh: {self.name}: no planar face selected\n")
            return
        import FemGui

        analysis = FemGui.getActiveAnalysis()
        if analysis is not None and analysis.Document != doc:
            analysis = None
        # The task panel ends this transaction: OK commits it, Cancel aborts
        # it and so takes the new object back (see taskpanels).
        doc.openTransaction(self.name)
        try:
            if len({obj.Name for obj, _ in faces}) == 1:
                mesh = objects.make_mesh_object(doc, faces[0][0], [subname for _, subname in faces],
                                                analysis=analysis)
            else:
                mesh = objects.make_mesh_object(doc, faces, None, analysis=analysis)
        except Exception:
            doc.abortTransaction()
            raise
        FreeCADGui.Selection.clearSelection()
        if mesh.Status.startswith("ok"):
            FreeCAD.Console.PrintMessage(f"MedialMesh: {mesh.Label}: {mesh.QuadCount} quads\n")
        opened = False
        try:
            mesh.ViewObject.Proxy.just_created = True
            opened = FreeCADGui.getDocument(doc.Name).setEdit(mesh.Name, 0)
        finally:
            if not opened:  # no panel to end the transaction: the object stays, as made
                doc.commitTransaction()
                if hasattr(mesh.ViewObject.Proxy, "just_created"):
                    mesh.ViewObject.Proxy.just_created = False


FreeCADGui.addCommand("MedialMesh_Analyse", CommandAnalyse())
FreeCADGui.addCommand("MedialMesh_Decompose", CommandDecompose())
FreeCADGui.addCommand("MedialMesh_QuadMesh", CommandQuadMesh())

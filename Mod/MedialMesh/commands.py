# SPDX-License-Identifier: LGPL-2.1-or-later
"""The workbench's commands.

Each is active as soon as something is selected in an open document; what
it cannot use (a curved face, an edge, a mesh, a solid where one face is
wanted) is named in the status bar and the report view with what it needs,
rather than the button staying grey with no word why. With nothing
selected the buttons are grey, and their tooltips say what to select.
"""

import os

import FreeCAD
import FreeCADGui
import Part

from . import objects
from .recording import doc_ref, made_by, obj_ref
from .viewproviders import ICON_FOLDER

STATUS_SECONDS = 15  # how long a message stays in the status bar


def is_planar(face):
    try:
        return face.findPlane() is not None
    except Exception:  # OCC refuses some degenerate faces: not plane then
        return False


def surface_name(face):
    """'cylinder', 'B-spline surface', ...: what a curved face is."""
    name = type(face.Surface).__name__  # Cylinder, BSplineSurface, SurfaceOfRevolution, ...
    return {"BSplineSurface": "B-spline surface", "BezierSurface": "Bezier surface",
            "SurfaceOfRevolution": "surface of revolution", "SurfaceOfExtrusion": "surface of extrusion",
            "OffsetSurface": "offset surface"}.get(name, name.lower())


def faces(count, what):
    """'1 curved face', '3 curved faces'."""
    return f"{count} {what}{'' if count == 1 else 's'}"


def explain(text, advice=""):
    """Say why a selection cannot be used: in the status bar (which has room
    for a line), and with the advice in the report view."""
    FreeCAD.Console.PrintWarning(f"MedialMesh: {text}{'. ' + advice if advice else ''}\n")
    # FreeCAD also puts a warning into the status bar, by a queued event
    # that would replace this shorter line: shown after it.
    from PySide import QtCore

    def show():
        try:
            FreeCADGui.getMainWindow().statusBar().showMessage(f"MedialMesh: {text}", STATUS_SECONDS * 1000)
        except Exception:  # no main window (a closing GUI): the report view has it
            pass

    QtCore.QTimer.singleShot(0, show)


class Selection:
    """What is selected, read for a command: the planar faces it can use,
    as (object, 'FaceN', face), and why the rest cannot be used."""

    def __init__(self, whole_solids):
        """whole_solids: a solid picked whole gives its planar faces (the
        Quad mesh command), rather than a request to pick one."""
        self.faces, self.problems = [], []
        for selection in FreeCADGui.Selection.getSelectionEx():
            obj = selection.Object
            if selection.SubElementNames:
                for subname, shape in zip(selection.SubElementNames, selection.SubObjects):
                    self.read_element(obj, subname, shape)
            else:
                self.read_object(obj, whole_solids)

    def read_element(self, obj, subname, shape):
        name = f"{obj.Label}.{subname}"
        if isinstance(shape, Part.Face):
            if is_planar(shape):
                self.faces.append((obj, subname, shape))
            else:
                self.problems.append(f"{name} is a curved face ({surface_name(shape)}): planar faces only")
        else:
            kind = {"Edge": "an edge", "Vertex": "a vertex"}.get(subname.rstrip("0123456789"), f"a {subname}")
            self.problems.append(f"{name} is {kind}, not a face")

    def read_object(self, obj, whole_solids):
        shape = getattr(obj, "Shape", None)
        if obj.isDerivedFrom("Fem::FemMeshObject") or obj.isDerivedFrom("Mesh::Feature"):
            self.problems.append(f"{obj.Label} is a mesh, not a part")
            return
        if not isinstance(shape, Part.Shape) or shape.isNull() or not shape.Faces:
            self.problems.append(f"{obj.Label} has no faces")
            return
        planar = [(obj, f"Face{i}", face) for i, face in enumerate(shape.Faces, 1) if is_planar(face)]
        curved = len(shape.Faces) - len(planar)
        if shape.Solids and not whole_solids:
            self.problems.append(f"{obj.Label} is a whole solid: pick one of its planar faces")
            return
        self.faces.extend(planar)
        if not planar:
            self.problems.append(f"{obj.Label} has no planar face")
        elif curved:
            self.problems.append(f"{obj.Label}: {faces(curved, 'curved face')} left out, "
                                 f"{faces(len(planar), 'planar face')} meshed")


class SelectionCommand:
    """A command on the selected planar faces: active when anything is
    selected; subclasses say what to do with the faces (run_on)."""

    name = ""  # the transaction's name, and the command's in messages
    whole_solids = False  # see Selection
    needs = ""  # what to select, for the messages

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and bool(FreeCADGui.Selection.getSelectionEx())

    def Activated(self):
        # Runs from a toolbar: nothing may escape into FreeCAD.
        try:
            selection = Selection(self.whole_solids)
            if not selection.faces:
                why = "; ".join(selection.problems) or "nothing it can use is selected"
                explain(f"{self.name}: {why}", f"To use it, {self.needs}")
                return
            for problem in selection.problems:
                explain(f"{self.name}: {problem}")
            self.run_on(selection.faces)
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: {self.name} failed: {error!r}\n")


class FaceCommand(SelectionCommand):
    """A command that makes one object per selected planar face, in one
    transaction; subclasses say what to make and what to tell the user."""

    needs = "select one or more planar faces (click them in the 3D view)"

    def run_on(self, faces):
        doc = FreeCAD.ActiveDocument
        doc.openTransaction(self.name)
        try:
            made = [made_by(doc, f"MedialMesh.{self.make_function}({doc_ref(doc)}, {obj_ref(obj)}, {subname!r})",
                            self.type_name) for obj, subname, _ in faces]
        finally:
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
            "and their mesh singularities with their k. Select planar faces in the 3D view first.",
            "StatusTip": "Analyse face: select one or more planar faces in the 3D view, then press",
        }

    make_function = "make_analysis_object"
    type_name = objects.TYPE

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
            "each holding at most one singularity; the splits also go into a Sketch on the face. "
            "Select planar faces in the 3D view first.",
            "StatusTip": "Decompose face: select one or more planar faces in the 3D view, then press",
        }

    make_function = "make_decomposition_object"
    type_name = objects.DECOMPOSITION_TYPE

    def summary(self, obj):
        return (f"{obj.SplitCount} splits, {obj.BlockCount} blocks ({obj.PolygonBlocks} polygon, "
                f"{obj.SubmapBlocks} submapped), {obj.FixedCount} fixed singularities")


class CommandQuadMesh(SelectionCommand):
    """Mesh the selected planar faces together into one parametric quad mesh,
    put it into the active FEM Analysis and open its task panel, as FreeCAD's
    Gmsh command does (femcommands/commands.py, _MeshGmshFromShape). The
    panel meshes it, off the GUI thread."""

    name = "Quad mesh"
    whole_solids = True
    needs = ("select planar faces in the 3D view, or a part, sketch face or sheet in the tree "
             "(its planar faces are meshed together)")

    def GetResources(self):
        return {
            "Pixmap": os.path.join(ICON_FOLDER, "MedialMesh_QuadMesh.svg"),
            "MenuText": "Quad mesh",
            "ToolTip": "Mesh the selected planar faces together with quads into one FEM mesh object, put into "
            "the active Analysis; set its parameters in the task panel. Select planar faces in the 3D view, "
            "or a whole part in the tree to mesh all its planar faces.",
            "StatusTip": "Quad mesh: select planar faces, or a part in the tree, then press",
        }

    def run_on(self, faces):
        if FreeCADGui.Control.activeDialog():
            explain(f"{self.name}: close the open task dialog first")
            return
        doc = FreeCAD.ActiveDocument
        import FemGui

        analysis = FemGui.getActiveAnalysis()
        if analysis is not None and analysis.Document != doc:
            analysis = None
        pairs = ", ".join(f"({obj_ref(obj)}, {subname!r})" for obj, subname, _ in faces)
        target = f"{obj_ref(analysis)}" if analysis is not None else "None"
        # The task panel ends this transaction: OK commits it, Cancel aborts
        # it and so takes the new object back (see taskpanels).
        doc.openTransaction(self.name)
        try:
            mesh = made_by(doc, f"MedialMesh.make_mesh_object({doc_ref(doc)}, [{pairs}], None, analysis={target}, "
                           "compute=False)", objects.QUAD_MESH_TYPE)
        except Exception:
            doc.abortTransaction()
            raise
        FreeCADGui.Selection.clearSelection()
        opened = False
        try:
            mesh.ViewObject.Proxy.just_created = True
            opened = FreeCADGui.getDocument(doc.Name).setEdit(mesh.Name, 0)
        finally:
            if not opened:  # no panel to mesh it and end the transaction: mesh it here, as made
                mesh.recompute()
                doc.commitTransaction()
                if hasattr(mesh.ViewObject.Proxy, "just_created"):
                    mesh.ViewObject.Proxy.just_created = False


FreeCADGui.addCommand("MedialMesh_Analyse", CommandAnalyse())
FreeCADGui.addCommand("MedialMesh_Decompose", CommandDecompose())
FreeCADGui.addCommand("MedialMesh_QuadMesh", CommandQuadMesh())

# SPDX-License-Identifier: LGPL-2.1-or-later
"""How the objects look: an analysis as the medial axis with its edges
coloured by flow type and the singularities as dots coloured by sign with
their k; a decomposition as its splits, with its Sketch as a child; a quad
mesh as FreeCAD draws any FEM mesh, with its decomposition Sketch as a child
and the task panel on double click."""

import os

import FreeCAD
import FreeCADGui
from pivy import coin

from . import analysis, decomposition, objects

ICON_FOLDER = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                           "Resources", "icons")


class ViewProviderMedialAnalysis:
    """Proxy of the view provider of a MedialMesh analysis object."""

    def __init__(self, vobj):
        vobj.Proxy = self
        vobj.LineWidth = 3
        vobj.PointSize = 1

    def attach(self, vobj):
        self.object = vobj.Object
        # The singularity marks ride along in every display mode. They sit
        # beside FreeCAD's display mode switch, which hiding the object turns
        # off, so they need a switch of their own (see onChanged).
        self.marks = coin.SoSeparator()
        self.marks_shown = coin.SoSwitch()
        self.marks_shown.addChild(self.marks)
        vobj.RootNode.addChild(self.marks_shown)
        self.show_marks(vobj)
        self.draw_marks(vobj.Object)

    def show_marks(self, vobj):
        self.marks_shown.whichChild = coin.SO_SWITCH_ALL if vobj.Visibility else coin.SO_SWITCH_NONE

    def updateData(self, obj, prop):
        try:
            if prop == "FlowTypes" and obj.ViewObject:
                obj.ViewObject.LineColorArray = [analysis.flow_colour(n) for n in obj.FlowTypes] or [(0.0, 0.0, 0.0)]
            elif prop == "SingularityK":
                self.draw_marks(obj)
        except Exception as error:  # drawing must never take FreeCAD down
            FreeCAD.Console.PrintError(f"MedialMesh: {obj.Label}: cannot draw the analysis: {error!r}\n")

    def draw_marks(self, obj):
        if not hasattr(self, "marks") or not hasattr(obj, "SingularityK"):
            return
        self.marks.removeAllChildren()
        positions, ks = obj.SingularityPositions, obj.SingularityK
        size = 0.02 * obj.Shape.BoundBox.DiagonalLength if obj.Shape.Edges else 1.0
        for point, k in zip(positions, ks):
            mark = coin.SoSeparator()
            colour = coin.SoBaseColor()
            colour.rgb = analysis.POSITIVE_COLOUR if k > 0 else analysis.NEGATIVE_COLOUR
            place = coin.SoTranslation()
            place.translation = (point.x, point.y, point.z)
            dot = coin.SoSphere()
            dot.radius = size
            font = coin.SoFont()
            font.size = 16
            label = coin.SoText2()
            label.string = f"{k:+d}"
            offset = coin.SoTranslation()
            offset.translation = (1.5 * size, 1.5 * size, 0)
            for node in (colour, place, dot, offset, font, label):
                mark.addChild(node)
            self.marks.addChild(mark)

    def onChanged(self, vobj, prop):
        if prop == "Visibility" and hasattr(self, "marks_shown"):
            self.show_marks(vobj)

    def getIcon(self):
        return os.path.join(ICON_FOLDER, "MedialMesh_Analyse.svg")

    def claimChildren(self):
        return []

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


class ViewProviderMedialDecomposition:
    """Proxy of the view provider of a MedialMesh decomposition object."""

    def __init__(self, vobj):
        vobj.Proxy = self
        vobj.LineWidth = 4
        vobj.LineColor = decomposition.SPLIT_COLOUR
        vobj.PointSize = 1

    def attach(self, vobj):
        self.object = vobj.Object
        # Lines lying exactly on a face fight it for depth and show in pieces;
        # lifted a hair off its front, as the Sketcher lifts what it edits,
        # they show whole.
        self.lift = coin.SoTranslation()
        vobj.RootNode.insertChild(self.lift, 0)
        self.update_lift(vobj.Object)

    def updateData(self, obj, prop):
        if prop == "Shape":
            self.update_lift(obj)

    def update_lift(self, obj):
        if not hasattr(self, "lift"):
            return
        try:
            face = objects.linked_face(obj)
            lift = face.normalAt(0, 0) * (1e-3 * face.BoundBox.DiagonalLength)
        except Exception:  # no face (Status says why): nothing drawn to lift
            lift = FreeCAD.Vector()
        self.lift.translation = (lift.x, lift.y, lift.z)

    def onChanged(self, vobj, prop):
        pass

    def getIcon(self):
        return os.path.join(ICON_FOLDER, "MedialMesh_Decompose.svg")

    def claimChildren(self):
        # The tree asks during restores and deletions too: never fail here.
        sketch = getattr(getattr(self, "object", None), "Sketch", None)
        return [sketch] if sketch else []

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


class ViewProviderMedialQuadMesh:
    """Proxy of the view provider (a ViewProviderFemMeshPython) of a MedialMesh
    quad mesh object, as FreeCAD's Gmsh mesh has (femviewprovider/view_mesh_gmsh.py)."""

    def __init__(self, vobj):
        vobj.Proxy = self  # FreeCAD calls attach

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object
        if not hasattr(vobj, "ColourByShape"):  # new, or from a document of an older version
            vobj.addProperty("App::PropertyBool", "ColourByShape", "Quality",
                             "Colour each element by its Verdict shape: red under 0.3 (poor), orange to yellow up "
                             "to 0.6, green from 0.8 (good)")
        self.panel = None  # the open task panel, if any
        # Set by the Quad mesh command just before it opens the panel on the
        # object it made: the panel then removes the object on Cancel.
        self.just_created = False

    def getIcon(self):
        return os.path.join(ICON_FOLDER, "MedialMesh_QuadMesh.svg")

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None  # FreeCAD's own editing (Transform, ...)
        from . import taskpanels

        try:
            self.panel = taskpanels.QuadMeshTaskPanel(vobj.Object, created=self.just_created)
            FreeCADGui.Control.showDialog(self.panel)
        except Exception as error:  # another dialog is open, ...: say so, do not enter edit mode
            FreeCAD.Console.PrintError(f"MedialMesh: {vobj.Object.Label}: cannot open the task panel: {error}\n")
            self.panel = None
            return False
        finally:
            self.just_created = False
        return True

    def unsetEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        self.panel = None
        FreeCADGui.Control.closeDialog()
        return True

    def doubleClicked(self, vobj):
        gui_doc = FreeCADGui.getDocument(vobj.Object.Document)
        if gui_doc.getInEdit() or FreeCADGui.Control.activeDialog():
            FreeCAD.Console.PrintError(
                f"MedialMesh: {vobj.Object.Label}: close the open task dialog before editing this mesh\n")
        else:
            gui_doc.setEdit(vobj.Object.Name)
        return True

    def claimChildren(self):
        # The tree asks during restores and deletions too: never fail here.
        sketch = getattr(getattr(self, "Object", None), "Sketch", None)
        return [sketch] if sketch else []

    def onDelete(self, vobj, subelements):
        # The decomposition Sketch belongs to this mesh alone: it goes with it.
        try:
            obj = vobj.Object
            sketch = obj.Sketch
            if sketch and all(o == obj for o in sketch.InList):
                obj.Sketch = None
                obj.Document.removeObject(sketch.Name)
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: cannot delete the mesh's sketch: {error!r}\n")
        return True

    def updateData(self, obj, prop):
        if prop in objects.MESH_PARAMETERS and getattr(obj.Document, "Transacting", False):
            self.follow_undo(obj)
        if prop != "FemMesh" or not obj.ViewObject:
            return
        # FreeCAD builds its mesh nodes after attach; by the first mesh they are there.
        if not getattr(self, "faces_pushed_back", False):
            try:
                self.faces_pushed_back = push_faces_back(obj.ViewObject.RootNode)
            except Exception as error:  # drawing must never take FreeCAD down
                FreeCAD.Console.PrintError(f"MedialMesh: {obj.Label}: cannot draw the mesh: {error!r}\n")
                self.faces_pushed_back = True  # once is enough
        if getattr(obj.ViewObject, "ColourByShape", False):
            # After FreeCAD's own view has rebuilt its drawing of the new
            # mesh, which comes after this call and would drop the colours.
            from PySide import QtCore

            vobj = obj.ViewObject
            QtCore.QTimer.singleShot(0, lambda: self.colour_elements(vobj))

    def follow_undo(self, obj):
        """FreeCAD's Undo and Redo restore the parameters and the Results but
        not the FemMesh: the mesh drawn would not be the one the values say.
        Recomputed once the Undo is done, the object takes the mesh back from
        its recent ones (objects.store_mesh), or meshes again."""
        if getattr(self, "follow_undo_pending", False):
            return  # one recompute for all the values one Undo restores
        self.follow_undo_pending = True
        doc_name, name = obj.Document.Name, obj.Name

        def recompute():
            self.follow_undo_pending = False
            try:
                undone = FreeCAD.getDocument(doc_name).getObject(name)
                if undone is not None and "Touched" in undone.State:
                    undone.recompute()
                    undone.purgeTouched()  # the mesh is the values' again
            except Exception as error:  # a timer's slot: nothing may escape into FreeCAD
                FreeCAD.Console.PrintError(f"MedialMesh: {name}: cannot follow the Undo: {error!r}\n")

        from PySide import QtCore

        QtCore.QTimer.singleShot(0, recompute)

    def onChanged(self, vobj, prop):
        if prop == "ColourByShape" and getattr(self, "Object", None) is not None:
            self.colour_elements(vobj)

    def colour_elements(self, vobj):
        """Each element coloured by its shape, or FreeCAD's one colour again.
        FreeCAD 1.0 shows ElementColor only in its ColorMode 'ByElement'
        (0.20 has no ColorMode, and shows it at once)."""
        try:
            on = vobj.ColourByShape and vobj.Object.FemMesh.FaceCount > 0
            if on:
                colours = shape_colours(element_shapes(vobj.Object)).tolist()
                vobj.ElementColor = {i: tuple(c) for i, c in enumerate(colours, 1)}
            else:
                vobj.ElementColor = {}
            if "ColorMode" in vobj.PropertiesList:
                vobj.ColorMode = "ByElement" if on else "Overall"
        except Exception as error:  # drawing must never take FreeCAD down
            FreeCAD.Console.PrintError(f"MedialMesh: cannot colour the mesh: {error!r}\n")  # the object may be gone

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


FACE_OFFSET = 3.0  # the depth offset of the mesh faces, see push_faces_back
# The colours of element shape (shape_colours): red at 0 through the poor
# bar (0.3) to orange, yellow at 0.6, green from 0.8 (linear between).
SHAPE_COLOURS = [(0.0, (0.85, 0.0, 0.0)), (0.3, (1.0, 0.45, 0.0)), (0.6, (1.0, 0.9, 0.2)), (0.8, (0.45, 0.8, 0.35)),
                 (1.0, (0.3, 0.7, 0.3))]


def shape_colours(shapes):
    """The colour of each of an array of Verdict shapes (0 to 1), as an (M, 3) float32 array."""
    import numpy

    stops = [stop for stop, _ in SHAPE_COLOURS]
    channels = [numpy.interp(shapes, stops, [colour[c] for _, colour in SHAPE_COLOURS]) for c in range(3)]
    return numpy.stack(channels, axis=1).astype(numpy.float32)


def element_shapes(obj):
    """The Verdict shape of each element of the quad mesh object, in element
    id order: as the mesher measured them when it made the mesh in this
    session, else measured again from the FemMesh (a document reopened)."""
    shapes = getattr(obj.Proxy, "element_shape", None)
    femmesh = obj.FemMesh
    if shapes is None or len(shapes) != femmesh.FaceCount:
        from . import meshing

        shapes = meshing.femmesh_shapes(femmesh)
        obj.Proxy.element_shape = shapes
    return shapes


def push_faces_back(root):
    """FreeCAD's FEM mesh view draws the element edges at the depth of the
    element faces, and they lose to the faces: 'Faces & Wireframe' shows no
    edges, and a mesh of a face of a solid fights that face in patches.
    Pushed back in depth more than FreeCAD pushes a part's faces (between 1
    and 2 here, measured), the element faces let through their own edges and
    the part's face, on which the edges then show; with the part hidden, the
    faces show with their edges. Returns whether the faces were found."""
    search = coin.SoSearchAction()
    search.setType(coin.SoIndexedFaceSet.getClassTypeId())
    search.setInterest(coin.SoSearchAction.FIRST)
    search.setSearchingAll(True)  # in every display mode, shown or not
    search.apply(root)
    path = search.getPath()
    if path is None:
        return False
    offset = coin.SoPolygonOffset()
    offset.factor = FACE_OFFSET
    offset.units = FACE_OFFSET
    offset.styles = coin.SoPolygonOffset.FILLED
    # The faces' group is shared by the display modes showing faces and is a
    # plain group: the offset reaches the faces, and lines ignore it.
    path.getNodeFromTail(1).insertChild(offset, 0)
    return True

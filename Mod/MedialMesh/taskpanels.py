# SPDX-License-Identifier: LGPL-2.1-or-later
"""The task panel of a MedialMesh quad mesh object, as FreeCAD's Gmsh mesh
has one (femtaskpanels/task_mesh_gmsh.py).

It edits ElementSize, MergeFactor, ElementOrder and Smoothing. Preview meshes
the linked faces with the panel's values in a worker thread (the core lets go
of the GIL while it meshes, so the GUI keeps drawing) and shows the mesh and
the decomposition splits in the 3D view as a Coin node of the view, not of the
document; the object itself is hidden meanwhile. Nothing in the document
changes before OK. OK and Cancel wait for a running preview to finish: the
core cannot be stopped, and FreeCAD's meshes must not be built in two threads
at once.

OK writes the values that changed into the object and recomputes, in one
transaction. Cancel leaves the document as it was. When the Quad mesh command
opened the panel on the object it had just made (created=True), that object
is part of what Cancel takes back: the command's transaction is still open
and Cancel aborts it (before resetEdit, which would commit it), as
PartDesign's feature panels do, so the object, its Sketch and its place in
the Analysis go and the undo stack is as before; OK commits it as one undo
step.
"""

import threading
import time

import FreeCAD
import FreeCADGui
from pivy import coin
from PySide import QtCore, QtGui

from . import decomposition, objects, viewproviders

PREVIEW_FACE_COLOUR = (0.82, 0.88, 1.0)
PREVIEW_EDGE_COLOUR = (0.1, 0.15, 0.45)
# A mesh bigger than this (in estimated quads) would take minutes and
# gigabytes; the panel refuses it with a message rather than hang.
MAX_QUADS = 2_000_000
SHOW_PROGRESS_AFTER = 1.0  # seconds: shorter runs just finish
NO_MERGING = 0.2  # the merge factor field's minimum, which stands for 0: no merging
QUALITY_LINES = 9  # the quality summary: a heading, six lines, room to wrap


def too_many_quads(faces, size, names):
    """Why meshing the faces with this element size is refused, or None."""
    if size <= 0:
        return None  # automatic: some 400 quads a face
    estimate = sum(face.Area for face in faces) / size**2
    if estimate <= MAX_QUADS:
        return None
    return (f"{names}: element size {size:g} mm gives about {estimate:.3g} quads; "
            f"choose a larger size (at most {MAX_QUADS} quads)")


def quality_text(quality, separator=", "):
    return separator.join((
        f"{quality['quads']} quads, {quality['nodes']} nodes",
        f"shape min {quality['min_shape']:.3f} mean {quality['mean_shape']:.3f}",
        f"edge ratio max {quality['max_edge_ratio']:.1f}",
        f"{quality['poor_shape']} of shape < 0.3, {quality['needles']} over 10:1",
        f"scaled Jacobian min {quality['min_scaled_jacobian']:.3f}",
        f"{quality['irregular_nodes']} irregular nodes, {quality['seconds']:.2f} s"))


def fallback_line(obj):
    """The Status's fallback on a line of its own, or nothing."""
    status = obj.Status
    return "\n" + status[len("ok ("):-1] if status.startswith("ok (") else ""


class QuadMeshTaskPanel:
    """Task dialog (shown with FreeCADGui.Control.showDialog) editing one
    MedialMesh quad mesh object."""

    def __init__(self, obj, created=False):
        self.obj = obj
        self.obj_name = obj.Name  # for messages once the object is gone
        self.label = obj.Label
        self.doc = obj.Document
        self.created = created
        self.worker = None  # the preview's thread while it runs
        self.outcome = {}  # the preview's face names, and what the worker left: 'result' and 'geometry', or 'error'
        self.started = 0.0
        self.preview_root = None  # (scene graph, node) of the preview shown
        self.hidden_object = False  # the object hidden to show the preview
        self.form = self.build_form()
        self.timer = QtCore.QTimer()
        self.timer.setInterval(100)
        self.timer.timeout.connect(self.poll)
        self.load_values()
        self.show_object_results()

    # --- the widgets -------------------------------------------------------

    def build_form(self):
        form = QtGui.QWidget()
        form.setObjectName("MedialMeshQuadMeshPanel")
        form.setWindowTitle("Quad mesh")
        form.setWindowIcon(QtGui.QIcon(self.obj.ViewObject.Proxy.getIcon()))
        layout = QtGui.QVBoxLayout(form)

        parameters = QtGui.QGroupBox("Parameters")
        rows = QtGui.QFormLayout(parameters)
        self.faces_label = QtGui.QLabel()
        self.faces_label.setObjectName("faces")
        self.faces_label.setWordWrap(True)
        rows.addRow("Faces:", self.faces_label)
        # FreeCAD's own length field: shows and reads lengths in the user's unit schema.
        self.size = FreeCADGui.UiLoader().createWidget("Gui::QuantitySpinBox")
        self.size.setObjectName("elementSize")
        self.size.setProperty("unit", "mm")
        self.size.setProperty("minimum", 0.0)
        self.size.setToolTip("Target element size; 0: automatic (the faces' bounding box diagonal / 20)")
        rows.addRow("Element size:", self.size)
        self.merge = QtGui.QDoubleSpinBox()
        self.merge.setObjectName("mergeFactor")
        # The factors the core takes are 0.25 to 1; one step below them is
        # the spin box's minimum, shown as "no merging", so no other value
        # can be entered.
        self.merge.setRange(NO_MERGING, 1.0)
        self.merge.setSingleStep(0.05)
        self.merge.setDecimals(2)
        self.merge.setSpecialValueText("no merging")
        self.merge.setToolTip("Merge singularities closer than this factor (0.25 to 1) times their medial "
                              "radius into one; 0: no merging")
        rows.addRow("Merge factor:", self.merge)
        self.order = QtGui.QComboBox()
        self.order.setObjectName("elementOrder")
        self.order.addItems(self.obj.getEnumerationsOfProperty("ElementOrder"))
        self.order.setToolTip("1st: 4-node quads; 2nd: 8-node quads")
        rows.addRow("Element order:", self.order)
        self.smooth = QtGui.QCheckBox("Smoothing")
        self.smooth.setObjectName("smoothing")
        self.smooth.setToolTip("Smooth the nodes inside each block")
        rows.addRow(self.smooth)
        # The task view is often narrower than the fields' size hints (the
        # length field's allows for huge numbers): let them shrink to it.
        for field in (self.size, self.merge, self.order):
            field.setMinimumWidth(60)
        layout.addWidget(parameters)

        preview = QtGui.QGroupBox("Preview")
        column = QtGui.QVBoxLayout(preview)
        self.preview_button = QtGui.QPushButton("Preview")
        self.preview_button.setObjectName("preview")
        self.preview_button.setToolTip("Mesh with these values and show the mesh and the decomposition "
                                       "in the 3D view; the object changes only on OK")
        self.preview_button.clicked.connect(self.start_preview)
        column.addWidget(self.preview_button)
        self.progress = QtGui.QProgressBar()
        self.progress.setObjectName("progress")
        self.progress.setRange(0, 0)  # busy: the core does not say how far it is
        self.progress.setTextVisible(False)
        self.progress.hide()
        column.addWidget(self.progress)
        self.quality = QtGui.QLabel()
        self.quality.setObjectName("quality")
        self.quality.setWordWrap(True)
        self.quality.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        # FreeCAD's task box keeps the height it had when shown: room for the
        # summary's lines (and a wrapped one or two) from the start.
        self.quality.setMinimumHeight(QUALITY_LINES * self.quality.fontMetrics().lineSpacing())
        column.addWidget(self.quality)
        layout.addWidget(preview)
        layout.addStretch()
        return form

    def load_values(self):
        try:
            names = ", ".join(objects.linked_faces(self.obj)[1])
        except Exception as error:  # shown; Preview and OK report it again
            names = f"({error})"
        self.faces_label.setText(names)
        self.size.setProperty("rawValue", self.obj.ElementSize.Value)
        self.merge.setValue(self.obj.MergeFactor if self.obj.MergeFactor >= 0.25 else NO_MERGING)
        self.order.setCurrentIndex(max(0, self.order.findText(self.obj.ElementOrder)))
        self.smooth.setChecked(self.obj.Smoothing)

    def values(self):
        """The panel's values as the object's properties take them."""
        return {
            "ElementSize": float(self.size.property("rawValue")),
            "MergeFactor": 0.0 if self.merge.value() <= NO_MERGING else round(self.merge.value(), 4),
            "ElementOrder": self.order.currentText(),
            "Smoothing": self.smooth.isChecked(),
        }

    def show_object_results(self):
        obj = self.obj
        if obj.Status.startswith("ok"):
            self.show_message("Current mesh:\n" + quality_text(self.object_quality(), "\n") + fallback_line(obj))
        else:
            self.show_message(f"Current mesh: {obj.Status or 'not computed'}", error=bool(obj.Status))

    def show_message(self, text, error=False):
        self.quality.setStyleSheet("color: #c00000" if error else "")
        self.quality.setText(text)

    def report_error(self, message):
        """In the panel and in the report view, naming the object (the
        message names the face)."""
        self.show_message(message, error=True)
        FreeCAD.Console.PrintError(f"MedialMesh: {self.label}: {message}\n")

    # --- preview ------------------------------------------------------------

    def start_preview(self):
        # A Qt slot: nothing may escape into FreeCAD.
        try:
            self.run_preview()
        except Exception as error:
            self.report_error(f"preview failed: {error!r}")

    def run_preview(self):
        if self.busy():
            return
        try:
            faces, names = objects.linked_faces(self.obj)
        except Exception as error:
            self.report_error(str(error))
            return
        values = self.values()
        too_many = too_many_quads(faces, values["ElementSize"], ",".join(names))
        if too_many:
            self.report_error(too_many)
            return
        from .meshing import mesh_face

        arguments = objects.mesh_arguments(values["ElementSize"], values["ElementOrder"], values["MergeFactor"],
                                           values["Smoothing"])
        arguments["name"] = names
        outcome = {"names": ",".join(names)}

        def work():
            try:
                result = mesh_face(faces if len(faces) > 1 else faces[0], **arguments)
                outcome["geometry"] = preview_geometry(result)
                outcome["result"] = result
            except Exception as error:  # handed to the GUI thread
                outcome["error"] = error

        self.outcome = outcome
        self.started = time.monotonic()
        self.worker = threading.Thread(target=work, name="MedialMesh preview", daemon=True)
        self.worker.start()
        self.preview_button.setEnabled(False)
        self.show_message("Meshing ...")
        self.timer.start()

    def busy(self):
        return self.worker is not None and self.worker.is_alive()

    def poll(self):
        try:
            self.check_worker()
        except Exception as error:
            self.report_error(f"preview failed: {error!r}")

    def check_worker(self):
        elapsed = time.monotonic() - self.started
        if self.busy():
            if elapsed > SHOW_PROGRESS_AFTER:
                self.progress.show()
                self.show_message(f"Meshing ... {elapsed:.1f} s")
            return
        self.timer.stop()
        self.worker = None
        self.progress.hide()
        self.preview_button.setEnabled(True)
        if "error" in self.outcome:
            error = self.outcome["error"]
            message = str(error) if isinstance(error, ValueError) else f"internal error: {error!r}"
            if self.outcome["names"] not in message:  # a few core messages do not name the face
                message = f"{self.outcome['names']}: {message}"
            self.report_error(message)
            return
        result = self.outcome["result"]
        self.show_preview(self.outcome["geometry"])
        text = "Preview:\n" + quality_text(result.quality, "\n")
        if result.fallbacks:
            text += "\nfallback: " + ", ".join(result.fallbacks)
        if result.notes:
            text += "\n" + "\n".join(result.notes)
        self.show_message(text)

    def wait_for_worker(self):
        """Let a running preview finish: the meshing cannot be stopped, and
        FreeCAD must not build meshes in two threads at once."""
        if self.worker is None:
            return
        QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        try:
            self.worker.join()
        finally:
            QtGui.QApplication.restoreOverrideCursor()
        self.timer.stop()
        self.worker = None

    def show_preview(self, geometry):
        self.remove_preview()
        view = FreeCADGui.getDocument(self.doc.Name).ActiveView
        graph = view.getSceneGraph()
        node = preview_node(geometry)
        graph.addChild(node)
        self.preview_root = (graph, node)
        if not self.hidden_object and self.obj.ViewObject.Visibility:
            self.obj.ViewObject.Visibility = False
            self.hidden_object = True

    def remove_preview(self):
        if self.preview_root:
            graph, node = self.preview_root
            graph.removeChild(node)
            self.preview_root = None

    def clean_up(self):
        """Take the preview out of the view and show the object again."""
        self.wait_for_worker()
        try:
            self.remove_preview()
        except Exception as error:  # the view is gone
            FreeCAD.Console.PrintLog(f"MedialMesh: preview already gone: {error!r}\n")
        if self.hidden_object:
            self.obj.ViewObject.Visibility = True
            self.hidden_object = False

    # --- OK and Cancel --------------------------------------------------------

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        try:
            faces, names = objects.linked_faces(self.obj)
            too_many = too_many_quads(faces, self.values()["ElementSize"], ",".join(names))
        except Exception:  # no faces: the object's recompute says why
            too_many = None
        if too_many:  # the panel stays open for a larger size
            self.report_error(too_many)
            return False
        try:
            self.clean_up()
            self.apply()
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: {self.label}: applying the values failed: {error!r}\n")
        self.close()
        return True

    def apply(self):
        obj, doc = self.obj, self.doc
        if not self.created:
            doc.openTransaction("Edit quad mesh")
        for name, value in self.values().items():
            current = obj.ElementSize.Value if name == "ElementSize" else getattr(obj, name)
            if value != current:
                setattr(obj, name, value)
        QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        try:
            doc.recompute()
        finally:
            QtGui.QApplication.restoreOverrideCursor()
            doc.commitTransaction()
        if obj.Status.startswith("ok"):  # a failure is in the report view already (see objects)
            FreeCAD.Console.PrintMessage(f"MedialMesh: {obj.Label}: {quality_text(self.object_quality())}\n")

    def object_quality(self):
        obj = self.obj
        return {"quads": obj.QuadCount, "nodes": obj.NodeCount, "min_scaled_jacobian": obj.MinScaledJacobian,
                "mean_scaled_jacobian": obj.MeanScaledJacobian, "min_shape": obj.MinShape,
                "mean_shape": obj.MeanShape, "max_edge_ratio": obj.MaxEdgeRatio, "poor_shape": obj.PoorShapeCount,
                "needles": obj.NeedleCount, "irregular_nodes": obj.IrregularNodes, "seconds": obj.Seconds}

    def reject(self):
        try:
            self.clean_up()
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: {self.label}: closing the preview failed: {error!r}\n")
        # Before resetEdit, which commits the transaction still open.
        if self.created:
            self.take_back_creation()
        self.close()
        return True

    def take_back_creation(self):
        """Cancel right after the Quad mesh command: abort its transaction;
        should it have been committed meanwhile (another command ran), remove
        the objects it made."""
        doc = self.doc
        try:
            doc.abortTransaction()
            obj = doc.getObject(self.obj_name)
            if obj is not None:
                sketch = obj.Sketch
                doc.removeObject(obj.Name)
                if sketch is not None:
                    doc.removeObject(sketch.Name)
            doc.recompute()
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: {self.label}: cannot remove the new mesh: {error!r}\n")

    def close(self):
        try:
            FreeCADGui.getDocument(self.doc.Name).resetEdit()
        except Exception as error:  # the document is being closed
            FreeCAD.Console.PrintLog(f"MedialMesh: {self.label}: {error!r}\n")


def preview_geometry(result):
    """The preview as flat lists, ready for Coin: the mesh's node positions,
    its elements as polygons (corner, mid-side node, next corner ...), its
    element edges as index pairs, and the splits as polylines. Plain Python
    work, done in the worker thread so that the GUI keeps running."""
    femmesh = result.femmesh
    positions = femmesh.Nodes
    node_ids = sorted(positions)
    index = {node_id: i for i, node_id in enumerate(node_ids)}
    polygons, edges = [], set()
    for face_id in femmesh.Faces:
        element = [index[n] for n in femmesh.getElementNodes(face_id)]
        corners, midsides = element[:4], element[4:]
        loop = []
        for c in range(4):
            loop.append(corners[c])
            if midsides:
                loop.append(midsides[c])
        polygons.extend(loop)
        polygons.append(-1)
        edges.update((min(a, b), max(a, b)) for a, b in zip(loop, loop[1:] + loop[:1]))
    splits = [[(p.x, p.y, p.z) for p in edge.discretize(QuasiDeflection=1e-3 * max(edge.Length, 1e-9))]
              for split in result.splits for edge in split.Edges]
    return {
        "points": [(p.x, p.y, p.z) for p in (positions[n] for n in node_ids)],
        "polygons": polygons,
        "edges": [i for a, b in sorted(edges) for i in (a, b, -1)],
        "splits": splits,
    }


def preview_node(geometry):
    """A Coin node of the mesh (faces and element edges) and the splits. The
    faces are pushed back in depth, as the mesh object's are (see
    viewproviders.push_faces_back): the edges show on them and on the face
    of a part they lie on."""
    root = coin.SoSeparator()
    root.setName("MedialMeshPreview")
    unpickable = coin.SoPickStyle()
    unpickable.style = coin.SoPickStyle.UNPICKABLE
    root.addChild(unpickable)
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    root.addChild(light)
    coordinates = coin.SoCoordinate3()
    coordinates.point.setValues(0, len(geometry["points"]), geometry["points"])
    root.addChild(coordinates)

    faces = coin.SoSeparator()
    offset = coin.SoPolygonOffset()
    offset.factor = viewproviders.FACE_OFFSET
    offset.units = viewproviders.FACE_OFFSET
    faces.addChild(offset)
    faces.addChild(base_colour(PREVIEW_FACE_COLOUR))
    face_set = coin.SoIndexedFaceSet()
    face_set.coordIndex.setValues(0, len(geometry["polygons"]), geometry["polygons"])
    faces.addChild(face_set)
    root.addChild(faces)

    root.addChild(base_colour(PREVIEW_EDGE_COLOUR))
    line_set = coin.SoIndexedLineSet()
    line_set.coordIndex.setValues(0, len(geometry["edges"]), geometry["edges"])
    root.addChild(line_set)

    splits = geometry["splits"]
    if splits:  # drawn last: where they run along element edges, they show
        root.addChild(base_colour(decomposition.SPLIT_COLOUR))
        style = coin.SoDrawStyle()
        style.lineWidth = 3
        root.addChild(style)
        split_points = coin.SoCoordinate3()
        flat = [p for line in splits for p in line]
        split_points.point.setValues(0, len(flat), flat)
        root.addChild(split_points)
        split_lines = coin.SoLineSet()
        split_lines.numVertices.setValues(0, len(splits), [len(line) for line in splits])
        root.addChild(split_lines)
    return root


def base_colour(rgb):
    colour = coin.SoBaseColor()
    colour.rgb = rgb
    return colour

# SPDX-License-Identifier: LGPL-2.1-or-later
"""The task panel of a MedialMesh quad mesh object, as FreeCAD's Gmsh mesh
has one (femtaskpanels/task_mesh_gmsh.py).

It edits ElementSize, MergeFactor, ElementOrder and Smoothing. Meshing runs
in a worker thread (the core lets go of the GIL while it meshes, and the
FemMesh is built in chunks), never on the GUI thread: a progress bar tells
the stage and the blocks done, Stop (and Cancel) stop it within a step.
Preview shows the mesh and the decomposition splits in the 3D view as a
Coin node of the view, not of the document; the object itself is hidden
meanwhile. Nothing in the document changes before OK.

Mesh once: OK stores the mesh the panel made for the values shown (by
Preview, or by the run the panel starts on a new object) into the object
without meshing again. When there is none (the values changed since), OK
meshes in the worker with the progress bar and stores the result when it is
done; the panel closes then. Handing the mesh to FreeCAD (the FemMesh
property, drawn by FreeCAD's FEM mesh view) is the one step on the GUI
thread.

OK writes the values that changed into the object, in one transaction.
Cancel stops a run and leaves the document as it was. When the Quad mesh
command opened the panel on the object it had just made (created=True),
that object is part of what Cancel takes back: the command's transaction
is still open and Cancel aborts it (before resetEdit, which would commit
it), as PartDesign's feature panels do, so the object, its Sketch and its
place in the Analysis go and the undo stack is as before; OK commits it as
one undo step.
"""

import threading
import time

import FreeCAD
import FreeCADGui
import numpy
from pivy import coin
from PySide import QtCore, QtGui

from . import decomposition, meshing, messages, objects, recording, viewproviders

PREVIEW_FACE_COLOUR = (0.82, 0.88, 1.0)
PREVIEW_EDGE_COLOUR = (0.1, 0.15, 0.45)
# A mesh bigger than this (in estimated quads) would take minutes and
# gigabytes; the panel refuses it with a message rather than hang.
MAX_QUADS = 2_000_000
PREVIEW_EDGES_UP_TO = 200_000  # elements; a preview of more draws their faces only
PREVIEW_STEP = 250_000  # values copied into Coin between two turns of the GUI's event loop
POLL_SECONDS = 0.1  # how often the panel reads the worker's progress
NO_MERGING = 0.2  # the merge factor field's minimum, which stands for 0: no merging
QUALITY_LINES = 8  # the quality summary: a heading, six lines, room to wrap
MESSAGE_ROWS = 6  # the messages list's height in rows; it scrolls beyond
WARNING_COLOUR = "#a05a00"


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


class MeshRun:
    """One meshing of the panel's faces with one set of values, in a worker
    thread: its progress, and when done its result or error."""

    def __init__(self, faces, names, values):
        self.values = values
        self.names = ", ".join(names)
        self.progress = meshing.Progress()
        self.result = None  # a FaceMesh
        self.geometry = None  # its preview, as flat lists for Coin
        self.error = None
        self.started = time.monotonic()
        arguments = objects.mesh_arguments(values["ElementSize"], values["ElementOrder"], values["MergeFactor"],
                                           values["Smoothing"])

        def work():
            try:
                result = meshing.mesh_face(faces if len(faces) > 1 else faces[0], name=names,
                                           progress=self.progress, **arguments)
                self.geometry = preview_geometry(result)
                self.result = result
            except BaseException as error:  # handed to the GUI thread
                self.error = error

        self.thread = threading.Thread(target=work, name="MedialMesh meshing", daemon=True)
        self.thread.start()

    def running(self):
        return self.thread.is_alive()

    def stop(self):
        """Cancel, and wait for the worker: it stops within a step."""
        self.progress.cancel()
        self.thread.join()


class QuadMeshTaskPanel:
    """Task dialog (shown with FreeCADGui.Control.showDialog) editing one
    MedialMesh quad mesh object."""

    def __init__(self, obj, created=False):
        self.obj = obj
        self.obj_name = obj.Name  # for messages once the object is gone
        self.label = obj.Label
        self.doc = obj.Document
        self.created = created
        self.run = None  # the MeshRun running or last done
        self.closing_after_run = False  # OK was pressed: store the run's outcome and close when it is done
        self.preview_root = None  # (scene graph, node) of the preview shown
        self.preview_build = None  # the steps of a preview being built (preview_steps)
        self.hidden_object = False  # the object hidden to show the preview
        self.faces, self.names, self.faces_error = [], [], None
        try:
            self.faces, self.names = objects.linked_faces(obj)
        except Exception as error:  # shown; Preview and OK report it again
            self.faces_error = error
        self.form = self.build_form()
        self.timer = QtCore.QTimer()
        self.timer.setInterval(int(POLL_SECONDS * 1000))
        self.timer.timeout.connect(self.poll)
        self.load_values()
        self.show_object_results()
        if obj.Status == objects.NOT_MESHED:  # made by the Quad mesh command: mesh it now, off the GUI thread
            self.start_run()

    # --- the widgets -------------------------------------------------------

    def build_form(self):
        form = QtGui.QWidget()
        form.setObjectName("MedialMeshQuadMeshPanel")
        form.setWindowTitle("Quad mesh")
        form.setWindowIcon(QtGui.QIcon(self.obj.ViewObject.Proxy.getIcon()))
        layout = QtGui.QVBoxLayout(form)

        parameters = QtGui.QGroupBox("Parameters")
        rows = QtGui.QFormLayout(parameters)
        rows.setRowWrapPolicy(QtGui.QFormLayout.WrapLongRows)  # fields under their labels in a narrow task view
        self.faces_label = QtGui.QLabel()
        self.faces_label.setObjectName("faces")
        self.faces_label.setWordWrap(True)
        rows.addRow("Faces:", self.faces_label)
        # FreeCAD's own length field: shows and reads lengths in the user's unit schema.
        self.size = FreeCADGui.UiLoader().createWidget("Gui::QuantitySpinBox")
        self.size.setObjectName("elementSize")
        self.size.setProperty("unit", "mm")
        self.size.setProperty("minimum", 0.0)
        self.size.setToolTip("Target element size; 0: automatic, the faces' bounding box diagonal / 20 "
                             "(shown below the field)")
        self.size.valueChanged.connect(self.show_automatic_size)
        rows.addRow("Element size:", self.size)
        self.automatic_size = QtGui.QLabel()
        self.automatic_size.setObjectName("automaticSize")
        self.automatic_size.setWordWrap(True)
        rows.addRow("", self.automatic_size)
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
        self.faces_label.setMinimumWidth(40)
        layout.addWidget(parameters)

        mesh = QtGui.QGroupBox("Mesh")
        column = QtGui.QVBoxLayout(mesh)
        buttons = QtGui.QHBoxLayout()
        self.preview_button = QtGui.QPushButton("Preview")
        self.preview_button.setObjectName("preview")
        self.preview_button.setToolTip("Mesh with these values and show the mesh and the decomposition "
                                       "in the 3D view; the object changes only on OK, which keeps this mesh")
        self.preview_button.clicked.connect(lambda: self.guarded(self.start_preview))
        buttons.addWidget(self.preview_button)
        self.stop_button = QtGui.QPushButton("Stop")
        self.stop_button.setObjectName("stop")
        self.stop_button.setToolTip("Stop the meshing running; the panel stays open")
        self.stop_button.setEnabled(False)
        self.stop_button.clicked.connect(lambda: self.guarded(self.stop_run))
        buttons.addWidget(self.stop_button)
        column.addLayout(buttons)
        self.progress = QtGui.QProgressBar()
        self.progress.setObjectName("progress")
        self.progress.setRange(0, 1000)
        self.progress.setTextVisible(False)
        self.progress.hide()
        column.addWidget(self.progress)
        self.stage = QtGui.QLabel()
        self.stage.setObjectName("stage")
        self.stage.hide()
        column.addWidget(self.stage)
        self.quality = QtGui.QLabel()
        self.quality.setObjectName("quality")
        self.quality.setWordWrap(True)
        self.quality.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        # FreeCAD's task box keeps the height it had when shown: room for the
        # summary's lines (and a wrapped one or two) from the start.
        self.quality.setMinimumHeight(QUALITY_LINES * self.quality.fontMetrics().lineSpacing())
        column.addWidget(self.quality)
        self.colour = QtGui.QCheckBox("Colour by shape")
        self.colour.setObjectName("colourByShape")
        self.colour.setToolTip("Colour each element by its Verdict shape: red under 0.3 (poor), orange to "
                               "yellow up to 0.6, green from 0.8 (good); in the preview and on the mesh object")
        self.colour.setChecked(bool(getattr(self.obj.ViewObject, "ColourByShape", False)))
        self.colour.toggled.connect(lambda on: self.guarded(self.colour_changed, on))
        column.addWidget(self.colour)
        # The messages: a list that scrolls, and wraps its lines to the
        # panel's width rather than widening the panel.
        self.messages = QtGui.QListWidget()
        self.messages.setObjectName("messages")
        self.messages.setWordWrap(True)
        self.messages.setTextElideMode(QtCore.Qt.ElideNone)
        self.messages.setHorizontalScrollBarPolicy(QtCore.Qt.ScrollBarAlwaysOff)
        self.messages.setSizePolicy(QtGui.QSizePolicy.Ignored, QtGui.QSizePolicy.Fixed)
        self.messages.setFixedHeight(MESSAGE_ROWS * self.messages.fontMetrics().lineSpacing())
        self.messages.setToolTip("What the mesher did, grouped; the full notes are in the object's Notes")
        column.addWidget(self.messages)
        layout.addWidget(mesh)
        layout.addStretch()
        return form

    def guarded(self, action, *arguments):
        """Run a Qt slot's work: nothing may escape into FreeCAD."""
        try:
            action(*arguments)
        except Exception as error:
            self.report_error(messages.failure_message(error, self.face_names()))

    def load_values(self):
        self.faces_label.setText(", ".join(self.names) if self.names else f"({self.faces_error})")
        self.size.setProperty("rawValue", self.obj.ElementSize.Value)
        self.merge.setValue(self.obj.MergeFactor if self.obj.MergeFactor >= 0.25 else NO_MERGING)
        self.order.setCurrentIndex(max(0, self.order.findText(self.obj.ElementOrder)))
        self.smooth.setChecked(self.obj.Smoothing)
        self.show_automatic_size()

    def show_automatic_size(self, *_):
        automatic = self.faces and float(self.size.property("rawValue")) == 0.0
        self.automatic_size.setText(f"Automatic ({meshing.automatic_size(self.faces):.4g} mm)" if automatic else "")

    def values(self):
        """The panel's values as the object's properties take them."""
        return {
            "ElementSize": float(self.size.property("rawValue")),
            "MergeFactor": 0.0 if self.merge.value() <= NO_MERGING else round(self.merge.value(), 4),
            "ElementOrder": self.order.currentText(),
            "Smoothing": self.smooth.isChecked(),
        }

    def face_names(self):
        return ", ".join(self.names) or self.label

    def show_object_results(self):
        obj = self.obj
        if obj.Status.startswith("ok"):
            fallback = f"\nfallback: {obj.Status[len('ok (fallback: '):-1]}" if obj.Status.startswith("ok (") else ""
            self.show_message("Current mesh:\n" + quality_text(self.object_quality(), "\n") + fallback)
            self.show_notes(list(obj.Notes))
        elif obj.Status == objects.NOT_MESHED:
            self.show_message("")
        else:
            self.show_message(f"Current mesh: {obj.Status or 'not computed'}", error=bool(obj.Status))

    def show_message(self, text, error=False):
        self.quality.setStyleSheet("color: #c00000" if error else "")
        self.quality.setText(text)

    def show_notes(self, notes):
        self.messages.clear()
        for message in messages.group_notes(notes):
            item = QtGui.QListWidgetItem(("Warning: " if message.level == messages.WARNING else "") + message.text)
            if message.level == messages.WARNING:
                item.setForeground(QtGui.QBrush(QtGui.QColor(WARNING_COLOUR)))
            self.messages.addItem(item)

    def report_error(self, message):
        """In the panel and once in the report view, naming the object (the
        message names the face)."""
        self.show_message(message, error=True)
        FreeCAD.Console.PrintError(f"MedialMesh: {self.label}: {message}\n")

    def colour_changed(self, on):
        self.obj.ViewObject.ColourByShape = on
        if self.preview_root and self.run and self.run.result:
            self.show_preview(self.run)

    # --- meshing in the worker -----------------------------------------------

    def start_preview(self):
        self.closing_after_run = False
        self.start_run()

    def start_run(self):
        """Mesh the faces with the panel's values in the worker, unless a
        run for them is going already; False when refused (said why)."""
        if self.faces_error is not None:
            self.report_error(messages.failure_message(self.faces_error, self.label))
            return False
        values = self.values()
        if self.run is not None and self.run.running():
            if self.run.values == values:
                return True
            self.run.stop()
        too_many = too_many_quads(self.faces, values["ElementSize"], ", ".join(self.names))
        if too_many:
            self.report_error(too_many)
            return False
        self.run = MeshRun(self.faces, self.names, values)
        self.preview_button.setEnabled(False)
        self.stop_button.setEnabled(True)
        self.progress.setValue(0)
        self.progress.show()
        self.stage.show()
        self.stage.setText("Starting")
        self.show_message("Meshing ...")
        self.messages.clear()
        self.timer.start()
        return True

    def stop_run(self):
        self.closing_after_run = False
        if self.run is not None and self.run.running():
            self.run.stop()
        self.poll()

    def poll(self):
        try:
            self.follow_run()
        except Exception as error:
            self.report_error(messages.failure_message(error, self.face_names()))

    def follow_run(self):
        run = self.run
        if run is None or self.preview_build is not None:
            return
        if run.running():
            self.progress.setValue(int(1000 * run.progress.fraction()))
            self.stage.setText(f"{run.progress.text()} ({time.monotonic() - run.started:.1f} s)")
            return
        self.timer.stop()
        if run.error is None:  # drawn first, then shown as done
            self.stage.setText("Drawing the preview")
            self.show_preview(run, then=lambda: self.end_run(run))
        else:
            self.end_run(run)

    def end_run(self, run):
        """The run's outcome shown, the panel ready for another; stored and
        closed if OK is waiting for it."""
        self.progress.hide()
        self.stage.hide()
        self.preview_button.setEnabled(True)
        self.stop_button.setEnabled(False)
        if run.error is not None:
            self.report_error(messages.failure_message(run.error, run.names))
            if isinstance(run.error, meshing.Cancelled):
                self.run = None  # nothing to keep
        else:
            text = "Preview:\n" + quality_text(run.result.quality, "\n")
            if run.result.fallbacks:
                text += "\nfallback: " + ", ".join(run.result.fallbacks)
            self.show_message(text)
            self.show_notes(run.result.notes)
        if self.closing_after_run:
            self.closing_after_run = False
            if self.run is not None:
                self.finish()

    # --- the preview ------------------------------------------------------------

    def show_preview(self, run, then=None):
        """Draw the run's mesh in place of the object, its Coin node built a
        step at a time between the GUI's events (a step of a million quads
        takes some 0.15 s; the whole node, 0.5 s); then call `then`."""
        self.remove_preview()
        shapes = run.result.element_shape if self.colour.isChecked() else None
        build = preview_steps(run.geometry, shapes)
        self.preview_build = build

        def step():
            try:
                if build is not self.preview_build:
                    return  # replaced, or the panel closed
                try:
                    next(build)
                except StopIteration as done:
                    self.preview_build = None
                    self.attach_preview(done.value)
                    if then is not None:
                        then()
                    return
                QtCore.QTimer.singleShot(0, step)
            except Exception as error:  # a timer's slot: nothing may escape into FreeCAD
                self.preview_build = None
                self.report_error(messages.failure_message(error, self.face_names()))

        step()

    def attach_preview(self, node):
        graph = FreeCADGui.getDocument(self.doc.Name).ActiveView.getSceneGraph()
        graph.addChild(node)
        self.preview_root = (graph, node)
        if not self.hidden_object and self.obj.ViewObject.Visibility:
            self.obj.ViewObject.Visibility = False
            self.hidden_object = True

    def remove_preview(self):
        self.preview_build = None  # a preview being built is dropped
        if self.preview_root:
            graph, node = self.preview_root
            graph.removeChild(node)
            self.preview_root = None

    def clean_up(self):
        """Stop a run, take the preview out of the view and show the object again."""
        self.timer.stop()
        if self.run is not None and self.run.running():
            self.run.stop()
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
        values = self.values()
        done = self.run is not None and not self.run.running() and self.run.values == values
        unchanged = values == objects.parameter_values(self.obj) and self.obj.Status != objects.NOT_MESHED
        if not done and unchanged:  # the object's own mesh is for these values
            if self.run is not None and self.run.running():
                self.run.stop()
            self.run = None
        if done or unchanged:
            self.finish()
            return True
        # No mesh for these values yet: make it off the GUI thread, then store it and close.
        if not self.start_run():
            return False  # refused (too many quads, no faces): the panel stays, saying why
        self.closing_after_run = True
        self.stage.setText("Meshing; the panel closes and keeps the mesh when done")
        return False

    def finish(self):
        """Store the last run's outcome (if any) and the values, close."""
        try:
            run = self.run
            self.clean_up()
            self.apply(run)
        except Exception as error:
            FreeCAD.Console.PrintError(f"MedialMesh: {self.label}: applying the values failed: {error!r}\n")
        self.close()

    def apply(self, run):
        obj, doc = self.obj, self.doc
        if not self.created:
            doc.openTransaction("Edit quad mesh")
        values = self.values() if run is None else run.values
        current = objects.parameter_values(obj)
        for name, value in values.items():
            if value != current[name]:
                recording.recorded(f"{recording.obj_ref(obj)}.{name} = {value!r}")
        QtGui.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
        try:
            if run is not None:
                self.show_message("Handing the mesh to FreeCAD, which draws it (seconds for a million quads)")
                FreeCADGui.updateGui()
                if run.error is not None:
                    objects.store_failure(obj, messages.failure_message(run.error, run.names))
                else:
                    objects.store_mesh(obj, run.result, objects.mesh_key(obj, self.faces, run.values))
                obj.purgeTouched()  # the mesh is for these values: no meshing again on recompute
            # Recorded for a macro, which meshes there; here the mesh is stored already.
            recording.recorded(f"{recording.doc_ref(doc)}.recompute()")
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
    """The preview as flat arrays, ready for Coin: the mesh's node positions,
    its elements as polygons (corner, mid-side node, next corner ..., -1),
    its element outlines as closed polylines (-1 after each), and the
    splits as polylines. Done with numpy in the worker thread, so that the
    GUI keeps running."""
    elements = result.elements
    corners, midsides = elements[:, :4], elements[:, 4:]
    if midsides.shape[1]:
        loops = numpy.stack([corners, midsides], axis=2).reshape(len(elements), 8)
    else:
        loops = corners
    polygons = numpy.hstack([loops, numpy.full((len(loops), 1), -1)]).ravel()
    # Each element's outline closed on itself: a side between two elements
    # is drawn twice, which costs less than finding it once. None past
    # PREVIEW_EDGES_UP_TO elements: there they are finer than the pixels,
    # and would only double the time the GUI spends drawing.
    if len(loops) <= PREVIEW_EDGES_UP_TO:
        edges = numpy.hstack([loops, loops[:, :1], numpy.full((len(loops), 1), -1)]).ravel()
    else:
        edges = numpy.zeros(0, dtype=numpy.int32)
    splits = [[(p.x, p.y, p.z) for p in edge.discretize(QuasiDeflection=1e-3 * max(edge.Length, 1e-9))]
              for split in result.splits for edge in split.Edges]
    return {
        # arrays: lists would copy into Coin faster, but making them holds the GIL
        "points": result.nodes.astype(numpy.float32),
        "polygons": polygons.astype(numpy.int32),
        "edges": edges.astype(numpy.int32),
        "splits": splits,
    }


def preview_node(geometry, shapes=None):
    """A Coin node of the mesh (faces and element edges) and the splits;
    with shapes (each element's Verdict shape), the faces coloured by them
    as the mesh object colours its elements. The faces are pushed back in
    depth, as the mesh object's are (see viewproviders.push_faces_back): the
    edges show on them and on the face of a part they lie on."""
    steps = preview_steps(geometry, shapes)
    while True:
        try:
            next(steps)
        except StopIteration as done:
            return done.value


def fill_in_steps(field, values):
    """Set a Coin multiple-value field to the array `values`, PREVIEW_STEP
    values at a time, yielding after each piece: pivy copies an array into
    Coin value by value (some 0.15 s for a million points)."""
    for start in range(0, len(values), PREVIEW_STEP):
        piece = values[start:start + PREVIEW_STEP]
        field.setValues(start, len(piece), piece)
        yield


def preview_steps(geometry, shapes=None):
    """preview_node a step at a time: a generator that yields after each
    piece of the node (fill_in_steps) and returns the node."""
    root = coin.SoSeparator()
    root.setName("MedialMeshPreview")
    unpickable = coin.SoPickStyle()
    unpickable.style = coin.SoPickStyle.UNPICKABLE
    root.addChild(unpickable)
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    root.addChild(light)
    coordinates = coin.SoCoordinate3()
    yield from fill_in_steps(coordinates.point, geometry["points"])
    root.addChild(coordinates)

    faces = coin.SoSeparator()
    offset = coin.SoPolygonOffset()
    offset.factor = viewproviders.FACE_OFFSET
    offset.units = viewproviders.FACE_OFFSET
    faces.addChild(offset)
    if shapes is None:
        faces.addChild(base_colour(PREVIEW_FACE_COLOUR))
    else:
        colours = coin.SoBaseColor()
        yield from fill_in_steps(colours.rgb, viewproviders.shape_colours(shapes))
        faces.addChild(colours)
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_FACE
        faces.addChild(binding)
    face_set = coin.SoIndexedFaceSet()
    yield from fill_in_steps(face_set.coordIndex, geometry["polygons"])
    faces.addChild(face_set)
    root.addChild(faces)

    if len(geometry["edges"]):
        root.addChild(base_colour(PREVIEW_EDGE_COLOUR))
        line_set = coin.SoIndexedLineSet()
        yield from fill_in_steps(line_set.coordIndex, geometry["edges"])
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

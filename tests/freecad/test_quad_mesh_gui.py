# SPDX-License-Identifier: LGPL-2.1-or-later
"""The Quad mesh command, its view provider and task panel as a user runs
them, in the FreeCAD GUI under Xvfb.

Run by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh --gui tests/freecad/test_quad_mesh_gui.py [BUILD_DIR [SHARED_DIR]]
The pictures of the 3D view go to BUILD_DIR/test-output/quad_mesh_gui_*.png.
"""

import os
import sys
import time
import unittest

import FemGui
import FreeCAD
import FreeCADGui
import ObjectsFem
import Part
from pivy import coin
from qt_compat import QtCore, QtGui, QtWidgets

from MedialMesh import analysis, decomposition, objects
from test_analyse_gui import PLACEMENT, colour_count

OUTPUT = os.path.join(os.environ["MEDIALMESH_BUILD_DIR"], "test-output")
SIZE = (640, 480)


def process_events_until(condition, timeout):
    """Run the GUI's event loop until condition() holds; False on timeout."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        QtWidgets.QApplication.processEvents(QtCore.QEventLoop.AllEvents, 50)
        if condition():
            return True
        time.sleep(0.01)
    return condition()


def panel_widget(name):
    """A widget of the open Quad mesh task panel, found as a user sees it."""
    # the one shown: the forms of panels closed before may not be deleted yet
    forms = FreeCADGui.getMainWindow().findChildren(QtWidgets.QWidget, "MedialMeshQuadMeshPanel")
    shown = [f for f in forms if f.isVisible()]
    form = (shown or forms or [None])[-1]
    if form is None:
        raise AssertionError("the Quad mesh task panel is not shown")
    return form if name is None else form.findChild(QtWidgets.QWidget, name)


def wait_for_run(timeout=300):
    """Let the open panel's meshing run to its end."""
    done = process_events_until(lambda: panel_widget("stop") is None or not panel_widget("stop").isEnabled(),
                                timeout)
    FreeCADGui.updateGui()
    return done


def wait_for_panel_to_close(timeout=300):
    return process_events_until(lambda: not FreeCADGui.Control.activeDialog(), timeout)


def press(button):
    """Press OK or Cancel of the open task dialog."""
    FreeCADGui.updateGui()  # the task view replaces the buttons of an earlier dialog
    for box in FreeCADGui.getMainWindow().findChildren(QtWidgets.QDialogButtonBox):
        widget = box.button(button)
        if widget is not None and widget.isVisible() and widget.isEnabled():
            widget.click()
            FreeCADGui.updateGui()
            return
    raise AssertionError(f"no task dialog button {button}")


def report_view_text():
    FreeCADGui.updateGui()  # the report view shows messages from its event queue
    return "\n".join(w.toPlainText() for w in FreeCADGui.getMainWindow().findChildren(QtWidgets.QTextEdit)
                     if w.objectName() == "Report view")


def dark_transitions(image, rows):
    """Light-to-dark steps along the given rows: each element edge a scanline
    crosses is one."""
    count = 0
    for y in rows:
        dark = False
        for x in range(image.width()):
            now = QtGui.QColor(image.pixel(x, y)).lightness() < 110
            count += now and not dark
            dark = now
    return count


class TestQuadMeshCommand(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        FreeCADGui.activateWorkbench("MedialMeshWorkbench")
        os.makedirs(OUTPUT, exist_ok=True)
        cls.doc = FreeCAD.newDocument("QuadMeshGui")
        shape = Part.read(os.path.join(os.environ["MEDIALMESH_SHARED"], "geometry", "plate_with_hole.brep"))
        cls.plate = cls.doc.addObject("Part::Feature", "Plate")
        cls.plate.Shape = shape
        cls.plate.Placement = PLACEMENT
        cls.cylinder = cls.doc.addObject("Part::Cylinder", "Cylinder")
        cls.cylinder.Placement.Base = FreeCAD.Vector(30, 0, 0)
        cls.analysis = ObjectsFem.makeAnalysis(cls.doc, "Analysis")
        cls.doc.recompute()
        FemGui.setActiveAnalysis(cls.analysis)
        FreeCADGui.updateGui()

    @classmethod
    def tearDownClass(cls):
        FreeCAD.closeDocument(cls.doc.Name)

    def tearDown(self):
        if FreeCADGui.Control.activeDialog():  # a failed test must not leave its panel to the next
            FreeCADGui.Control.closeDialog()
            FreeCADGui.getDocument(self.doc.Name).resetEdit()
        FreeCADGui.updateGui()

    def select(self, *picks):
        FreeCADGui.Selection.clearSelection()
        for obj, subname in picks:
            FreeCADGui.Selection.addSelection(self.doc.Name, obj.Name, subname)
        FreeCADGui.updateGui()

    def run_quad_mesh(self, *picks):
        """Run the command on the picks; return the mesh object it made."""
        self.select(*picks)
        before = set(o.Name for o in self.doc.Objects)
        FreeCADGui.runCommand("MedialMesh_QuadMesh")
        FreeCADGui.updateGui()
        self.assertTrue(wait_for_run(), "the panel's first meshing did not finish")
        made = [self.doc.getObject(name) for name in set(o.Name for o in self.doc.Objects) - before]
        meshes = [o for o in made if getattr(o, "Type", "") == objects.QUAD_MESH_TYPE]
        self.assertEqual(len(meshes), 1)
        self.assertEqual(sorted(o.Name for o in made), sorted([meshes[0].Name, meshes[0].Sketch.Name]))
        return meshes[0]

    def state(self):
        """What Cancel must leave as it was."""
        mesh_state = {}
        for o in self.doc.Objects:
            if getattr(o, "Type", "") == objects.QUAD_MESH_TYPE:
                mesh_state[o.Name] = (o.ElementSize.Value, o.MergeFactor, o.ElementOrder, o.Smoothing, o.QuadCount,
                                      o.FemMesh.NodeCount, o.ViewObject.Visibility)
        return (sorted(o.Name for o in self.doc.Objects), sorted(o.Name for o in self.analysis.Group),
                self.doc.UndoCount, self.doc.UndoNames, mesh_state)

    def look_at_plate(self, view):
        view.setCameraOrientation(PLACEMENT.Rotation)  # straight at the face
        self.select((self.plate, ""))
        FreeCADGui.SendMsgToActiveView("ViewSelection")
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.updateGui()

    def preview(self):
        panel_widget("preview").click()
        self.assertTrue(wait_for_run(120), "the preview did not finish")
        return panel_widget("quality").text()

    def test_in_toolbar_and_menu(self):
        toolbars = FreeCADGui.getWorkbench("MedialMeshWorkbench").getToolbarItems()
        self.assertIn("MedialMesh_QuadMesh", toolbars["MedialMesh"])
        pixmap = FreeCADGui.Command.get("MedialMesh_QuadMesh").getInfo()["pixmap"]
        self.assertTrue(pixmap.endswith("MedialMesh_QuadMesh.svg") and os.path.isfile(pixmap))
        menus = [m for m in FreeCADGui.getMainWindow().menuBar().findChildren(QtWidgets.QMenu)
                 if m.title() == "MedialMesh"]
        self.assertIn("Quad mesh", [a.text() for m in menus for a in m.actions()])

    def test_a_selection_it_cannot_use_is_named_with_what_it_needs(self):
        command = FreeCADGui.Command.get("MedialMesh_QuadMesh")
        FreeCADGui.Selection.clearSelection()
        self.assertFalse(command.isActive())  # grey: its tooltip says what to select
        self.assertIn("Select planar faces", command.getInfo()["toolTip"])
        status_bar = FreeCADGui.getMainWindow().statusBar()
        before = len(self.doc.Objects)
        for pick, why in (((self.cylinder, "Face1"), "Cylinder.Face1 is a curved face (cylinder): planar faces only"),
                          ((self.plate, "Edge1"), "Plate.Edge1 is an edge, not a face"),
                          ((self.analysis, ""), "Analysis has no faces")):
            self.select(pick)
            self.assertTrue(command.isActive())  # pressed, it says why it cannot
            FreeCADGui.runCommand("MedialMesh_QuadMesh")
            FreeCADGui.updateGui()
            self.assertEqual(len(self.doc.Objects), before)
            self.assertIn(why, status_bar.currentMessage())
            self.assertIn(f"MedialMesh: Quad mesh: {why}. To use it, select planar faces", report_view_text())
        self.select((self.plate, "Face1"))
        self.assertTrue(command.isActive())

    def test_analyse_decompose_quad_mesh_and_edit(self):
        view = FreeCADGui.getDocument(self.doc.Name).ActiveView
        for command, kind in (("MedialMesh_Analyse", objects.TYPE),
                              ("MedialMesh_Decompose", objects.DECOMPOSITION_TYPE)):
            self.select((self.plate, "Face1"))
            FreeCADGui.runCommand(command)
            FreeCADGui.updateGui()
            (made,) = [o for o in self.doc.Objects if getattr(o, "Type", "") == kind]
            self.assertEqual(made.Status, "ok")
            made.ViewObject.Visibility = False  # only the plate and the mesh in the pictures

        undo_before = self.doc.UndoCount
        mesh = self.run_quad_mesh((self.plate, "Face1"))
        self.assertTrue(FreeCADGui.Control.activeDialog())
        # The panel meshed it at once, off the GUI thread: shown, not stored before OK.
        self.assertEqual(mesh.Status, objects.NOT_MESHED)
        self.assertIn(mesh, self.analysis.Group)
        self.assertEqual(mesh.ViewObject.Proxy.__class__.__name__, "ViewProviderMedialQuadMesh")
        self.assertEqual(mesh.ViewObject.claimChildren(), [mesh.Sketch])
        text = panel_widget("quality").text()
        self.assertTrue(text.startswith("Preview:\n"), text)
        automatic = int(text.split()[1])

        # Half the automatic size (the diagonal / 20): some four times the quads.
        # (The field keeps FreeCAD's two decimals.)
        size = round(self.plate.Shape.Face1.BoundBox.DiagonalLength / 40, 2)
        panel_widget("elementSize").setProperty("rawValue", size)
        text = self.preview()
        self.assertTrue(text.startswith("Preview:\n"), text)
        previewed = int(text.split()[1])
        self.assertGreater(previewed, 2 * automatic)
        self.assertEqual(mesh.QuadCount, 0)  # the preview leaves the object alone
        self.assertFalse(mesh.ViewObject.Visibility)  # it stands in for the object meanwhile
        self.cylinder.ViewObject.Visibility = False
        self.look_at_plate(view)
        preview_picture = os.path.join(OUTPUT, "quad_mesh_gui_preview.png")
        view.saveImage(preview_picture, *SIZE, "White")
        # The panel says the measures a FEM engineer checks, and the whole window shows them.
        self.assertIn("shape min", text)
        self.assertIn("edge ratio max", text)
        FreeCADGui.getMainWindow().grab().save(os.path.join(OUTPUT, "quad_mesh_gui_window.png"))

        press(QtWidgets.QDialogButtonBox.Ok)
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertAlmostEqual(mesh.ElementSize.Value, size, places=6)
        self.assertEqual(mesh.QuadCount, previewed)
        self.assertEqual(mesh.FemMesh.QuadrangleCount, previewed)
        self.assertEqual(mesh.FemMesh.FaceCount, previewed)  # quads only
        self.assertTrue(mesh.ViewObject.Visibility)
        self.assertEqual(self.doc.UndoCount, undo_before + 1)  # making and setting it: one step
        self.assertEqual(self.doc.UndoNames[0], "Quad mesh")

        # The picture: the mesh's element edges on the plate.
        FreeCADGui.updateGui()
        meshed = os.path.join(OUTPUT, "quad_mesh_gui.png")
        view.saveImage(meshed, *SIZE, "White")
        mesh.ViewObject.Visibility = False
        FreeCADGui.updateGui()
        alone = os.path.join(OUTPUT, "quad_mesh_gui_plate_alone.png")
        view.saveImage(alone, *SIZE, "White")
        mesh.ViewObject.Visibility = True
        image, plate = QtGui.QImage(meshed), QtGui.QImage(alone)
        self.assertEqual((image.width(), image.height()), SIZE)
        # the hidden analysis hides its singularity marks too
        self.assertEqual(colour_count(plate, analysis.POSITIVE_COLOUR), 0)
        rows = range(SIZE[1] // 4, 3 * SIZE[1] // 4, 10)
        with_mesh, without = dark_transitions(image, rows), dark_transitions(plate, rows)
        # A row across the plate crosses about sqrt(quads) element edges.
        self.assertGreater(with_mesh, without + 0.5 * len(rows) * previewed**0.5,
                           f"{with_mesh} edge crossings with the mesh, {without} without")
        # The preview showed the same mesh, and the four splits from the hole to the sides.
        preview_image = QtGui.QImage(preview_picture)
        self.assertGreater(dark_transitions(preview_image, rows), without + 0.5 * len(rows) * previewed**0.5)
        self.assertGreater(colour_count(preview_image, decomposition.SPLIT_COLOUR), 200)

        # Double click opens the panel on the object made; 2nd order there gives 8-node quads.
        self.assertTrue(mesh.ViewObject.doubleClicked())
        self.assertTrue(FreeCADGui.Control.activeDialog())
        order = panel_widget("elementOrder")
        order.setCurrentIndex(order.findText("2nd"))
        press(QtWidgets.QDialogButtonBox.Ok)  # no mesh for these values yet: OK meshes, then closes
        self.assertTrue(wait_for_panel_to_close())
        self.assertEqual(mesh.ElementOrder, "2nd")
        self.assertEqual(mesh.QuadCount, previewed)
        self.assertGreater(mesh.FemMesh.NodeCount, 2 * mesh.QuadCount)
        self.assertEqual(self.doc.UndoNames[0], "Edit quad mesh")

    def test_cancel_after_the_command_takes_the_object_back(self):
        before = self.state()
        self.run_quad_mesh((self.plate, "Face1"))
        panel_widget("elementSize").setProperty("rawValue", 0.3)
        panel_widget("mergeFactor").setValue(0.5)
        self.assertTrue(self.preview().startswith("Preview:\n"))
        press(QtWidgets.QDialogButtonBox.Cancel)
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertEqual(self.state(), before)

    def test_cancel_of_an_edit_leaves_the_object(self):
        mesh = objects.make_mesh_object(self.doc, self.plate, "Face1", analysis=self.analysis)
        self.doc.recompute()
        before = self.state()
        self.assertTrue(FreeCADGui.getDocument(self.doc.Name).setEdit(mesh.Name, 0))
        panel_widget("elementSize").setProperty("rawValue", 0.25)
        panel_widget("smoothing").setChecked(False)
        self.assertTrue(self.preview().startswith("Preview:\n"))
        self.assertFalse(mesh.ViewObject.Visibility)
        press(QtWidgets.QDialogButtonBox.Cancel)
        self.assertEqual(self.state(), before)
        search = coin.SoSearchAction()
        search.setName("MedialMeshPreview")
        search.apply(FreeCADGui.getDocument(self.doc.Name).ActiveView.getSceneGraph())
        self.assertIsNone(search.getPath(), "the preview is still shown")

    def test_faces_not_planar_are_named_and_left_out(self):
        mesh = self.run_quad_mesh((self.plate, "Face1"), (self.cylinder, "Face1"))
        self.assertEqual(mesh.Source, [(self.plate, ("Face1",))])
        self.assertIn("Cylinder.Face1 is a curved face (cylinder): planar faces only", report_view_text())
        press(QtWidgets.QDialogButtonBox.Ok)
        self.assertEqual(mesh.Status, "ok")

    def test_faces_of_several_objects_go_into_one_mesh(self):
        top = self.cylinder.Shape.Faces[1]  # the cylinder's top: planar
        self.assertIsNotNone(top.findPlane())
        mesh = self.run_quad_mesh((self.plate, "Face1"), (self.cylinder, "Face2"))
        self.assertEqual(sorted((o.Name, subs) for o, subs in mesh.Source),
                         [("Cylinder", ("Face2",)), ("Plate", ("Face1",))])
        self.assertEqual(panel_widget("faces").text(), "Plate.Face1, Cylinder.Face2")
        press(QtWidgets.QDialogButtonBox.Ok)

    def test_face_object_picked_in_the_tree(self):
        sheet = self.doc.addObject("Part::Plane", "Sheet")
        sheet.Placement.Base = FreeCAD.Vector(0, 30, 0)
        self.doc.recompute()
        mesh = self.run_quad_mesh((sheet, ""))
        self.assertEqual(mesh.Source, [(sheet, ("Face1",))])
        press(QtWidgets.QDialogButtonBox.Ok)
        self.assertEqual(mesh.Status, "ok")

    def test_a_solid_picked_whole_gives_its_planar_faces(self):
        mesh = self.run_quad_mesh((self.cylinder, ""))
        self.assertEqual(mesh.Source, [(self.cylinder, ("Face2", "Face3"))])  # its top and bottom
        self.assertIn("Cylinder: 1 curved face left out, 2 planar faces meshed", report_view_text())
        press(QtWidgets.QDialogButtonBox.Ok)
        self.assertEqual(mesh.Status, "ok")
        self.assertEqual(mesh.Label, "QuadMesh (Cylinder Face2 + 1 face)")

    def test_deleting_the_mesh_deletes_its_sketch(self):
        mesh = objects.make_mesh_object(self.doc, self.plate, "Face1", analysis=self.analysis)
        names = (mesh.Name, mesh.Sketch.Name)
        self.select((mesh, ""))
        questions = []  # a question would stop the test: answer it, and fail

        def answer():
            for widget in QtWidgets.QApplication.topLevelWidgets():
                if isinstance(widget, QtWidgets.QMessageBox) and widget.isVisible():
                    questions.append(widget.text())
                    widget.reject()

        guard = QtCore.QTimer()
        guard.timeout.connect(answer)
        guard.start(200)
        FreeCADGui.runCommand("Std_Delete")
        FreeCADGui.updateGui()
        guard.stop()
        self.assertEqual(questions, [])
        self.assertEqual([n for n in names if self.doc.getObject(n)], [])
        self.assertNotIn(names[0], [o.Name for o in self.analysis.Group])

    def test_a_size_giving_millions_of_quads_is_refused(self):
        sheet = self.doc.addObject("Part::Plane", "BigSheet")
        sheet.Length = sheet.Width = 2000
        sheet.Placement.Base = FreeCAD.Vector(0, -3000, 0)
        self.doc.recompute()
        mesh = objects.make_mesh_object(self.doc, sheet, "Face1", analysis=self.analysis)
        quads = mesh.QuadCount
        self.assertTrue(FreeCADGui.getDocument(self.doc.Name).setEdit(mesh.Name, 0))
        panel_widget("elementSize").setProperty("rawValue", 1.0)  # some 4 million quads
        text = self.preview()
        self.assertIn("BigSheet.Face1: element size 1 mm gives about 4e+06 quads", text)
        press(QtWidgets.QDialogButtonBox.Ok)  # refused: the panel stays
        self.assertTrue(FreeCADGui.Control.activeDialog())
        self.assertEqual((mesh.ElementSize.Value, mesh.QuadCount), (0.0, quads))
        press(QtWidgets.QDialogButtonBox.Cancel)
        self.assertFalse(FreeCADGui.Control.activeDialog())

    def test_one_panel_at_a_time(self):
        first = objects.make_mesh_object(self.doc, self.plate, "Face1", analysis=self.analysis)
        second = objects.make_mesh_object(self.doc, self.plate, "Face1", analysis=self.analysis)
        self.assertTrue(first.ViewObject.doubleClicked())
        self.assertTrue(second.ViewObject.doubleClicked())  # refused: a line in the report view
        self.assertIn(f"MedialMesh: {second.Label}: close the open task dialog", report_view_text())
        self.assertFalse(second.ViewObject.Proxy.panel)
        before = len(self.doc.Objects)
        self.select((self.plate, "Face1"))
        FreeCADGui.runCommand("MedialMesh_QuadMesh")  # refused too
        self.assertEqual(len(self.doc.Objects), before)
        self.assertIn("MedialMesh: Quad mesh: close the open task dialog first", report_view_text())
        press(QtWidgets.QDialogButtonBox.Cancel)
        self.assertFalse(FreeCADGui.Control.activeDialog())

    def test_preview_error_names_object_and_face(self):
        # A macro can link a face the command would not take.
        mesh = objects.make_mesh_object(self.doc, self.cylinder, "Face1", analysis=self.analysis)
        self.assertNotEqual(mesh.Status, "ok")
        self.assertTrue(FreeCADGui.getDocument(self.doc.Name).setEdit(mesh.Name, 0))
        text = self.preview()
        self.assertIn("Cylinder.Face1", text)
        self.assertIn(f"MedialMesh: {mesh.Label}: {text}", report_view_text())
        self.assertEqual(panel_widget("quality").styleSheet(), "color: #c00000")
        press(QtWidgets.QDialogButtonBox.Cancel)

    def test_merge_factor_field_takes_only_what_the_core_takes(self):
        mesh = objects.make_mesh_object(self.doc, self.plate, "Face1", analysis=self.analysis)
        self.assertTrue(FreeCADGui.getDocument(self.doc.Name).setEdit(mesh.Name, 0))
        merge = panel_widget("mergeFactor")
        self.assertEqual(merge.value(), 0.75)
        merge.setValue(0.1)  # below 0.25: the field offers "no merging" instead
        self.assertEqual(merge.text(), "no merging")
        press(QtWidgets.QDialogButtonBox.Ok)
        self.assertTrue(wait_for_panel_to_close())
        self.assertEqual(mesh.MergeFactor, 0.0)
        self.assertEqual(mesh.Status, "ok")

    def test_closing_the_document_during_a_preview(self):
        doc = FreeCAD.newDocument("QuadMeshClosed")
        try:
            plate = doc.addObject("Part::Feature", "Plate")
            plate.Shape = self.plate.Shape
            doc.recompute()
            # the active Analysis is in the other document: not this mesh's
            mesh = objects.make_mesh_object(doc, plate, "Face1")
            self.assertNotIn(mesh, self.analysis.Group)
            self.assertTrue(FreeCADGui.getDocument(doc.Name).setEdit(mesh.Name, 0))
            panel_widget("elementSize").setProperty("rawValue", 0.01)
            panel_widget("preview").click()
        finally:
            FreeCAD.closeDocument(doc.Name)
            FreeCAD.setActiveDocument(self.doc.Name)
        process_events_until(lambda: False, 3)  # the preview finishes with its document gone
        self.assertFalse(FreeCADGui.Control.activeDialog())
        self.assertNotIn("QuadMeshClosed", FreeCAD.listDocuments())
        self.assertNotIn("Traceback", report_view_text())

    def test_saved_and_reopened(self):
        doc = FreeCAD.newDocument("QuadMeshSaved")
        path = os.path.join(OUTPUT, "quad_mesh_gui_saved.FCStd")
        if os.path.exists(path):  # FreeCAD would keep the old one as a backup
            os.remove(path)
        try:
            plate = doc.addObject("Part::Feature", "Plate")
            plate.Shape = self.plate.Shape
            doc.recompute()
            mesh = objects.make_mesh_object(doc, plate, "Face1", size=0.5)
            quads = mesh.QuadCount
            doc.saveAs(path)
        finally:
            FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
        try:
            mesh = doc.getObject("MedialQuadMesh")
            self.assertEqual(mesh.ViewObject.Proxy.__class__.__name__, "ViewProviderMedialQuadMesh")
            self.assertTrue(mesh.ViewObject.Proxy.getIcon().endswith("MedialMesh_QuadMesh.svg"))
            self.assertEqual(mesh.ViewObject.claimChildren(), [mesh.Sketch])
            self.assertEqual(mesh.FemMesh.QuadrangleCount, quads)
            self.assertTrue(mesh.ViewObject.doubleClicked())
            self.assertEqual(panel_widget("elementSize").property("rawValue"), 0.5)
            press(QtWidgets.QDialogButtonBox.Cancel)
            self.assertFalse(FreeCADGui.Control.activeDialog())
        finally:
            FreeCAD.closeDocument(doc.Name)
            FreeCAD.setActiveDocument(self.doc.Name)

    def test_long_preview_shows_progress_and_the_gui_keeps_running(self):
        mesh = objects.make_mesh_object(self.doc, self.plate, "Face1", analysis=self.analysis)
        self.assertTrue(FreeCADGui.getDocument(self.doc.Name).setEdit(mesh.Name, 0))
        panel_widget("elementSize").setProperty("rawValue", 0.006)  # some 350 000 quads, 2 s in the core alone
        ticks = []
        timer = QtCore.QTimer()
        timer.timeout.connect(lambda: ticks.append(time.monotonic()))
        timer.start(50)
        progress_seen = []
        panel_widget("preview").click()
        started = time.monotonic()
        done = process_events_until(
            lambda: progress_seen.append(panel_widget("progress").isVisible()) or panel_widget("preview").isEnabled(),
            300)
        seconds = time.monotonic() - started
        timer.stop()
        self.assertTrue(done)
        self.assertGreater(seconds, 1.0, "too quick to need a progress indication: choose a smaller size")
        self.assertTrue(any(progress_seen))
        self.assertFalse(panel_widget("progress").isVisible())
        # the event loop ran all along: no gap between timer ticks as long as the meshing
        gaps = [b - a for a, b in zip(ticks, ticks[1:])]
        print(f"long preview: {seconds:.2f} s, longest stand-still {max(gaps):.2f} s; "
              f"{panel_widget('quality').text()!r}", file=sys.__stdout__)
        self.assertLess(max(gaps), 0.5 * seconds, f"the GUI stood still for {max(gaps):.2f} s of {seconds:.2f} s")
        self.assertTrue(panel_widget("quality").text().startswith("Preview:\n"))
        press(QtWidgets.QDialogButtonBox.Cancel)


if __name__ == "__main__":
    unittest.main()

# SPDX-License-Identifier: LGPL-2.1-or-later
"""The demo's FreeCAD part, run by tools/demo.sh in the GUI under Xvfb: what a
user does by hand. Imports the face, selects it, presses Analyse, then
Decompose, saves a picture of the 3D view; then imports a second face (the
FEM face), quad-meshes it into a FEM Analysis (the edge furthest in -x fixed,
a force pulling the straight edge furthest in +x), solves it with CalculiX
through FreeCAD's ccxtools, saves pictures of the mesh and of the von Mises
stress, and the document.

Environment: MEDIALMESH_DEMO_INPUT (a face file), MEDIALMESH_DEMO_FEM_INPUT
(the FEM face's file), MEDIALMESH_DEMO_OUT (the stem of the outputs:
STEM.FCStd, STEM.png, STEM.mesh.png, STEM.stress.png and the CalculiX files
in STEM.ccx/).
"""

import os
import sys
import time
import traceback

out = sys.__stdout__  # the GUI may take sys.stdout for its report view

# the load of the CalculiX run: a steel shell of THICKNESS pulled with FORCE
FORCE = 1000.0  # N
THICKNESS = 1.0  # mm


def show_only(doc, shown):
    """Hide every object of the document but `shown`, look at it from the top, fit it."""
    import FreeCADGui

    for obj in doc.Objects:
        if obj.ViewObject is not None:
            obj.ViewObject.Visibility = obj in shown
    FreeCADGui.ActiveDocument.ActiveView.viewTop()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.updateGui()


def quad_mesh_command(doc, part):
    """Mesh Face1 of `part` as a user does: select it, press Quad mesh (its
    panel meshes it), press OK in the task panel once the panel has meshed it;
    save a picture of the mesh; return the mesh object."""
    import FreeCADGui
    from PySide import QtCore, QtGui  # FreeCAD's shim: PySide2 in 0.20, 2 or 6 in 1.0

    try:
        from PySide import QtWidgets
    except ImportError:  # 0.20's shim keeps the widgets in QtGui
        QtWidgets = QtGui

    def wait_until(condition, what, seconds=300):
        end = time.monotonic() + seconds
        while not condition():
            if time.monotonic() > end:
                raise RuntimeError(f"the Quad mesh task panel: {what} after {seconds} s")
            QtWidgets.QApplication.processEvents(QtCore.QEventLoop.AllEvents, 50)
            time.sleep(0.01)

    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(doc.Name, part.Name, "Face1")
    FreeCADGui.runCommand("MedialMesh_QuadMesh")
    FreeCADGui.updateGui()
    mesh = next((o for o in doc.Objects if getattr(o, "Type", "") == "MedialMesh::QuadMesh"), None)
    if mesh is None or not FreeCADGui.Control.activeDialog():
        raise RuntimeError("the Quad mesh task panel did not open")
    stop = FreeCADGui.getMainWindow().findChild(QtWidgets.QPushButton, "stop")
    wait_until(lambda: not stop.isEnabled(), "still meshing")
    buttons = [box.button(QtWidgets.QDialogButtonBox.Ok)
               for box in FreeCADGui.getMainWindow().findChildren(QtWidgets.QDialogButtonBox)]
    ok = next((b for b in buttons if b is not None and b.isVisible() and b.isEnabled()), None)
    if ok is None:
        raise RuntimeError("the Quad mesh task panel has no OK button")
    ok.click()
    wait_until(lambda: not FreeCADGui.Control.activeDialog(), "still open")
    FreeCADGui.updateGui()
    if mesh.Status != "ok":
        raise RuntimeError(f"the quad mesh failed: {mesh.Status}")
    show_only(doc, [part, mesh])
    FreeCADGui.ActiveDocument.ActiveView.saveImage(os.environ["MEDIALMESH_DEMO_OUT"] + ".quadmesh.png", 1000, 800,
                                                   "White")
    return mesh


def quad_mesh_and_calculix(doc, source, stem):
    """Import the face in file `source`, quad-mesh it into a FEM Analysis,
    solve it with CalculiX and save pictures of the mesh and of the von Mises
    stress; return a summary line."""
    import FreeCADGui
    import Part

    import MedialMesh
    from MedialMesh import fem_example

    part = doc.addObject("Part::Feature", os.path.splitext(os.path.basename(source))[0])
    part.Shape = Part.read(source).Faces[0]
    doc.recompute()
    edges = part.Shape.Edges
    lines = [i for i, e in enumerate(edges) if isinstance(e.Curve, Part.Line)]
    if len(lines) < 2:
        raise RuntimeError(f"{part.Label}: the CalculiX demo needs two straight edges, to fix and to pull")
    fixed = min(range(len(edges)), key=lambda i: edges[i].CenterOfMass.x)
    loaded = max(lines, key=lambda i: edges[i].CenterOfMass.x)
    analysis = fem_example.setup_tension_analysis(doc, part, f"Edge{fixed + 1}", f"Edge{loaded + 1}", FORCE,
                                                  thickness=THICKNESS)
    mesh = MedialMesh.make_mesh_object(doc, part, "Face1", order=2, analysis=analysis)
    if mesh.Status != "ok":
        raise RuntimeError(f"the quad mesh failed: {mesh.Status}")
    show_only(doc, [mesh])
    FreeCADGui.ActiveDocument.ActiveView.saveImage(stem + ".mesh.png", 1000, 800, "White")

    result = fem_example.solve(analysis, stem + ".ccx")
    # as FreeCAD's result panel colours a result: on the result's own mesh
    result.Mesh.ViewObject.setNodeColorByScalars(result.NodeNumbers, result.vonMises)
    show_only(doc, [result.Mesh])
    FreeCADGui.ActiveDocument.ActiveView.saveImage(stem + ".stress.png", 1000, 800, "White")
    return (f"{mesh.Label}: {mesh.QuadCount} 8-node quads, min shape {mesh.MinShape:.3f}, "
            f"min scaled Jacobian {mesh.MinScaledJacobian:.3f}; "
            f"CalculiX: {FORCE:g} N on Edge{loaded + 1}, Edge{fixed + 1} fixed, max von Mises "
            f"{max(result.vonMises):.1f} MPa; wrote {stem}.mesh.png and {stem}.stress.png")


try:
    import FreeCAD
    import FreeCADGui
    import Part

    source = os.environ["MEDIALMESH_DEMO_INPUT"]
    stem = os.environ["MEDIALMESH_DEMO_OUT"]
    FreeCADGui.activateWorkbench("MedialMeshWorkbench")
    doc = FreeCAD.newDocument("MedialMeshDemo")
    part = doc.addObject("Part::Feature", os.path.splitext(os.path.basename(source))[0])
    part.Shape = Part.read(source)
    doc.recompute()
    FreeCADGui.Selection.addSelection(doc.Name, part.Name, "Face1")
    FreeCADGui.runCommand("MedialMesh_Analyse")
    analysis = doc.Objects[-1]
    if getattr(analysis, "Status", None) != "ok":
        raise RuntimeError(f"the analysis failed: {getattr(analysis, 'Status', 'no analysis object')}")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(doc.Name, part.Name, "Face1")
    FreeCADGui.runCommand("MedialMesh_Decompose")
    decomposition = next((o for o in doc.Objects if getattr(o, "Type", "") == "MedialMesh::Decomposition"), None)
    if getattr(decomposition, "Status", None) != "ok":
        raise RuntimeError(f"the decomposition failed: {getattr(decomposition, 'Status', 'no decomposition object')}")
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.ActiveDocument.ActiveView.viewTop()
    FreeCADGui.SendMsgToActiveView("ViewFit")
    FreeCADGui.updateGui()
    FreeCADGui.ActiveDocument.ActiveView.saveImage(stem + ".png", 1000, 800, "White")
    quad_mesh = quad_mesh_command(doc, part)
    fem_summary = quad_mesh_and_calculix(doc, os.environ["MEDIALMESH_DEMO_FEM_INPUT"], stem)
    doc.saveAs(stem + ".FCStd")
    out.write(f"freecad-demo: {analysis.Label}: {len(analysis.SingularityK)} singularities, "
              f"sum of k {analysis.SumK}; {decomposition.Label}: {decomposition.SplitCount} splits, "
              f"{decomposition.BlockCount} blocks ({decomposition.PolygonBlocks} polygon, "
              f"{decomposition.SubmapBlocks} submapped); wrote {stem}.FCStd and {stem}.png\n")
    out.write(f"freecad-demo: {quad_mesh.Label} (Quad mesh command, task panel accepted): {quad_mesh.QuadCount} "
              f"quads, min shape {quad_mesh.MinShape:.3f}, min scaled Jacobian {quad_mesh.MinScaledJacobian:.3f}, "
              f"{quad_mesh.IrregularNodes} "
              f"irregular nodes; wrote {stem}.quadmesh.png\n")
    out.write(f"freecad-demo: {fem_summary}\n")
    status = 0
except Exception:
    traceback.print_exc(file=out)
    status = 1
out.flush()
sys.exit(status)

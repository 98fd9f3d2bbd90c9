# SPDX-License-Identifier: LGPL-2.1-or-later
"""The demo's FreeCAD part, run by tools/demo.sh in the GUI under Xvfb: what a
user does by hand. Imports the face, selects it, presses Analyse, then
Decompose, saves the document and a picture of the 3D view.

Environment: MEDIALMESH_DEMO_INPUT (a face file), MEDIALMESH_DEMO_OUT (the
stem of the outputs: STEM.FCStd and STEM.png).
"""

import os
import sys
import traceback

out = sys.__stdout__  # the GUI may take sys.stdout for its report view
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
    doc.saveAs(stem + ".FCStd")
    out.write(f"freecad-demo: {analysis.Label}: {len(analysis.SingularityK)} singularities, "
              f"sum of k {analysis.SumK}; {decomposition.Label}: {decomposition.SplitCount} splits, "
              f"{decomposition.BlockCount} blocks ({decomposition.PolygonBlocks} polygon, "
              f"{decomposition.SubmapBlocks} submapped); wrote {stem}.FCStd and {stem}.png\n")
    status = 0
except Exception:
    traceback.print_exc(file=out)
    status = 1
out.flush()
sys.exit(status)

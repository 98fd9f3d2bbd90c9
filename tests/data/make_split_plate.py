# Writes split_plate_left.brep and split_plate_right.brep (run: freecadcmd make_split_plate.py).
import Part, FreeCAD as App
V = App.Vector
# A 4 x 2 plate with a hole of radius 0.5 at (2, 1), split along x = 2; the
# halves fused so that they share their edges in the file.
plate = Part.makePlane(4, 2).cut(Part.Face(Part.Wire(Part.makeCircle(0.5, V(2, 1, 0)))))
left = plate.common(Part.makeBox(2, 4, 2, V(0, -1, -1))).Faces[0]
right = plate.common(Part.makeBox(2, 4, 2, V(2, -1, -1))).Faces[0]
fused = left.generalFuse([right])[0]
faces = sorted(fused.Faces, key=lambda f: f.BoundBox.XMin)
print([(f.Area, len(f.Edges)) for f in faces])
for name, f in zip(["left", "right"], faces):
    open("split_plate_%s.brep" % name, "w").write(f.exportBrepToString())

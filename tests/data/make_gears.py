# Writes gear_18_keyed.brep and gear_30_keyed.brep (run: freecadcmd make_gears.py):
# spur gears of trapezoidal teeth (root radius 8.5, tip 10) round a bore of
# radius 3 with a keyway 1.5 wide reaching y = 4.2, as a CAD system cuts them.
import math
import FreeCAD as App
import Part

V = App.Vector


def gear(teeth):
    points = []
    for i in range(teeth):
        for fraction, radius in ((0.0, 8.5), (0.225, 8.5), (0.325, 10.0), (0.675, 10.0), (0.775, 8.5)):
            angle = 2 * math.pi * (i + fraction) / teeth
            points.append(V(radius * math.cos(angle), radius * math.sin(angle), 0))
    face = Part.Face(Part.makePolygon(points + [points[0]]))
    face = face.cut(Part.Face(Part.Wire(Part.makeCircle(3))))
    return face.cut(Part.makePlane(1.5, 1.8, V(-0.75, 2.4, 0))).Faces[0]


for teeth in (18, 30):
    open("gear_%d_keyed.brep" % teeth, "w").write(gear(teeth).exportBrepToString())

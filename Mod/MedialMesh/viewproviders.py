# SPDX-License-Identifier: LGPL-2.1-or-later
"""How an analysis object looks: the medial axis with its edges coloured by
flow type, and the singularities as dots coloured by sign with their k."""

import os

import FreeCAD
from pivy import coin

from . import analysis

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
        # The singularity marks ride along in every display mode.
        self.marks = coin.SoSeparator()
        vobj.RootNode.addChild(self.marks)
        self.draw_marks(vobj.Object)

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
        pass

    def getIcon(self):
        return os.path.join(ICON_FOLDER, "MedialMesh_Analyse.svg")

    def claimChildren(self):
        return []

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


# SPDX-License-Identifier: LGPL-2.1-or-later
"""The parametric analysis object: the medial axis of a linked face, cut into
runs of one flow type, and the face's mesh singularities.

Its Shape is the axis as one edge per flow run, in 3-D on the face; FlowTypes
gives each edge's n. The singularities are kept as positions and k. It
recomputes when the face or MergeFactor changes. A face that cannot be
analysed leaves an empty shape, the problem in Status and in the report view.
"""

import FreeCAD
import Part
from _medialmesh import InputError

from . import analysis

TYPE = "MedialMesh::Analysis"


class MedialAnalysis:
    """Proxy of a Part::FeaturePython analysing one face."""

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)

    def add_properties(self, obj):
        def add(kind, name, group, doc, mode=0):
            if not hasattr(obj, name):
                obj.addProperty(kind, name, group, doc, mode)

        add("App::PropertyString", "Type", "Base", "Kind of MedialMesh object", 1)
        obj.Type = TYPE
        # Global: the face may sit inside a PartDesign body, the analysis beside it.
        add("App::PropertyLinkSubGlobal", "Source", "Analysis", "The planar face analysed")
        add("App::PropertyFloat", "MergeFactor", "Analysis",
            "Merge singularities closer than this factor (0.25 to 1) times their medial radius; 0: do not merge")
        read_only = 1  # the results: shown, not edited
        add("App::PropertyIntegerList", "FlowTypes", "Results", "Flow type n of each edge of Shape", read_only)
        add("App::PropertyVectorList", "SingularityPositions", "Results", "Where the singularities are", read_only)
        add("App::PropertyIntegerList", "SingularityK", "Results", "k of each singularity (4 + k elements)", read_only)
        add("App::PropertyInteger", "SumK", "Results", "Sum of the singularities' k", read_only)
        add("App::PropertyInteger", "PredictedSumK", "Results",
            "Sum every quad mesh of the face must have: sum(2 - nc) - 4 (1 - holes)", read_only)
        add("App::PropertyString", "Status", "Results", "'ok', or why the face could not be analysed", read_only)

    def onDocumentRestored(self, obj):
        self.add_properties(obj)  # documents from older versions get the new properties
        # A document saved without the GUI has no view provider proxy to restore.
        if FreeCAD.GuiUp and obj.ViewObject and getattr(obj.ViewObject, "Proxy", None) is None:
            from . import viewproviders

            viewproviders.ViewProviderMedialAnalysis(obj.ViewObject)

    def execute(self, obj):
        # No exception may leave here: FreeCAD would show a traceback, not the problem.
        try:
            self.analyse(obj)
        except Exception as error:  # InputError, or anything unforeseen in a user's file
            # An InputError names the face already; anything else gets it here.
            message = str(error) if isinstance(error, ValueError) else f"{describe_source(obj)}: internal error: {error!r}"
            FreeCAD.Console.PrintError(f"MedialMesh: {obj.Label}: {message}\n")
            obj.Shape = Part.Shape()
            obj.FlowTypes = []
            obj.SingularityPositions = []
            obj.SingularityK = []
            obj.SumK = 0
            obj.PredictedSumK = 0
            obj.Status = message

    def analyse(self, obj):
        if not obj.Source or not obj.Source[1]:
            raise InputError("no face linked in Source")
        source, subnames = obj.Source
        if len(subnames) != 1:
            raise InputError(f"{describe_source(obj)}: Source must name one face, got {len(subnames)}")
        merge = obj.MergeFactor if obj.MergeFactor > 0 else None
        face = analysis.global_face(source, subnames[0])
        result = analysis.analyse_face(face, merge=merge, name=describe_source(obj))
        obj.Shape = Part.Compound([run.shape for run in result.flow])
        obj.FlowTypes = [run.n for run in result.flow]
        obj.SingularityPositions = [s.point for s in result.singularities]
        obj.SingularityK = [s.k for s in result.singularities]
        obj.SumK = result.sum_k
        obj.PredictedSumK = result.predicted_sum_k
        obj.Status = "ok"

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


def describe_source(obj):
    """'Body.Pad.Face7'-like name of the linked face, for messages."""
    if not obj.Source:
        return "(no face)"
    source, subnames = obj.Source
    return f"{source.Label}.{','.join(subnames) or '?'}"


def make_analysis_object(doc, obj, subname, merge=0.75, name="MedialAnalysis"):
    """Create the parametric analysis of face `subname` ('Face3') of `obj` in
    `doc`, compute it and return it. merge: the MergeFactor (0: no merging)."""
    analysis_obj = doc.addObject("Part::FeaturePython", name)
    MedialAnalysis(analysis_obj)
    analysis_obj.Source = (obj, [subname])
    analysis_obj.MergeFactor = merge
    analysis_obj.Label = f"{name}_{obj.Label}_{subname}"
    if FreeCAD.GuiUp:
        from . import viewproviders

        viewproviders.ViewProviderMedialAnalysis(analysis_obj.ViewObject)
    analysis_obj.recompute()
    return analysis_obj

# SPDX-License-Identifier: LGPL-2.1-or-later
"""The parametric objects: the analysis of a linked face (its medial axis,
cut into runs of one flow type, and its mesh singularities) and its block
decomposition (the splits, with a Sketch of them).

The analysis's Shape is the axis as one edge per flow run, in 3-D on the
face; FlowTypes gives each edge's n. The singularities are kept as positions
and k. The decomposition's Shape is the splits, in 3-D on the face. Both
recompute when the face or MergeFactor changes. A face that cannot be
analysed leaves an empty shape, the problem in Status and in the report view.
"""

import FreeCAD
import Part
from _medialmesh import InputError

from . import analysis, decomposition

TYPE = "MedialMesh::Analysis"
DECOMPOSITION_TYPE = "MedialMesh::Decomposition"


def add_face_properties(obj, type_name, group, source_doc):
    """Give a MedialMesh object the properties every one of them has (Type,
    Source, MergeFactor), missing ones only (documents from older versions);
    return the function that adds further properties the same way."""

    def add(kind, name, group, doc, mode=0):
        if not hasattr(obj, name):
            obj.addProperty(kind, name, group, doc, mode)

    add("App::PropertyString", "Type", "Base", "Kind of MedialMesh object", 1)
    obj.Type = type_name
    # Global: the face may sit inside a PartDesign body, the object beside it.
    add("App::PropertyLinkSubGlobal", "Source", group, source_doc)
    add("App::PropertyFloat", "MergeFactor", group,
        "Merge singularities closer than this factor (0.25 to 1) times their medial radius; 0: do not merge")
    return add


class MedialAnalysis:
    """Proxy of a Part::FeaturePython analysing one face."""

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)

    def add_properties(self, obj):
        add = add_face_properties(obj, TYPE, "Analysis", "The planar face analysed")
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
            message = report_failure(obj, error)
            obj.Shape = Part.Shape()
            obj.FlowTypes = []
            obj.SingularityPositions = []
            obj.SingularityK = []
            obj.SumK = 0
            obj.PredictedSumK = 0
            obj.Status = message

    def analyse(self, obj):
        merge = obj.MergeFactor if obj.MergeFactor > 0 else None
        face = linked_face(obj)
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


class MedialDecomposition:
    """Proxy of a Part::FeaturePython decomposing one face into blocks."""

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)

    def add_properties(self, obj):
        add = add_face_properties(obj, DECOMPOSITION_TYPE, "Decomposition", "The planar face decomposed")
        # Hidden: a plain link would make this object depend on the sketch it
        # rewrites, so the sketch would stay touched after every recompute.
        add("App::PropertyLinkHidden", "Sketch", "Decomposition", "The splits as a sketch on the face's plane")
        read_only = 1
        add("App::PropertyInteger", "BlockCount", "Results", "Blocks the splits cut the face into", read_only)
        add("App::PropertyInteger", "PolygonBlocks", "Results",
            "Blocks meshed by an m-sided template around one singularity", read_only)
        add("App::PropertyInteger", "SubmapBlocks", "Results", "Blocks meshed by submapping", read_only)
        add("App::PropertyInteger", "SplitCount", "Results", "Splits, one edge or wire each in Shape", read_only)
        add("App::PropertyInteger", "FixedCount", "Results",
            "Singularities fixed at corners of blocks rather than inside one", read_only)
        add("App::PropertyStringList", "Notes", "Results",
            "What the decomposition had to do, such as fixing a singularity that no split could free", read_only)
        add("App::PropertyString", "Status", "Results", "'ok', or why the face could not be decomposed", read_only)

    def onDocumentRestored(self, obj):
        self.add_properties(obj)
        if FreeCAD.GuiUp and obj.ViewObject and getattr(obj.ViewObject, "Proxy", None) is None:
            from . import viewproviders

            viewproviders.ViewProviderMedialDecomposition(obj.ViewObject)

    def execute(self, obj):
        # No exception may leave here: FreeCAD would show a traceback, not the problem.
        try:
            self.decompose(obj)
        except Exception as error:  # InputError, or anything unforeseen in a user's file
            message = report_failure(obj, error)
            obj.Shape = Part.Shape()
            obj.BlockCount = 0
            obj.PolygonBlocks = 0
            obj.SubmapBlocks = 0
            obj.SplitCount = 0
            obj.FixedCount = 0
            obj.Notes = []
            obj.Status = message
            if obj.Sketch:  # no splits left over from an earlier face
                obj.Sketch.deleteAllGeometry()
                obj.Sketch.recompute()

    def decompose(self, obj):
        merge = obj.MergeFactor if obj.MergeFactor > 0 else None
        face = linked_face(obj)
        result = decomposition.decompose_face(face, merge=merge, name=describe_source(obj))
        obj.Shape = Part.Compound(result.splits)
        obj.BlockCount = len(result.blocks)
        obj.PolygonBlocks = sum(1 for b in result.blocks if b.kind == "polygon")
        obj.SubmapBlocks = sum(1 for b in result.blocks if b.kind == "submap")
        obj.SplitCount = len(result.splits)
        obj.FixedCount = len(result.fixed)
        obj.Notes = result.notes
        obj.Status = "ok"
        if obj.Sketch:
            self.update_sketch(obj.Sketch, result)

    def update_sketch(self, sketch, result):
        """Replace the sketch's geometry by the splits, one line segment per
        straight piece, in the coordinates of the face's 2-D frame."""
        to_sketch = result.placement.inverse()

        def in_sketch(point):
            local = to_sketch.multVec(point)
            return FreeCAD.Vector(local.x, local.y, 0)  # on the plane, not 1e-16 off it

        segments = [Part.LineSegment(in_sketch(edge.Vertexes[0].Point), in_sketch(edge.Vertexes[-1].Point))
                    for split in result.splits for edge in split.Edges]
        sketch.Placement = result.placement
        sketch.deleteAllGeometry()
        if segments:
            sketch.addGeometry(segments)
        # The sketch does not depend on this object (see Sketch above): its
        # shape must follow now, even when only this object is recomputed.
        sketch.recompute()

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


def report_failure(obj, error):
    """Put the problem of a failed execute in the report view and return it.
    An InputError names the face already; anything else gets it here."""
    message = str(error) if isinstance(error, ValueError) else f"{describe_source(obj)}: internal error: {error!r}"
    FreeCAD.Console.PrintError(f"MedialMesh: {obj.Label}: {message}\n")
    return message


def linked_face(obj):
    """The one face obj.Source links, placed where it is seen in 3-D."""
    if not obj.Source or not obj.Source[1]:
        raise InputError("no face linked in Source")
    source, subnames = obj.Source
    if len(subnames) != 1:
        raise InputError(f"{describe_source(obj)}: Source must name one face, got {len(subnames)}")
    return analysis.global_face(source, subnames[0])


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


def make_decomposition_object(doc, obj, subname, merge=0.75, name="MedialDecomposition"):
    """Create the parametric decomposition of face `subname` ('Face3') of
    `obj` in `doc` with its Sketch, compute it and return it. merge: the
    MergeFactor (0: no merging)."""
    decomposition_obj = doc.addObject("Part::FeaturePython", name)
    MedialDecomposition(decomposition_obj)
    decomposition_obj.Source = (obj, [subname])
    decomposition_obj.MergeFactor = merge
    decomposition_obj.Label = f"{name}_{obj.Label}_{subname}"
    sketch = doc.addObject("Sketcher::SketchObject", name + "Sketch")
    sketch.Label = f"{decomposition_obj.Label}_Sketch"
    decomposition_obj.Sketch = sketch
    if FreeCAD.GuiUp:
        from . import viewproviders

        viewproviders.ViewProviderMedialDecomposition(decomposition_obj.ViewObject)
        sketch.ViewObject.Visibility = False  # the decomposition draws the same lines
    decomposition_obj.recompute()
    return decomposition_obj

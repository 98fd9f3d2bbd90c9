# SPDX-License-Identifier: LGPL-2.1-or-later
"""The parametric objects: the analysis of a linked face (its medial axis,
cut into runs of one flow type, and its mesh singularities), its block
decomposition (the splits, with a Sketch of them) and the quad mesh of
linked faces (a FEM mesh object, with a Sketch of the splits).

The analysis's Shape is the axis as one edge per flow run, in 3-D on the
face; FlowTypes gives each edge's n. The singularities are kept as positions
and k. The decomposition's Shape is the splits, in 3-D on the face. Both
recompute when the face or MergeFactor changes. A face that cannot be
analysed leaves an empty shape, the problem in Status and in the report view.
The quad mesh's FemMesh is in 3-D on the faces; it recomputes when a face or
a parameter changes, and a failure leaves an empty FemMesh and the problem.
"""

import Fem
import FreeCAD
import Part
from _medialmesh import InputError

from . import analysis, decomposition, meshing, messages

TYPE = "MedialMesh::Analysis"
DECOMPOSITION_TYPE = "MedialMesh::Decomposition"
QUAD_MESH_TYPE = "MedialMesh::QuadMesh"


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


class MedialObject:
    """What every MedialMesh proxy does: add its properties (missing ones
    only, for documents from older versions), get its view provider back
    after a restore, and compute in execute with no exception escaping.
    Subclasses give VIEW_PROVIDER (a class name in viewproviders), compute
    (fill the outputs and results) and clear_output (empty the outputs)."""

    VIEW_PROVIDER = ""

    def __init__(self, obj):
        obj.Proxy = self
        self.add_properties(obj)

    def onDocumentRestored(self, obj):
        self.add_properties(obj)
        # A document saved without the GUI has no view provider proxy to restore.
        if FreeCAD.GuiUp and obj.ViewObject and getattr(obj.ViewObject, "Proxy", None) is None:
            attach_view_provider(obj)

    def execute(self, obj):
        # No exception may leave here: FreeCAD would show a traceback, not the problem.
        try:
            self.compute(obj)
        except Exception as error:  # InputError, or anything unforeseen in a user's file
            store_failure(obj, report_failure(obj, error))

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


def attach_view_provider(obj):
    """Give obj's view object the workbench's view provider for its proxy."""
    from . import viewproviders

    getattr(viewproviders, obj.Proxy.VIEW_PROVIDER)(obj.ViewObject)


class MedialAnalysis(MedialObject):
    """Proxy of a Part::FeaturePython analysing one face."""

    VIEW_PROVIDER = "ViewProviderMedialAnalysis"

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

    def clear_output(self, obj):
        obj.Shape = Part.Shape()

    def compute(self, obj):
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


class MedialDecomposition(MedialObject):
    """Proxy of a Part::FeaturePython decomposing one face into blocks."""

    VIEW_PROVIDER = "ViewProviderMedialDecomposition"

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

    def clear_output(self, obj):
        obj.Shape = Part.Shape()

    def compute(self, obj):
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
            update_sketch(obj.Sketch, result.placement, result.splits)


def update_sketch(sketch, placement, splits):
    """Replace the sketch's geometry by the splits lying on the plane of
    `placement` (a face's 2-D frame), one line segment per straight piece, in
    the frame's coordinates; splits off that plane (on other faces) are left out."""
    to_sketch = placement.inverse()
    tolerance = 1e-9 * max([1.0] + [split.BoundBox.DiagonalLength for split in splits])

    def in_sketch(point):
        local = to_sketch.multVec(point)
        return FreeCAD.Vector(local.x, local.y, 0)  # on the plane, not 1e-16 off it

    def on_plane(edge):
        return all(abs(to_sketch.multVec(v.Point).z) <= tolerance for v in edge.Vertexes)

    segments = [Part.LineSegment(in_sketch(edge.Vertexes[0].Point), in_sketch(edge.Vertexes[-1].Point))
                for split in splits for edge in split.Edges if on_plane(edge)]
    sketch.Placement = placement
    sketch.deleteAllGeometry()
    if segments:
        sketch.addGeometry(segments)
    # The sketch does not depend on the object that owns it (a hidden link):
    # its shape must follow now, even when only that object is recomputed.
    sketch.recompute()


def store_failure(obj, message):
    """Empty a MedialMesh object (its output, its Results, its Sketch: no
    figure or split left over from an earlier face) and put why into its
    Status: what execute does when computing fails, and what the task panel
    does with a failure it met off the GUI thread and has said already."""
    obj.Proxy.clear_output(obj)
    clear_results(obj, message)
    sketch = getattr(obj, "Sketch", None)
    if sketch:
        sketch.deleteAllGeometry()
        sketch.recompute()


def clear_results(obj, status):
    """Empty every property of the Results group (no figure left over from
    an earlier face) and put `status`, the problem, into Status."""
    empty = {"App::PropertyInteger": 0, "App::PropertyFloat": 0.0, "App::PropertyVector": FreeCAD.Vector()}
    for name in obj.PropertiesList:
        if obj.getGroupOfProperty(name) == "Results" and name != "Status":
            setattr(obj, name, empty.get(obj.getTypeIdOfProperty(name), []))
    obj.Status = status


def report_failure(obj, error):
    """Put the problem of a failed execute in the report view, worded as
    everywhere (messages.failure_message), and return it."""
    message = messages.failure_message(error, describe_source(obj))
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
    """'Pad.Face7'-like name of the linked face (faces), for messages."""
    if not obj.Source:
        return "(no face)"
    links = obj.Source if isinstance(obj.Source, list) else [obj.Source]  # a LinkSubList, or a LinkSub
    return ", ".join(f"{source.Label}.{','.join(subnames) or '?'}" for source, subnames in links)


def unique_label(doc, kind, faces):
    """'QuadMesh (Plate Face1)': the kind of object and the face it is of
    ('Plate Face1 + 2 faces' for several), made unique by a number after
    the kind ('QuadMesh 2 (Plate Face1)'), never by changing the face's
    name as FreeCAD's own rule would ('..._Face069' for a second mesh of
    Face68). faces: (object, 'FaceN') pairs."""
    first, subname = faces[0]
    others = len(faces) - 1
    what = f"{first.Label} {subname}" + (f" + {others} face{'s' if others > 1 else ''}" if others else "")
    taken = {o.Label for o in doc.Objects}
    number = 1
    while True:
        label = f"{kind}{f' {number}' if number > 1 else ''} ({what})"
        if label not in taken and f"{label} splits" not in taken:
            return label
        number += 1


def make_analysis_object(doc, obj, subname, merge=0.75, name="MedialAnalysis"):
    """Create the parametric analysis of face `subname` ('Face3') of `obj` in
    `doc`, compute it and return it. merge: the MergeFactor (0: no merging)."""
    analysis_obj = doc.addObject("Part::FeaturePython", name)
    MedialAnalysis(analysis_obj)
    analysis_obj.Source = (obj, [subname])
    analysis_obj.MergeFactor = merge
    analysis_obj.Label = unique_label(doc, "MedialAxis", [(obj, subname)])
    if FreeCAD.GuiUp:
        attach_view_provider(analysis_obj)
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
    decomposition_obj.Label = unique_label(doc, "Decomposition", [(obj, subname)])
    sketch = doc.addObject("Sketcher::SketchObject", name + "Sketch")
    sketch.Label = f"{decomposition_obj.Label} splits"
    decomposition_obj.Sketch = sketch
    if FreeCAD.GuiUp:
        attach_view_provider(decomposition_obj)
        sketch.ViewObject.Visibility = False  # the decomposition draws the same lines
    decomposition_obj.recompute()
    return decomposition_obj


ELEMENT_ORDERS = ["1st", "2nd"]  # as FreeCAD's Gmsh mesh object names them
NOT_MESHED = "not meshed yet"  # the Status of a mesh object made with compute=False


class MedialQuadMesh(MedialObject):
    """Proxy of a Fem::FemMeshObjectPython holding the quad mesh of its
    Source faces, with a Sketch of the decomposition's splits."""

    Type = QUAD_MESH_TYPE
    VIEW_PROVIDER = "ViewProviderMedialQuadMesh"

    def add_properties(self, obj):
        def add(kind, name, group, doc, mode=0):
            if hasattr(obj, name):
                return False
            obj.addProperty(kind, name, group, doc, mode)
            return True

        add("App::PropertyString", "Type", "Base", "Kind of MedialMesh object", 1)
        obj.Type = QUAD_MESH_TYPE
        # Global: the faces may sit inside PartDesign bodies or App::Part containers, the mesh beside them.
        add("App::PropertyLinkSubListGlobal", "Source", "Mesh", "The planar faces meshed (of one or more objects)")
        add("App::PropertyLength", "ElementSize", "Mesh",
            "Target element size; 0: the faces' bounding-box diagonal / 20")
        if add("App::PropertyFloat", "MergeFactor", "Mesh",
               "Merge singularities closer than this factor (0.25 to 1) times their medial radius; 0: do not merge"):
            obj.MergeFactor = 0.75
        if add("App::PropertyEnumeration", "ElementOrder", "Mesh", "1st: 4-node quads, 2nd: 8-node quads"):
            obj.ElementOrder = ELEMENT_ORDERS
            obj.ElementOrder = "1st"
        if add("App::PropertyBool", "Smoothing", "Mesh", "Smooth the mesh inside the blocks"):
            obj.Smoothing = True
        # Hidden: see MedialDecomposition.Sketch.
        add("App::PropertyLinkHidden", "Sketch", "Mesh",
            "The decomposition's splits as a sketch on the first face's plane")
        # FreeCAD's solvers find the geometry a mesh is made from in Part (as for its Gmsh mesh objects).
        add("App::PropertyLinkGlobal", "Part", "FEM Mesh", "The object of the first source face", 1)
        read_only = 1
        add("App::PropertyInteger", "QuadCount", "Results", "Quads in the mesh", read_only)
        add("App::PropertyInteger", "NodeCount", "Results", "Nodes in the mesh", read_only)
        add("App::PropertyFloat", "MinScaledJacobian", "Results", "Smallest scaled Jacobian of a quad (1: a square)",
            read_only)
        add("App::PropertyFloat", "MeanScaledJacobian", "Results", "Mean scaled Jacobian of the quads", read_only)
        add("App::PropertyFloat", "MinShape", "Results",
            "Smallest Verdict shape of a quad (1: a square; sees angles and stretch, under 0.3 is poor)", read_only)
        add("App::PropertyFloat", "MeanShape", "Results", "Mean Verdict shape of the quads", read_only)
        add("App::PropertyFloat", "MaxEdgeRatio", "Results", "Largest ratio of a quad's longest side to its shortest",
            read_only)
        add("App::PropertyFloat", "MaxSkew", "Results",
            "Largest Verdict skew of a quad (0: its axes at right angles, 1: flat)", read_only)
        add("App::PropertyInteger", "PoorShapeCount", "Results", "Quads with a Verdict shape under 0.3", read_only)
        add("App::PropertyInteger", "NeedleCount", "Results", "Quads whose longest side is over 10 times the shortest",
            read_only)
        add("App::PropertyVector", "WorstElementPosition", "Results",
            "Centre of the quad of least shape, in the document's coordinates", read_only)
        add("App::PropertyInteger", "IrregularNodes", "Results",
            "Nodes with other than 4 elements inside, or other than the corner's number on the boundary", read_only)
        add("App::PropertyFloat", "Seconds", "Results", "Time the mesh took, FemMesh included", read_only)
        add("App::PropertyString", "Status", "Results",
            "'ok', 'ok (fallback: ...)' when a fallback made the mesh, or why the faces could not be meshed",
            read_only)
        add("App::PropertyStringList", "Notes", "Results", "What the mesher had to do, for the user", read_only)

    def clear_output(self, obj):
        obj.FemMesh = Fem.FemMesh()

    def compute(self, obj):
        faces, names = linked_faces(obj)
        key = mesh_key(obj, faces)
        result = recent_mesh(obj, key)  # after an Undo or Redo: the mesh the values had
        if result is None:
            result = meshing.mesh_face(faces, name=names, **mesh_arguments(obj.ElementSize.Value, obj.ElementOrder,
                                                                           obj.MergeFactor, obj.Smoothing))
        store_mesh(obj, result, key)


# The quad mesh's parameters: a change of any makes another mesh.
MESH_PARAMETERS = ("ElementSize", "MergeFactor", "ElementOrder", "Smoothing")
# The meshes a quad mesh object keeps in memory (never saved) to take back
# on Undo and Redo, the newest first, if they are under this many elements.
RECENT_MESHES = 2
RECENT_MESH_MAX_QUADS = 300_000


def parameter_values(obj):
    """The quad mesh object's parameters as plain values (the size in mm),
    as the task panel reads its fields."""
    values = {name: getattr(obj, name) for name in MESH_PARAMETERS}
    values["ElementSize"] = obj.ElementSize.Value
    return values


def mesh_key(obj, faces, values=None):
    """What a mesh of obj is for: its parameter values (or `values`, as
    parameter_values gives them) and its faces' geometry."""
    values = values or parameter_values(obj)
    return tuple(values[name] for name in MESH_PARAMETERS), tuple(hash(f.exportBrepToString()) for f in faces)


def recent_mesh(obj, key):
    """The result kept for this key (see RECENT_MESHES), or None."""
    return next((result for k, result in getattr(obj.Proxy, "recent", []) if k == key), None)


def store_mesh(obj, result, key=None):
    """Put a mesh_face result for obj's faces and parameters into the quad
    mesh object: its FemMesh, the Results, the Sketch. The task panel stores
    the mesh it made off the GUI thread this way, so that OK never meshes
    again. key (mesh_key): kept with the result for Undo and Redo."""
    if key is not None and result.quality["quads"] <= RECENT_MESH_MAX_QUADS:
        recent = [(k, r) for k, r in getattr(obj.Proxy, "recent", []) if k != key]
        obj.Proxy.recent = [(key, result)] + recent[:RECENT_MESHES - 1]
    if obj.Part != obj.Source[0][0]:
        obj.Part = obj.Source[0][0]
    obj.Proxy.element_shape = result.element_shape  # for the view's colours; not saved
    obj.FemMesh = result.femmesh
    quality = result.quality
    obj.QuadCount = quality["quads"]
    obj.NodeCount = quality["nodes"]
    obj.MinScaledJacobian = quality["min_scaled_jacobian"]
    obj.MeanScaledJacobian = quality["mean_scaled_jacobian"]
    obj.MinShape = quality["min_shape"]
    obj.MeanShape = quality["mean_shape"]
    obj.MaxEdgeRatio = quality["max_edge_ratio"]
    obj.MaxSkew = quality["max_skew"]
    obj.PoorShapeCount = quality["poor_shape"]
    obj.NeedleCount = quality["needles"]
    if "worst_position" in quality:
        obj.WorstElementPosition = quality["worst_position"]
    obj.IrregularNodes = quality["irregular_nodes"]
    obj.Seconds = quality["seconds"]
    obj.Notes = result.notes
    obj.Status = ok_status(obj, result.fallbacks)
    if obj.Sketch:
        update_sketch(obj.Sketch, result.placement, result.splits)


def ok_status(obj, fallbacks):
    """'ok', or 'ok (fallback: ...)' with a warning in the report view: a
    mesh a fallback made is returned, but the user should know it was."""
    if not fallbacks:
        return "ok"
    FreeCAD.Console.PrintWarning(f"MedialMesh: {obj.Label}: meshed by a fallback ({', '.join(fallbacks)}); "
                                 "see the task panel's messages or its Notes\n")
    return messages.fallback_message(fallbacks)


def mesh_arguments(size, order, merge, smooth):
    """mesh_face's keyword arguments from the mesh object's property values
    (size 0: automatic; order '1st' or '2nd'; merge 0: no merging)."""
    return dict(size=size or None, order=ELEMENT_ORDERS.index(order) + 1, merge=merge or None, smooth=smooth)


def linked_faces(obj):
    """The faces obj.Source (a LinkSubList) links, placed where they are seen
    in 3-D, and their 'Pad.Face3'-like names."""
    faces, names = [], []
    for source, subnames in obj.Source:
        for subname in subnames:
            faces.append(analysis.global_face(source, subname))
            names.append(f"{source.Label}.{subname}")
    if not faces:
        raise InputError("no face linked in Source")
    return faces, names


def _source_links(obj, subnames):
    """(object, subname) pairs from make_mesh_object's arguments."""
    if subnames is None:
        pairs = [tuple(pair) for pair in obj]
    else:
        pairs = [(obj, name) for name in ([subnames] if isinstance(subnames, str) else subnames)]
    if not pairs:
        raise InputError("make_mesh_object: no face given")
    for source, subname in pairs:
        if not hasattr(source, "Shape") or not isinstance(subname, str):
            raise InputError(f"make_mesh_object: expected (object, 'FaceN') pairs, got ({source!r}, {subname!r})")
    return pairs


def _target_analysis(doc, analysis_obj):
    if analysis_obj is not None:
        return analysis_obj
    if FreeCAD.GuiUp:
        import FemGui

        active = FemGui.getActiveAnalysis()
        if active is not None and active.Document == doc:
            return active
    analyses = [o for o in doc.Objects if o.isDerivedFrom("Fem::FemAnalysis")]
    return analyses[0] if len(analyses) == 1 else None


def make_mesh_object(doc, obj, subnames, size=None, order=1, merge=0.75, smooth=True, analysis=None,
                     name="MedialQuadMesh", compute=True):
    """Create the parametric quad mesh of faces `subnames` ('Face3' or a list)
    of `obj` in `doc` (or, with subnames None, of the (object, 'FaceN') pairs
    `obj`), with its Sketch, put it into `analysis` (or the active FEM
    analysis, or the document's only one), compute it and return it.
    size: element size (None or 0: automatic); order 1 or 2; merge: the
    MergeFactor (None or 0: no merging); smooth: Smoothing. compute=False
    leaves it to be meshed (the Quad mesh command's task panel meshes it
    off the GUI thread and stores the result)."""
    pairs = _source_links(obj, subnames)
    if order not in (1, 2):
        raise InputError(f"make_mesh_object: element order must be 1 or 2, got {order!r}")
    mesh_obj = doc.addObject("Fem::FemMeshObjectPython", name)
    MedialQuadMesh(mesh_obj)
    mesh_obj.Source = [(source, [subname]) for source, subname in pairs]
    mesh_obj.ElementSize = size or 0
    mesh_obj.ElementOrder = ELEMENT_ORDERS[order - 1]
    mesh_obj.MergeFactor = merge or 0
    mesh_obj.Smoothing = smooth
    mesh_obj.Part = pairs[0][0]
    mesh_obj.Label = unique_label(doc, "QuadMesh", pairs)
    sketch = doc.addObject("Sketcher::SketchObject", name + "Sketch")
    sketch.Label = f"{mesh_obj.Label} splits"
    mesh_obj.Sketch = sketch
    target = _target_analysis(doc, analysis)
    if target is not None:
        target.addObject(mesh_obj)
    if FreeCAD.GuiUp:
        attach_view_provider(mesh_obj)
        sketch.ViewObject.Visibility = False  # the mesh shows the same lines
    if compute:
        mesh_obj.recompute()
    else:
        mesh_obj.Status = NOT_MESHED
    return mesh_obj

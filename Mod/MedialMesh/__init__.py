# SPDX-License-Identifier: LGPL-2.1-or-later
"""MedialMesh: block-structured quad meshes of planar faces from their medial axis.

The Python API for macros and for the workbench. The work is done by the
compiled module _medialmesh, which Init.py finds in <addon>/build/lib.
"""

try:
    import _medialmesh
except ImportError as error:
    raise ImportError(
        f"MedialMesh: cannot import the compiled core _medialmesh ({error}); "
        "build it with tools/install.sh"
    ) from error


# re-exported so that callers need not import _medialmesh
InputError = _medialmesh.InputError
SelfCheckError = _medialmesh.SelfCheckError
Cancelled = _medialmesh.Cancelled  # raised by mesh_face when its progress.cancel() was called


def boundary_model(face, name="face"):
    """Return the boundary model of a planar face as a dict.

    face: a Part.Face, or anything with exportBrepToString().
    name: names the face in error messages and in the result.
    Raises InputError when the face cannot be meshed (not planar, open wire, ...).
    """
    if not hasattr(face, "exportBrepToString"):
        raise InputError(f"{name}: expected a Part.Face, got {type(face).__name__}")
    return _medialmesh.face_model(face.exportBrepToString(), name)


def medial_axis(face, name="face"):
    """Return the medial axis of a planar face as a dict.

    {'vertices': [{'x', 'y', 'r', 'kind'}], 'edges': [{'from', 'to', 'polyline'}],
    'frame': {...}}: coordinates in the face's 2-D frame; to_3d() maps them back.
    kind is 'junction', 'flare', 'finite_contact' or 'curvature_contact'.
    Raises InputError for faces that cannot be meshed.
    """
    if not hasattr(face, "exportBrepToString"):
        raise InputError(f"{name}: expected a Part.Face, got {type(face).__name__}")
    return _medialmesh.medial_axis(face.exportBrepToString(), name)


def analyse_face(face, merge=None, mesh_size=None, name="face"):
    """Return the medial axis, flow types and singularities of a planar face, in 3-D.

    The result (MedialMesh.analysis.FaceAnalysis) has vertices (point, radius,
    kind), edges (one Part.Edge per medial edge), flow (edge index, flow type
    n and a Part.Edge per run of one n), singularities (point, k, at, members),
    unmerged (the singularities before merging), sum_k and predicted_sum_k.
    merge: merge singularities closer than this factor (0.25 to 1) times their
    medial radius; mesh_size: or closer than this length; both None: unmerged.
    Raises InputError naming the face and the problem.
    """
    from .analysis import analyse_face as analyse

    return analyse(face, merge=merge, mesh_size=mesh_size, name=name)


def make_analysis_object(doc, obj, subname, merge=0.75):
    """Create, compute and return the parametric analysis of face `subname`
    ('Face3') of document object `obj`: a Part::FeaturePython whose shape is
    the medial axis coloured by flow type, with the singularities, that
    recomputes when the face or its MergeFactor (0: no merging) changes."""
    from .objects import make_analysis_object as make

    return make(doc, obj, subname, merge=merge)


def decompose_face(face, merge=None, mesh_size=None, name="face"):
    """Return the block decomposition of a planar face, in 3-D.

    The result (MedialMesh.decomposition.FaceDecomposition) has splits (a
    Part.Edge per straight split, a Part.Wire per bent one, lying on the
    face), blocks (kind 'polygon' or 'submap', sides, outline as a closed
    Part.Wire, area, the singularity point and k it holds or None, corners
    with their types), fixed (singularities at block corners), singularities
    (all, after merging: point, k), fallback, notes and placement (the face's
    2-D frame). merge, mesh_size: as for analyse_face; both None: unmerged.
    Raises InputError naming the face and the problem.
    """
    from .decomposition import decompose_face as decompose

    return decompose(face, merge=merge, mesh_size=mesh_size, name=name)


def make_decomposition_object(doc, obj, subname, merge=0.75):
    """Create, compute and return the parametric decomposition of face
    `subname` ('Face3') of document object `obj`: a Part::FeaturePython whose
    shape is the splits, with a Sketch of them on the face's plane, that
    recomputes when the face or its MergeFactor (0: no merging) changes."""
    from .objects import make_decomposition_object as make

    return make(doc, obj, subname, merge=merge)


def mesh_face(face_or_faces, size=None, order=1, merge=0.75, smooth=True, name=None, progress=None):
    """Quad-mesh a planar Part.Face (placed in 3-D as it is) or a list of them.

    size: target element size (None or 0: the bounding-box diagonal / 20);
    order: 1 (4-node quads) or 2 (8-node quads); merge: merge singularities
    closer than this factor (0.25 to 1) times their medial radius, None or 0:
    no merging; smooth: smooth the mesh. The result
    (MedialMesh.meshing.FaceMesh) has femmesh (a Fem.FemMesh of quads, node
    ids 1..N, element ids 1..M), splits (Part edges and wires of the
    decomposition), singularities ((Vector, k) pairs), quality (quads, nodes,
    min_scaled_jacobian, mean_scaled_jacobian, min_shape, mean_shape,
    max_edge_ratio, max_skew, poor_shape, needles, worst_position,
    irregular_nodes, seconds, and the full report with every Verdict measure
    under "measures"),
    notes, placement (the first face's 2-D frame), per_face, fallbacks, and
    nodes, elements and element_shape as numpy arrays.
    progress: a MedialMesh.meshing.Progress, to follow the call from another
    thread (text(), fraction()) and stop it (cancel()).
    Raises InputError naming the face and the problem, SelfCheckError when a
    stage fails its own checks, Cancelled when progress.cancel() was called.
    """
    from .meshing import mesh_face as mesh

    return mesh(face_or_faces, size=size, order=order, merge=merge, smooth=smooth, name=name, progress=progress)


def make_mesh_object(doc, obj, subnames, size=None, order=1, merge=0.75, smooth=True, analysis=None,
                     name="MedialQuadMesh", compute=True):
    """Create, compute and return the parametric quad mesh of faces
    `subnames` ('Face3' or ['Face1', 'Face2']) of document object `obj` (or,
    with subnames None, of the (object, 'FaceN') pairs `obj`): a
    Fem::FemMeshObjectPython with a Sketch of the splits, put into `analysis`
    (or the active FEM analysis, or the document's only one), that recomputes
    when a face or a parameter (ElementSize, MergeFactor, ElementOrder,
    Smoothing) changes. size, order, merge, smooth: as for mesh_face.
    compute=False leaves it unmeshed, for the task panel to mesh."""
    from .objects import make_mesh_object as make

    return make(doc, obj, subnames, size=size, order=order, merge=merge, smooth=smooth, analysis=analysis,
                name=name, compute=compute)


def to_3d(frame, x, y):
    """Map a point of a face's 2-D frame (from boundary_model or medial_axis) to 3-D."""
    return tuple(o + x * a + y * b for o, a, b in zip(frame["origin"], frame["x_dir"], frame["y_dir"]))


def module_path():
    """Return the file the compiled module _medialmesh was loaded from."""
    return _medialmesh.__file__

# SPDX-License-Identifier: LGPL-2.1-or-later
"""Quad-mesh planar faces into a Fem.FemMesh, with the decomposition that
made the mesh (its splits and singularities) as FreeCAD geometry in 3-D."""

import time
from dataclasses import dataclass
from typing import List, Tuple

import Fem
import FreeCAD
import numpy
import Part

import _medialmesh

from . import decomposition

Cancelled = _medialmesh.Cancelled  # raised by mesh_face when its progress was cancelled

# The automatic element size: the faces' bounding-box diagonal over this.
AUTOMATIC_SIZE_DIVISOR = 20.0
# The FEM mesh is built this many elements at a time, its progress told
# and a cancel heard between them.
FEMMESH_CHUNK = 20_000
# Each stage's share of a run, for a progress bar: measured on a face of a
# million quads, where the compiled mesher took 2.1 s (the blocks most of
# it) and building FreeCAD's FemMesh 3.2 s.
CORE_STAGE_WEIGHTS = {"medial axis": 1, "decomposition": 1, "interval counts": 1, "blocks": 20, "smoothing": 5,
                      "checks": 2, "joining faces": 3, "quality": 2}
CORE_SHARE = 0.4  # of the whole run; the FemMesh the rest


class Progress:
    """How far a mesh_face call has got, read from another thread (a GUI's
    progress bar), and cancel() to stop it: mesh_face then raises Cancelled.
    text() says the stage ("Meshing: blocks 12 of 40", "Building the FEM
    mesh: 40 %"), fraction() how much of the run is done (0 to 1)."""

    def __init__(self):
        self.core = _medialmesh.Progress()
        self.building = False  # building the FemMesh, after the compiled mesher
        self.built = 0  # nodes and elements of the FemMesh built, of
        self.elements = 0  # its nodes and elements

    def cancel(self):
        self.core.cancel()

    @property
    def cancelled(self):
        return self.core.cancelled

    def check(self):
        if self.core.cancelled:
            raise _medialmesh.Cancelled("meshing cancelled")

    def text(self):
        if self.building:
            return f"Building the FEM mesh: {100 * self.built // max(self.elements, 1)} %"
        stage, done, total = self.core.stage, self.core.done, self.core.total
        if not stage:
            return "Reading the faces"
        return f"Meshing: {stage}" + (f" {done} of {total}" if total else "")

    def fraction(self):
        if self.building:
            return CORE_SHARE + (1 - CORE_SHARE) * self.built / max(self.elements, 1)
        stage, done, total = self.core.stage, self.core.done, self.core.total
        if stage not in CORE_STAGE_WEIGHTS:
            return 0.0
        names = list(CORE_STAGE_WEIGHTS)
        before = sum(CORE_STAGE_WEIGHTS[n] for n in names[:names.index(stage)])
        within = CORE_STAGE_WEIGHTS[stage] * (min(done, total) / total if total else 0.5)
        return CORE_SHARE * (before + within) / sum(CORE_STAGE_WEIGHTS.values())


@dataclass
class FacePart:
    """What one face of a mesh_face call gave."""

    name: str
    splits: List[Part.Shape]  # a Part.Edge per straight split, a Part.Wire per bent one
    singularities: List[Tuple[FreeCAD.Vector, int]]  # (where, k): the node there has 4 + k elements
    quality: dict  # the face's quality report
    notes: List[str]
    placement: FreeCAD.Placement  # the face's 2-D frame: maps its (x, y, 0) to 3-D
    fallbacks: List[str]  # what made the face's mesh when the way asked for did not pass its checks


@dataclass
class FaceMesh:
    """The result of mesh_face.

    femmesh: a Fem.FemMesh of 4-node (order 1) or 8-node (order 2) quads,
    node ids 1..N, element ids 1..M; an 8-node quad lists its corners
    counter-clockwise seen from the face's normal, then the mid-side nodes of
    the sides corner 1-2, 2-3, 3-4, 4-1 (FreeCAD's, SMESH's and CalculiX's S8
    order). splits, singularities: of every face, in 3-D. quality: quads,
    nodes, min_scaled_jacobian, mean_scaled_jacobian, the Verdict summaries
    (min_shape, mean_shape, max_edge_ratio, max_skew, poor_shape: quads of
    shape under 0.3, needles: quads with sides over 10:1, worst_position:
    the centre of the quad of least shape), irregular_nodes
    (interior and boundary), seconds (the whole call, FemMesh included),
    mesher_seconds (the compiled mesher alone) and the rest of the mesher's
    report. placement: the first face's 2-D frame (for a sketch).
    per_face: a FacePart per face. fallbacks: the fallbacks any face's mesh
    was made by ("less merging", "kinks as corners", ...), empty when every
    face was meshed as asked. nodes, elements, element_shape: the mesh as
    numpy arrays, and each element's Verdict shape (for colouring).
    """

    femmesh: "Fem.FemMesh"
    splits: List[Part.Shape]
    singularities: List[Tuple[FreeCAD.Vector, int]]
    quality: dict
    notes: List[str]
    placement: FreeCAD.Placement
    per_face: List[FacePart]
    fallbacks: List[str]
    nodes: "numpy.ndarray"  # (N, 3): FemMesh node i + 1
    elements: "numpy.ndarray"  # (M, 4 or 8) 0-based node indices: FemMesh element j + 1
    element_shape: "numpy.ndarray"  # (M,) each element's Verdict shape


def build_femmesh(nodes, elements, progress=None):
    """A Fem.FemMesh of the (N, 3) nodes and the (M, 4 or 8) 0-based quads.
    progress (a Progress): told the nodes and elements built, and a cancel
    heard, as it goes."""
    femmesh = Fem.FemMesh()
    if progress is not None:
        progress.elements, progress.built, progress.building = len(nodes) + len(elements), 0, True

    def chunks(count):
        for start in range(0, count, FEMMESH_CHUNK):
            if progress is not None:
                progress.check()
            yield start, min(start + FEMMESH_CHUNK, count)
            if progress is not None:
                progress.built += min(FEMMESH_CHUNK, count - start)

    add_node = femmesh.addNode
    for start, end in chunks(len(nodes)):
        for node_id, (x, y, z) in enumerate(nodes[start:end].tolist(), start + 1):
            add_node(x, y, z, node_id)
    add_face = femmesh.addFace
    for start, end in chunks(len(elements)):
        for element_id, element in enumerate((elements[start:end] + 1).tolist(), start + 1):
            add_face(element, element_id)
    return femmesh


def femmesh_shapes(femmesh):
    """The Verdict shape of each quad of a FemMesh of quads (element ids
    1..M), as the mesher measures it: the least over the corners of twice the
    corner's area over the sum of its two sides squared, 0 for a corner
    turned the wrong way. Each quad is measured in its own plane, facing as
    the normal of its diagonals, so a quad folded on itself as a whole is
    not seen (the mesher's own numbers, kept by the object in the session
    that made the mesh, see those too)."""
    nodes = femmesh.Nodes
    ids = sorted(nodes)
    index = numpy.zeros(max(ids) + 1, dtype=int)
    index[ids] = numpy.arange(len(ids))
    points = numpy.array([tuple(nodes[i]) for i in ids])
    corners = numpy.array([femmesh.getElementNodes(e)[:4] for e in range(1, femmesh.FaceCount + 1)])
    p = points[index[corners]]  # (M, 4, 3)
    normal = numpy.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    normal /= numpy.maximum(numpy.linalg.norm(normal, axis=1), 1e-300)[:, None]
    shape = numpy.full(len(p), numpy.inf)
    for c in range(4):
        a = p[:, (c + 1) % 4] - p[:, c]
        b = p[:, (c + 3) % 4] - p[:, c]
        area = numpy.einsum("ij,ij->i", numpy.cross(a, b), normal)
        lengths = numpy.einsum("ij,ij->i", a, a) + numpy.einsum("ij,ij->i", b, b)
        shape = numpy.minimum(shape, numpy.where(area > 0, 2 * area / numpy.maximum(lengths, 1e-300), 0.0))
    return shape


def _quality(report, nodes=None, elements=None):
    """The report, with the Verdict summaries a user reads at the top level
    (min_shape, mean_shape, max_edge_ratio, max_skew, poor_shape, needles)
    and, given the mesh's nodes and elements, worst_position: the 3-D
    centroid of the element of least shape."""
    quality = dict(report)
    quality["irregular_nodes"] = report["irregular_interior"] + report["irregular_boundary"]
    quality["mesher_seconds"] = report["seconds"]
    measures = report["measures"]
    quality["min_shape"] = measures["shape"]["min"]
    quality["mean_shape"] = measures["shape"]["mean"]
    quality["max_edge_ratio"] = measures["edge_ratio"]["max"]
    quality["max_skew"] = measures["skew"]["max"]
    quality["poor_shape"] = report["counts"]["shape_below_0.3"]
    quality["needles"] = report["counts"]["edge_ratio_above_10"]
    worst = measures["shape"]["worst_element"]
    if nodes is not None and elements is not None and worst > 0:
        x, y, z = nodes[elements[worst - 1, :4]].mean(axis=0).tolist()
        quality["worst_position"] = FreeCAD.Vector(x, y, z)
    return quality


def _face_part(name, face, report, decomposition_report):
    result = decomposition.from_report(decomposition_report, face, name)
    notes = list(report.get("notes", []))
    notes += [note for note in result.notes if note not in notes]
    return FacePart(
        name=name,
        splits=result.splits,
        singularities=[(s.point, s.k) for s in result.singularities],
        quality=_quality(report),
        notes=notes,
        placement=result.placement,
        fallbacks=list(report.get("fallbacks", [])),
    )


def automatic_size(faces):
    """The element size used when none is given: the faces' bounding-box
    diagonal / 20."""
    box = faces[0].BoundBox
    for face in faces[1:]:
        box.add(face.BoundBox)
    return box.DiagonalLength / AUTOMATIC_SIZE_DIVISOR


def _names(name, count):
    if isinstance(name, (list, tuple)):
        if len(name) != count:
            raise _medialmesh.InputError(f"{count} faces but {len(name)} names")
        return [str(n) for n in name]
    if count == 1:
        return [name or "face"]
    return [f"{name or 'face'}{i + 1}" for i in range(count)]


def mesh_face(face_or_faces, size=None, order=1, merge=0.75, smooth=True, name=None, progress=None):
    """Quad-mesh a planar Part.Face (placed in 3-D as it is) or a list of them.

    size: target element size in document units; None or 0: the faces'
    bounding-box diagonal / 20. order: 1 (4-node quads) or 2 (8-node).
    merge: merge singularities closer than this factor (0.25 to 1) times their
    medial radius; None or 0: no merging. smooth: smooth the mesh.
    name: names the face (or, a list, the faces) in messages. progress: a
    Progress, to follow the call from another thread and to cancel it.
    Returns a FaceMesh. Raises MedialMesh.InputError (a ValueError) naming the
    face and the problem, MedialMesh.SelfCheckError when a stage fails its
    own checks, MedialMesh.Cancelled when progress.cancel() was called.
    """
    start = time.perf_counter()
    faces = list(face_or_faces) if isinstance(face_or_faces, (list, tuple)) else [face_or_faces]
    names = _names(name, len(faces))
    if not faces:
        raise _medialmesh.InputError("no face to mesh")
    for face, face_name in zip(faces, names):
        if not isinstance(face, Part.Face):
            raise _medialmesh.InputError(f"{face_name}: expected a Part.Face, got {type(face).__name__}")
    if order not in (1, 2):
        raise _medialmesh.InputError(f"{names[0]}: element order must be 1 or 2, got {order!r}")
    size = size or automatic_size(faces)
    merge = merge or None
    core_progress = progress.core if progress is not None else None

    if len(faces) == 1:
        result = _medialmesh.mesh(faces[0].exportBrepToString(), size, order=order, merge=merge, smooth=smooth,
                                  name=names[0], progress=core_progress)
        per_face = [_face_part(names[0], faces[0], result["report"], result["decomposition"])]
    else:
        result = _medialmesh.mesh_faces([face.exportBrepToString() for face in faces], size, order=order,
                                        merge=merge, merge_size=None, smooth=smooth, names=names,
                                        progress=core_progress)
        per_face = [_face_part(n, f, r["report"], r["decomposition"])
                    for n, f, r in zip(names, faces, result["faces"])]

    femmesh = build_femmesh(result["nodes"], result["elements"], progress)
    quality = _quality(result["report"], result["nodes"], result["elements"])
    quality["seconds"] = time.perf_counter() - start
    notes = []
    for part in per_face:
        prefix = f"{part.name}: " if len(per_face) > 1 else ""
        notes += [prefix + note for note in part.notes]
    return FaceMesh(
        femmesh=femmesh,
        splits=[split for part in per_face for split in part.splits],
        singularities=[s for part in per_face for s in part.singularities],
        quality=quality,
        notes=notes,
        placement=per_face[0].placement,
        per_face=per_face,
        fallbacks=list(result["report"].get("fallbacks", [])),
        nodes=result["nodes"],
        elements=result["elements"],
        element_shape=result["element_shape"],
    )

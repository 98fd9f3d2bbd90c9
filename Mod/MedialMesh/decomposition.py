# SPDX-License-Identifier: LGPL-2.1-or-later
"""Decompose a planar face into blocks for quad meshing: the splits and the
blocks they leave, as FreeCAD geometry lying on the face in 3-D."""

from dataclasses import dataclass
from typing import List, Optional

import FreeCAD
import Part

import _medialmesh

from . import to_3d as frame_to_3d

SPLIT_COLOUR = (0.749, 0.0, 0.749)  # magenta: apart from the flow and singularity colours


@dataclass
class Singularity:
    point: FreeCAD.Vector
    k: int  # the mesh node there has 4 + k elements


@dataclass
class Corner:
    point: FreeCAD.Vector
    type: int  # elements of the block there: 1 convex, 0 cusp, 3 or 4 reflex


@dataclass
class Block:
    kind: str  # 'polygon' (meshed by an m-sided template) or 'submap'
    sides: int  # m for a polygon, the number of logical sides for a submap
    outline: Part.Wire  # closed polygon; curved sides finely sampled
    area: float  # exact
    singularity: Optional[FreeCAD.Vector]  # the one floating inside, or None
    k: Optional[int]
    corners: List[Corner]  # logical corners, counter-clockwise seen from the face normal


@dataclass
class FaceDecomposition:
    splits: List[Part.Shape]  # a Part.Edge per straight split, a Part.Wire per bent one
    blocks: List[Block]
    fixed: List[Singularity]  # singularities at corners of blocks rather than inside one
    singularities: List[Singularity]  # all of them, after merging
    fallback: bool  # some singularity could not be given its own polygon block
    notes: List[str]  # what the decomposition had to do, for the user
    placement: FreeCAD.Placement  # the face's 2-D frame: maps its (x, y, 0) to 3-D


def frame_placement(frame):
    """The face's 2-D frame as a placement, so that a sketch with it has the
    frame's coordinates. The frame is right-handed: normal = x_dir x y_dir."""
    o, x, y, n = (frame[key] for key in ("origin", "x_dir", "y_dir", "normal"))
    return FreeCAD.Placement(FreeCAD.Matrix(x[0], y[0], n[0], o[0],
                                            x[1], y[1], n[1], o[1],
                                            x[2], y[2], n[2], o[2],
                                            0, 0, 0, 1))


def _straight_runs(points, tolerance):
    """The polyline's corners: its points without repeats and without those
    lying on the line between their neighbours (a split through a medial
    point is often straight, and is then one segment)."""
    kept = [points[0]]
    for i, p in enumerate(points[1:], 1):
        if p.distanceToPoint(kept[-1]) <= tolerance:
            continue
        if i + 1 < len(points) and p.distanceToLine(kept[-1], points[i + 1] - kept[-1]) <= tolerance:
            continue
        kept.append(p)
    return kept


def _split_shape(points):
    edges = [Part.LineSegment(a, b).toShape() for a, b in zip(points, points[1:])]
    return edges[0] if len(edges) == 1 else Part.Wire(edges)


def decompose_face(face, merge=None, mesh_size=None, name="face"):
    """Splits and blocks of a planar Part.Face, in 3-D.

    merge: merge singularities closer than this factor (0.25 to 1) times their
    medial radius; mesh_size: or closer than this length. Both None: unmerged.
    Raises MedialMesh.InputError (a ValueError) naming the face and the problem.
    """
    if not hasattr(face, "exportBrepToString"):
        raise _medialmesh.InputError(f"{name}: expected a Part.Face, got {type(face).__name__}")
    report = _medialmesh.decompose(face.exportBrepToString(), name, merge, mesh_size)
    return from_report(report, face, name)


def from_report(report, face, name="face"):
    """The FaceDecomposition of a decomposition report (from
    _medialmesh.decompose, or the 'decomposition' of _medialmesh.mesh) of
    the Part.Face `face`, in 3-D."""

    def to_3d(x, y):
        return FreeCAD.Vector(*frame_to_3d(report["frame"], x, y))

    def singularity(s):
        return Singularity(to_3d(s["x"], s["y"]), s["k"])

    tolerance = 1e-9 * face.BoundBox.DiagonalLength
    splits = []
    for split in report["splits"]:
        points = _straight_runs([to_3d(x, y) for x, y in split["polyline"]], tolerance)
        if len(points) < 2:
            raise RuntimeError(f"{name}: the decomposition returned a split of no length")
        splits.append(_split_shape(points))

    blocks = []
    for b in report["blocks"]:
        outline = [to_3d(x, y) for x, y in b["boundary"]]
        inside = b["singularity"]
        blocks.append(Block(
            kind=b["kind"],
            sides=b["sides"],
            outline=Part.makePolygon(outline + outline[:1]),
            area=b["area"],
            singularity=to_3d(inside["x"], inside["y"]) if inside else None,
            k=inside["k"] if inside else None,
            corners=[Corner(to_3d(c["x"], c["y"]), c["type"]) for c in b["corners"]],
        ))
    return FaceDecomposition(
        splits=splits,
        blocks=blocks,
        fixed=[singularity(s) for s in report["fixed"]],
        singularities=[singularity(s) for s in report["singularities"]],
        fallback=report["fallback"],
        notes=list(report["notes"]),
        placement=frame_placement(report["frame"]),
    )

# SPDX-License-Identifier: LGPL-2.1-or-later
"""Analyse a planar face: its medial axis, the mesh flow type along it and
the mesh singularities, as FreeCAD geometry lying on the face in 3-D."""

from dataclasses import dataclass, field
from typing import List

import FreeCAD
import Part

import _medialmesh

from . import to_3d as frame_to_3d

# Flow types n = 0, 1, 2 (and beyond, next to near-cusps): the colours of the
# SVG pictures, so that both tell the same story.
FLOW_COLOURS = [(0.122, 0.467, 0.706), (0.173, 0.627, 0.173), (1.0, 0.498, 0.055), (0.580, 0.404, 0.741)]
POSITIVE_COLOUR = (0.839, 0.153, 0.157)  # k > 0
NEGATIVE_COLOUR = (0.122, 0.310, 0.839)  # k < 0


def flow_colour(n):
    return FLOW_COLOURS[min(n, len(FLOW_COLOURS) - 1)]


@dataclass
class MedialVertex:
    point: FreeCAD.Vector
    radius: float
    kind: str  # 'junction', 'flare', 'finite_contact' or 'curvature_contact'


@dataclass
class FlowRun:
    edge: int  # index into FaceAnalysis.edges
    n: int  # flow type: quarter turns of the mesh between the facing boundaries
    shape: Part.Edge


@dataclass
class Singularity:
    point: FreeCAD.Vector
    k: int  # the mesh node there has 4 + k elements
    at: str  # what produced it ('junction', 'flow_switch', ..., or 'merged')
    members: List[int] = field(default_factory=list)  # indices into unmerged, when merged


@dataclass
class FaceAnalysis:
    vertices: List[MedialVertex]
    edges: List[Part.Edge]  # the medial edges
    flow: List[FlowRun]  # the medial edges cut where the flow type changes
    singularities: List[Singularity]
    unmerged: List[Singularity]  # before merging (the same list when not merged)
    sum_k: int
    predicted_sum_k: int  # sum over corners of (2 - nc) - 4 (1 - holes)


def global_face(obj, subname):
    """The face `subname` ('Face3') of a document object, placed where it is
    seen in 3-D: PartDesign features keep their shapes in their body's
    coordinates, so the containers' placements are applied on top."""
    face = obj.Shape.getElement(subname)
    if not isinstance(face, Part.Face):
        raise _medialmesh.InputError(f"{obj.Label}.{subname}: not a face")
    containers = obj.getGlobalPlacement().multiply(obj.Placement.inverse())
    if not containers.isIdentity():
        face = face.copy()
        face.Placement = containers.multiply(face.Placement)
    return face


def _polyline_edge(points):
    """One edge through the points: a degree-1 B-spline, exactly the polyline."""
    poles = [points[0]]
    for p in points[1:]:
        if p.distanceToPoint(poles[-1]) > 1e-12:
            poles.append(p)
    if len(poles) < 2:
        return None
    if len(poles) == 2:
        return Part.LineSegment(poles[0], poles[1]).toShape()
    knots = [0.0]
    for a, b in zip(poles, poles[1:]):
        knots.append(knots[-1] + a.distanceToPoint(b))
    curve = Part.BSplineCurve()
    curve.buildFromPolesMultsKnots(poles, [2] + [1] * (len(poles) - 2) + [2], knots, False, 1)
    return curve.toShape()


def analyse_face(face, merge=None, mesh_size=None, name="face"):
    """Medial axis, flow types and singularities of a planar Part.Face, in 3-D.

    merge: merge singularities closer than this factor (0.25 to 1) times their
    medial radius; mesh_size: or closer than this length. Both None: unmerged.
    Raises MedialMesh.InputError (a ValueError) naming the face and the problem.
    """
    if not hasattr(face, "exportBrepToString"):
        raise _medialmesh.InputError(f"{name}: expected a Part.Face, got {type(face).__name__}")
    report = _medialmesh.analyse(face.exportBrepToString(), name, merge, mesh_size)

    def to_3d(x, y):
        return FreeCAD.Vector(*frame_to_3d(report["frame"], x, y))

    axis = report["medial_axis"]
    vertices = [MedialVertex(to_3d(v["x"], v["y"]), v["r"], v["kind"]) for v in axis["vertices"]]
    edges = [_polyline_edge([to_3d(x, y) for x, y, _ in e["polyline"]]) for e in axis["edges"]]
    flow = []
    for run in report["flow"]:
        shape = _polyline_edge([to_3d(x, y) for x, y in run["polyline"]])
        if shape is not None:  # a run between two switches at one point has no length
            flow.append(FlowRun(run["edge"], run["n"], shape))

    def singularity(s):
        return Singularity(to_3d(s["x"], s["y"]), s["k"], s["at"], s.get("members", []))

    singularities = [singularity(s) for s in report["singularities"]]
    unmerged = [singularity(s) for s in report.get("unmerged", report["singularities"])]
    return FaceAnalysis(vertices, edges, flow, singularities, unmerged, report["sum_k"], report["predicted_sum_k"])

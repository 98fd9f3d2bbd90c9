# SPDX-License-Identifier: LGPL-2.1-or-later
"""CalculiX through FreeCAD on our quad mesh, in freecadcmd.

plate_with_hole (a square plate with a central hole) as a steel shell of
thickness 1 in a FEM Analysis: the edge at x = xmin fixed, a force pulling
the edge at x = xmax along +x. Meshed by make_mesh_object (8-node quads) and,
as the reference, by FreeCAD's own Gmsh mesh object (6-node triangles, fine
at the hole); both solved by FreeCAD's ccxtools. The stress concentration on
the net section, K_tn = max sigma_xx on the hole / (F / ((W - d) t)), must
agree within 5 %. Peterson's long-strip value for d/W is printed, not
checked: the plate is as long as it is wide and its end is fixed.

Run by run_freecad_test.sh (see freecad_runner.py):
  tests/freecad/run_freecad_test.sh tests/freecad/test_ccx_plate.py [BUILD_DIR [SHARED_DIR]]
"""

import sys
import tempfile
import time
import unittest

import FreeCAD
import Part

import MedialMesh
from MedialMesh import fem_example
from test_analysis import shared_face

FORCE = 400.0  # N: 100 MPa on the gross section of the 4 x 1 end
THICKNESS = 1.0
AGREEMENT = 0.05
SIZE_FRACTION = 20  # our element size: W / this
GMSH_FRACTION, GMSH_HOLE_FRACTION = 25, 150  # the reference: W / these, the second along the hole


def peterson_net(d_over_w):
    """Peterson's fit of Howland's K_tn for a long strip with a central hole."""
    r = d_over_w
    return 3.0 - 3.13 * r + 3.66 * r ** 2 - 1.53 * r ** 3


class TestCalculixPlate(unittest.TestCase):

    def setUp(self):
        self.doc = FreeCAD.newDocument("MedialMeshCcxPlate")
        self.plate = self.doc.addObject("Part::Feature", "Plate")
        self.plate.Shape = shared_face("plate_with_hole")
        self.doc.recompute()
        edges = self.plate.Shape.Edges
        lines = [i for i, e in enumerate(edges) if isinstance(e.Curve, Part.Line)]
        circles = [i for i, e in enumerate(edges) if isinstance(e.Curve, Part.Circle)]
        self.assertEqual((len(lines), len(circles)), (4, 1), "plate_with_hole: a rectangle with one round hole")
        self.fixed = min(lines, key=lambda i: edges[i].CenterOfMass.x)
        self.loaded = max(lines, key=lambda i: edges[i].CenterOfMass.x)
        self.hole_name = f"Edge{circles[0] + 1}"
        self.hole = edges[circles[0]]
        box = self.plate.Shape.BoundBox
        self.width = box.YLength  # across the load
        self.diameter = 2 * self.hole.Curve.Radius
        self.workdir = tempfile.mkdtemp(prefix="medialmesh_ccx_")

    def tearDown(self):
        FreeCAD.closeDocument(self.doc.Name)

    def analysis(self, name):
        return fem_example.setup_tension_analysis(self.doc, self.plate, f"Edge{self.fixed + 1}",
                                                  f"Edge{self.loaded + 1}", FORCE, thickness=THICKNESS, name=name)

    def net_scf(self, mesh_obj, result):
        """K_tn and where sigma_xx peaks on the hole, from the result's nodal stresses."""
        femmesh = mesh_obj.FemMesh
        on_hole = set(femmesh.getNodesByEdge(self.hole))
        self.assertGreater(len(on_hole), 16)
        sxx = {n: s for n, s in zip(result.NodeNumbers, result.NodeStressXX)}
        peak = max(on_hole, key=lambda n: sxx[n])
        nominal = FORCE / ((self.width - self.diameter) * THICKNESS)
        return sxx[peak] / nominal, femmesh.getNodeById(peak)

    def check_fixed_nodes(self, mesh_obj):
        """FreeCAD's writer finds the constraint's nodes by geometry: all mesh nodes on the edge."""
        femmesh = mesh_obj.FemMesh
        x_fixed = self.plate.Shape.Edges[self.fixed].CenterOfMass.x
        on_edge = {n for n, p in femmesh.Nodes.items() if abs(p.x - x_fixed) < 1e-9}
        self.assertEqual(set(femmesh.getNodesByEdge(self.plate.Shape.Edges[self.fixed])), on_edge)
        return len(on_edge)

    def test_stress_concentration_agrees_with_a_fine_gmsh_mesh(self):
        start = time.perf_counter()
        ours_analysis = self.analysis("Ours")
        ours = MedialMesh.make_mesh_object(self.doc, self.plate, "Face1", size=self.width / SIZE_FRACTION, order=2,
                                           analysis=ours_analysis)
        self.assertEqual(ours.Status, "ok")
        self.assertIn(ours, ours_analysis.Group)
        self.assertEqual(ours.Part, self.plate)
        self.assertGreater(self.check_fixed_nodes(ours), SIZE_FRACTION)
        ours_result = fem_example.solve(ours_analysis, self.workdir)
        ours_seconds = time.perf_counter() - start
        self.assertEqual(len(ours_result.NodeNumbers), ours.NodeCount)
        k_ours, where_ours = self.net_scf(ours, ours_result)

        start = time.perf_counter()
        reference_analysis = self.analysis("Reference")
        gmsh = fem_example.add_gmsh_mesh(self.doc, reference_analysis, self.plate, self.width / GMSH_FRACTION,
                                         [self.hole_name],
                                         self.width / GMSH_HOLE_FRACTION)
        self.assertEqual(gmsh.FemMesh.QuadrangleCount, 0)
        reference_result = fem_example.solve(reference_analysis, tempfile.mkdtemp(prefix="medialmesh_ccx_gmsh_"))
        gmsh_seconds = time.perf_counter() - start
        k_gmsh, where_gmsh = self.net_scf(gmsh, reference_result)

        d_over_w = self.diameter / self.width
        sys.__stdout__.write(
            f"\nplate_with_hole d/W = {d_over_w:.3f}: K_tn ours {k_ours:.4f} ({ours.QuadCount} quad8, "
            f"{ours_seconds:.1f} s) at ({where_ours.x:.3f}, {where_ours.y:.3f}); Gmsh {k_gmsh:.4f} "
            f"({gmsh.FemMesh.TriangleCount} tria6, {gmsh_seconds:.1f} s) at ({where_gmsh.x:.3f}, {where_gmsh.y:.3f}); "
            f"{100 * (k_ours / k_gmsh - 1):+.2f} %; Peterson's long strip {peterson_net(d_over_w):.3f}\n")
        self.assertLess(abs(k_ours / k_gmsh - 1), AGREEMENT)
        # Both peak on the hole where its edge runs along the load, above or below its centre.
        centre = self.hole.Curve.Center
        for where in (where_ours, where_gmsh):
            self.assertLess(abs(where.x - centre.x), 0.1 * self.diameter)


if __name__ == "__main__":
    unittest.main()

# SPDX-License-Identifier: LGPL-2.1-or-later
"""A worked example for macros (as FreeCAD's femexamples): a planar face as a
steel shell in a FEM Analysis, one edge fixed, a force pulling on another
edge in the face's plane, meshed by MedialMesh (or, to compare, by FreeCAD's
Gmsh mesh object) and solved by CalculiX through FreeCAD's own ccxtools.

    analysis = fem_example.setup_tension_analysis(doc, plate, "Edge1", "Edge3", force=400)
    mesh = MedialMesh.make_mesh_object(doc, plate, "Face1", size=0.2, order=2, analysis=analysis)
    result = fem_example.solve(analysis, working_dir)   # a Fem::FemResultObject
"""

import os

import FreeCAD
import ObjectsFem
import Part

YOUNGS_MODULUS = "210000 MPa"
POISSON_RATIO = "0.30"


def _edge_index(subname):
    if not subname.startswith("Edge") or not subname[4:].isdigit():
        raise ValueError(f"expected an edge name such as 'Edge3', got {subname!r}")
    return int(subname[4:]) - 1


def outward_direction(face, edge):
    """The in-plane direction perpendicular to a straight edge of a planar
    face, pointing out of the face."""
    if not isinstance(edge.Curve, Part.Line):
        raise ValueError("the loaded edge must be straight")
    tangent = edge.Vertexes[-1].Point - edge.Vertexes[0].Point
    normal = face.normalAt(*face.Surface.parameter(edge.CenterOfMass))
    direction = tangent.cross(normal).normalize()
    inside = edge.CenterOfMass - direction * (1e-3 * edge.Length)
    return direction if face.isInside(inside, 1e-9 * edge.Length, True) else -direction


def setup_tension_analysis(doc, source, fixed_edge, loaded_edge, force, face="Face1", thickness=1.0,
                           name="Analysis"):
    """An Analysis with the CalculiX solver (ccxtools, static, linear), steel,
    a shell thickness, edge `fixed_edge` ('Edge1') of `source` fixed and a
    total force `force` (N) on straight edge `loaded_edge`, pulling out of
    face `face` in its plane. Returns the analysis; it still needs a mesh."""
    shape_face = source.Shape.getElement(face)
    direction = outward_direction(shape_face, source.Shape.Edges[_edge_index(loaded_edge)])
    analysis = ObjectsFem.makeAnalysis(doc, name)
    # FreeCAD 1.0 renamed it makeSolverCalculiXCcxTools (ObjectsFem.py), with no alias.
    make_solver = getattr(ObjectsFem, "makeSolverCalculiXCcxTools", None) or ObjectsFem.makeSolverCalculixCcxTools
    solver = make_solver(doc, name + "CalculiX")
    solver.AnalysisType = "static"
    solver.GeometricalNonlinearity = "linear"
    solver.WorkingDir = ""
    analysis.addObject(solver)
    analysis.addObject(ObjectsFem.makeElementGeometry2D(doc, thickness, name + "Thickness"))
    material = ObjectsFem.makeMaterialSolid(doc, name + "Steel")
    card = material.Material
    card.update({"Name": "Steel", "YoungsModulus": YOUNGS_MODULUS, "PoissonRatio": POISSON_RATIO})
    material.Material = card
    analysis.addObject(material)
    fixed = ObjectsFem.makeConstraintFixed(doc, name + "Fixed")
    fixed.References = [(source, fixed_edge)]
    analysis.addObject(fixed)
    # A force's direction is that of a linked edge: a line along it.
    line = doc.addObject("Part::Line", name + "LoadDirection")
    start = source.Shape.Edges[_edge_index(loaded_edge)].CenterOfMass
    line.X1, line.Y1, line.Z1 = start
    line.X2, line.Y2, line.Z2 = start + direction
    line.recompute()
    if FreeCAD.GuiUp:
        line.ViewObject.Visibility = False
    load = ObjectsFem.makeConstraintForce(doc, name + "Force")
    load.References = [(source, loaded_edge)]
    # A PropertyForce in FreeCAD 1.0, where a bare number would be millinewtons; a float of newtons in 0.20.
    load.Force = f"{force} N" if load.getTypeIdOfProperty("Force") == "App::PropertyForce" else force
    load.Direction = (line, ["Edge1"])
    load.Reversed = False
    analysis.addObject(load)
    return analysis


def add_gmsh_mesh(doc, analysis, source, size, refine_edges=(), refined_size=None, order=2, name="Gmsh"):
    """FreeCAD's own Gmsh mesh object of `source`'s faces in `analysis`, of
    `size`, finer (`refined_size`) along `refine_edges`, meshed now.
    Raises RuntimeError when Gmsh fails."""
    from femmesh.gmshtools import GmshTools

    mesh = ObjectsFem.makeMeshGmsh(doc, name)
    if "Shape" in mesh.PropertiesList:  # FreeCAD 1.0 links the geometry as Shape, 0.20 as Part
        mesh.Shape = source
    else:
        mesh.Part = source
    mesh.ElementDimension = "2D"
    mesh.ElementOrder = "2nd" if order == 2 else "1st"
    mesh.SecondOrderLinear = False  # mid-side nodes on the curves
    mesh.CharacteristicLengthMax = size
    analysis.addObject(mesh)
    if refine_edges:
        region = ObjectsFem.makeMeshRegion(doc, mesh, refined_size, name + "Region")
        region.References = [(source, edge) for edge in refine_edges]
    error = GmshTools(mesh).create_mesh()
    if error:
        raise RuntimeError(f"Gmsh failed: {error}")
    return mesh


def solve(analysis, working_dir):
    """Write the CalculiX input of `analysis` into `working_dir`, run ccx and
    load the results; return the result object. Raises RuntimeError naming
    what failed."""
    from femtools import ccxtools

    solver = next(o for o in analysis.Group if o.isDerivedFrom("Fem::FemSolverObjectPython"))
    fea = ccxtools.FemToolsCcx(analysis, solver)
    fea.update_objects()
    os.makedirs(working_dir, exist_ok=True)  # ccxtools would fall back to a temporary folder
    fea.setup_working_dir(working_dir)
    problems = fea.check_prerequisites()
    if problems:
        raise RuntimeError(f"{analysis.Label}: CalculiX cannot start: {problems}")
    fea.write_inp_file()
    if not fea.inp_file_name:
        raise RuntimeError(f"{analysis.Label}: writing the CalculiX input failed")
    status = fea.ccx_run()
    if status is None:
        raise RuntimeError(f"{analysis.Label}: CalculiX (ccx) was not found or did not start")
    if status != 0:
        raise RuntimeError(f"{analysis.Label}: CalculiX failed (exit {status}): {fea.ccx_stdout[-2000:]}")
    fea.load_results()
    results = [o for o in analysis.Group if o.isDerivedFrom("Fem::FemResultObject")]
    if not fea.results_present or not results:
        raise RuntimeError(f"{analysis.Label}: no CalculiX results to read")
    return results[-1]

#!/usr/bin/python3
"""End-to-end FEM check of our quad meshes: a plate with a hole in uniaxial tension.

The face of plate_with_hole.brep (a full square plate with a central circular
hole) is meshed by medialmesh at three sizes and by Gmsh finely; each mesh is
solved by CalculiX as a plane-stress plate (steel, thickness 1) pulled by a
uniform traction on its two ends x = xmin and x = xmax. Only three displacement
components are fixed (both lower corners in y, the lower-left one in x): the
loads balance, so these supports carry no force and the stresses are those of
pure uniaxial tension.

The stress concentration factor is taken on the net section:
    K_tn = max sigma_xx on the hole's edge / (S * W / (W - d)),
S the applied traction, W the plate's width across the load, d the hole's
diameter. sigma_xx comes from CalculiX's nodal stresses (.frd, extrapolated
from the integration points and averaged between elements).

Checks: our K_tn converges (each refinement changes it less than the one
before) and our finest mesh agrees with the Gmsh reference within 3 %.
Peterson's value for d/W is printed for information only: the plate is as
long as it is wide, so it is not the long strip of Peterson's charts.

Run with /usr/bin/python3 (Debian's numpy, gmsh, matplotlib):
    plate_with_hole_fem.py BUILD_DIR SHARED_DIR [--out DIR]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

E_MODULUS = 210000.0  # MPa, steel
POISSON = 0.3
THICKNESS = 1.0
TRACTION = 100.0  # MPa on the plate's ends (gross section)
SIZE_FRACTIONS = (10, 20, 40)  # our mesh sizes are W / these
ORDER = 2  # CPS8: quadratic quads
GMSH_SIZE_AT_HOLE = 1.0 / 100.0  # Gmsh reference sizes, as fractions of W: K_tn within 0.1 %
GMSH_SIZE_FAR = 1.0 / 30.0  # of its value on a mesh 4 times finer
AGREEMENT = 0.03
CCX_FIELD_WIDTH = 20  # CalculiX misreads longer numbers (a node moves, "nonpositive jacobian")

# Corner nodes first, then midside nodes, as Abaqus and Gmsh both number them.
CORNER_COUNT = {"CPS3": 3, "CPS6": 3, "CPS4": 4, "CPS8": 4}


class CheckFailed(Exception):
    pass


def run(cmd, cwd=None, env=None):
    result = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if result.returncode != 0:
        raise CheckFailed("command failed (exit %d): %s\n%s%s" %
                          (result.returncode, " ".join(cmd), result.stdout[-2000:], result.stderr[-2000:]))
    return result.stdout


class Mesh:
    """Nodes (id -> x, y) and elements of one type, as numpy arrays of node ids."""

    def __init__(self, node_ids, xyz, element_type, elements, boundary_set=None, element_ids=None):
        if np.abs(xyz[:, 2]).max() > 1e-9 * max(1.0, np.abs(xyz).max()):
            raise CheckFailed("mesh is not in the XY plane (max |z| = %g)" % np.abs(xyz[:, 2]).max())
        self.node_ids = np.asarray(node_ids, dtype=int)
        self.xy = np.asarray(xyz[:, :2], dtype=float)
        self.index = {nid: i for i, nid in enumerate(self.node_ids)}
        self.element_type = element_type
        self.elements = np.asarray(elements, dtype=int)
        self.element_ids = np.arange(1, len(elements) + 1) if element_ids is None else np.asarray(element_ids)
        self.boundary_set = boundary_set
        self.flipped = self._orient_counterclockwise()

    def coords(self, nid):
        return self.xy[self.index[nid]]

    def corners(self, element):
        return element[:CORNER_COUNT[self.element_type]]

    def signed_area(self, element):
        p = np.array([self.coords(n) for n in self.corners(element)])
        return 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])

    def _orient_counterclockwise(self):
        # CalculiX needs counterclockwise plane elements (seen from +z).
        reversed_order = {"CPS3": [0, 2, 1], "CPS6": [0, 2, 1, 5, 4, 3], "CPS4": [0, 3, 2, 1],
                          "CPS8": [0, 3, 2, 1, 7, 6, 5, 4]}[self.element_type]
        flipped = 0
        for k, element in enumerate(self.elements):
            area = self.signed_area(element)
            if area == 0.0:
                raise CheckFailed("element %d has zero area" % k)
            if area < 0.0:
                self.elements[k] = element[reversed_order]
                flipped += 1
        return flipped

    def edges(self, element):
        """(face number, corner a, corner b) of each side, as CalculiX numbers faces P1, P2, ..."""
        c = self.corners(element)
        return [(i + 1, c[i], c[(i + 1) % len(c)]) for i in range(len(c))]

    def boundary_nodes(self):
        """Nodes on sides used by exactly one element (corner and midside nodes)."""
        count = {}
        for element in self.elements:
            for _, a, b in self.edges(element):
                key = (min(a, b), max(a, b))
                count[key] = count.get(key, 0) + 1
        nodes = set()
        n_corners = CORNER_COUNT[self.element_type]
        for element in self.elements:
            for face, a, b in self.edges(element):
                if count[(min(a, b), max(a, b))] == 1:
                    nodes.update((a, b))
                    if len(element) > n_corners:
                        nodes.add(element[n_corners + face - 1])
        return nodes


def read_inp(path):
    """Reads the *NODE, *ELEMENT and *NSET cards of our writer's .inp."""
    node_ids, xyz, element_ids, elements, nsets = [], [], [], [], {}
    element_type, card, nset = None, None, None
    with open(path) as f:
        for raw in f:
            line = raw.strip()
            if not line or line.startswith("**"):
                continue
            if line.startswith("*"):
                words = [w.strip() for w in line.split(",")]
                card = words[0].upper()
                options = dict((w.split("=", 1)[0].upper(), w.split("=", 1)[1]) if "=" in w else (w.upper(), "")
                               for w in words[1:])
                if card == "*ELEMENT":
                    if element_type is not None and options.get("TYPE", "").upper() != element_type:
                        raise CheckFailed("%s: more than one element type" % path)
                    element_type = options.get("TYPE", "").upper()
                    if element_type not in CORNER_COUNT:
                        raise CheckFailed("%s: unexpected element type %r" % (path, element_type))
                elif card == "*NSET":
                    nset = options.get("NSET", "").upper()
                    nsets.setdefault(nset, [])
                continue
            fields = [w for w in line.replace(",", " ").split()]
            too_long = [w for w in fields if len(w) > CCX_FIELD_WIDTH]
            if too_long:
                raise CheckFailed("%s: field %r is longer than the %d characters CalculiX reads" %
                                  (path, too_long[0], CCX_FIELD_WIDTH))
            if card == "*NODE":
                node_ids.append(int(fields[0]))
                xyz.append([float(v) for v in (fields[1:4] + ["0"])[:3]])
            elif card == "*ELEMENT":
                element_ids.append(int(fields[0]))
                elements.append([int(v) for v in fields[1:]])
            elif card == "*NSET":
                nsets[nset].extend(int(v) for v in fields)
    if not node_ids or not elements:
        raise CheckFailed("%s: no *NODE or *ELEMENT data" % path)
    return Mesh(node_ids, np.array(xyz), element_type, elements, nsets.get("NBOUNDARY"), element_ids)


def gmsh_reference(brep, width, hole_radius, workdir):
    """A fine Gmsh mesh of the same face: 6-node triangles, finest on the hole."""
    import gmsh
    gmsh.initialize(["gmsh", "-nt", "1"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.model.add("plate")
        gmsh.model.occ.importShapes(brep)
        gmsh.model.occ.synchronize()
        faces = gmsh.model.getEntities(2)
        if len(faces) != 1:
            raise CheckFailed("%s: Gmsh reads %d faces, expected 1" % (brep, len(faces)))
        hole_curves = [tag for dim, tag in gmsh.model.getEntities(1)
                       if abs(gmsh.model.occ.getMass(1, tag) - 2 * math.pi * hole_radius) < 1e-6 * width]
        distance = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(distance, "CurvesList", hole_curves)
        gmsh.model.mesh.field.setNumber(distance, "NumPointsPerCurve", 400)
        threshold = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(threshold, "InField", distance)
        gmsh.model.mesh.field.setNumber(threshold, "SizeMin", GMSH_SIZE_AT_HOLE * width)
        gmsh.model.mesh.field.setNumber(threshold, "SizeMax", GMSH_SIZE_FAR * width)
        gmsh.model.mesh.field.setNumber(threshold, "DistMin", 0.05 * width)
        gmsh.model.mesh.field.setNumber(threshold, "DistMax", 0.4 * width)
        gmsh.model.mesh.field.setAsBackgroundMesh(threshold)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)  # midside nodes on the exact circle
        gmsh.model.mesh.generate(2)
        node_tags, coords, _ = gmsh.model.mesh.getNodes()
        triangle6 = 9  # Gmsh's type number of the 6-node triangle
        types = gmsh.model.mesh.getElementTypes(2)
        if list(types) != [triangle6]:
            raise CheckFailed("Gmsh made element types %s, expected only 6-node triangles" % list(types))
        _, element_nodes = gmsh.model.mesh.getElementsByType(triangle6)
        gmsh.write(os.path.join(workdir, "gmsh_reference.msh"))
    finally:
        gmsh.finalize()
    return Mesh(node_tags, np.asarray(coords).reshape(-1, 3), "CPS6", np.asarray(element_nodes).reshape(-1, 6))


def write_deck(mesh, path, x_ends, lower_corners, mesh_file=None):
    """A CalculiX deck: plane stress, traction TRACTION pulling both ends, 3 supports.

    With mesh_file the deck includes that .inp as it is (nodes, elements EALL),
    as a user would; else it writes the mesh's nodes and elements itself."""
    tol = 1e-7 * (x_ends[1] - x_ends[0])
    loads = []
    for k, element in enumerate(mesh.elements):
        for face, a, b in mesh.edges(element):
            xa, xb = mesh.coords(a)[0], mesh.coords(b)[0]
            for x_end in x_ends:
                if abs(xa - x_end) < tol and abs(xb - x_end) < tol:
                    loads.append((mesh.element_ids[k], face))
    if not loads:
        raise CheckFailed("no element side lies on the plate's ends x = %g, %g" % x_ends)
    supports = []
    for corner in lower_corners:
        distances = np.linalg.norm(mesh.xy - corner, axis=1)
        nearest = int(np.argmin(distances))
        if distances[nearest] > tol:
            raise CheckFailed("no node at the corner (%g, %g)" % tuple(corner))
        supports.append(int(mesh.node_ids[nearest]))
    with open(path, "w") as f:
        if mesh_file:
            f.write("*INCLUDE, INPUT=%s\n" % mesh_file)  # its *NODE is NSET=NALL
        else:
            f.write("*HEADING\nplate with a hole in uniaxial tension\n*NODE, NSET=NALL\n")
            for nid, (x, y) in zip(mesh.node_ids, mesh.xy):
                f.write("%d, %.12g, %.12g, 0\n" % (nid, x, y))  # 12 digits fit CCX_FIELD_WIDTH
            f.write("*ELEMENT, TYPE=%s, ELSET=EALL\n" % mesh.element_type)
            for element_id, element in zip(mesh.element_ids, mesh.elements):
                f.write("%d, %s\n" % (element_id, ", ".join(str(n) for n in element)))
        f.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n%g, %g\n" % (E_MODULUS, POISSON))
        f.write("*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n%g\n" % THICKNESS)
        f.write("*BOUNDARY\n%d, 1, 2\n%d, 2, 2\n" % (supports[0], supports[1]))
        f.write("*STEP\n*STATIC\n*DLOAD\n")
        for element, face in loads:
            f.write("%d, P%d, %g\n" % (element, face, -TRACTION))  # negative pressure pulls
        f.write("*NODE FILE\nU\n*EL FILE\nS\n*NODE PRINT, NSET=NALL, TOTALS=ONLY\nRF\n*END STEP\n")


def read_frd_stresses(path):
    """Nodal stresses (id -> sxx, syy, szz, sxy, syz, szx) from a CalculiX .frd."""
    stresses, in_block = {}, False
    with open(path) as f:
        for line in f:
            if line.startswith(" -4"):
                in_block = line.split()[1] == "STRESS"
            elif in_block and line.startswith(" -1"):
                nid = int(line[3:13])
                stresses[nid] = [float(line[13 + 12 * i:25 + 12 * i]) for i in range(6)]
            elif line.startswith(" -3"):
                in_block = False
    if not stresses:
        raise CheckFailed("%s: no STRESS block" % path)
    return stresses


def check_supports_idle(path, mesh):
    """The loads balance, so the three supports must carry (next to) no force."""
    with open(path) as f:
        lines = f.read().splitlines()
    totals = [k for k, line in enumerate(lines) if "total force" in line]
    if not totals:
        raise CheckFailed("%s: no total reaction force" % path)
    reaction = [float(v) for v in lines[totals[-1] + 2].split()]
    height = mesh.xy[:, 1].max() - mesh.xy[:, 1].min()
    end_load = TRACTION * height * THICKNESS
    if max(abs(v) for v in reaction) > 1e-6 * end_load:
        raise CheckFailed("supports carry a force %s against end loads of %g: the loads do not balance" %
                          (reaction, end_load))


def solve(mesh, name, workdir, x_ends, lower_corners, mesh_file=None):
    write_deck(mesh, os.path.join(workdir, name + ".inp"), x_ends, lower_corners, mesh_file)
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_STIFFNESS="1", CCX_NPROC_EQUATION_SOLVER="1")
    out = run(["ccx", "-i", name], cwd=workdir, env=env)
    if "*ERROR" in out:
        raise CheckFailed("CalculiX reports an error for %s:\n%s" % (name, out[-2000:]))
    check_supports_idle(os.path.join(workdir, name + ".dat"), mesh)
    stress = read_frd_stresses(os.path.join(workdir, name + ".frd"))
    return np.array([stress[nid][0] for nid in mesh.node_ids])  # sigma_xx


def net_scf(mesh, sigma_xx, outer_box, hole_radius, width):
    """K_tn from the largest sigma_xx on the hole's edge; also the node where it is."""
    xmin, xmax, ymin, ymax = outer_box
    tol = 1e-7 * width
    on_hole = [mesh.index[n] for n in mesh.boundary_nodes()
               if not (abs(mesh.coords(n)[0] - xmin) < tol or abs(mesh.coords(n)[0] - xmax) < tol or
                       abs(mesh.coords(n)[1] - ymin) < tol or abs(mesh.coords(n)[1] - ymax) < tol)]
    if not on_hole:
        raise CheckFailed("no boundary node on the hole")
    centre = np.array([(xmin + xmax) / 2, (ymin + ymax) / 2])
    radii = np.linalg.norm(mesh.xy[on_hole] - centre, axis=1)
    if np.abs(radii - hole_radius).max() > 1e-5 * width:
        raise CheckFailed("hole nodes are off the circle by up to %g" % np.abs(radii - hole_radius).max())
    peak = on_hole[int(np.argmax(sigma_xx[on_hole]))]
    nominal_net = TRACTION * width / (width - 2 * hole_radius)
    return sigma_xx[peak] / nominal_net, mesh.xy[peak]


def draw_stress(mesh, sigma_xx, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    n_corners = CORNER_COUNT[mesh.element_type]
    polygons, values = [], []
    for element in mesh.elements:
        # corner, midside, corner, ... so quadratic sides follow the curve
        ring = []
        for i in range(n_corners):
            ring.append(element[i])
            if len(element) > n_corners:
                ring.append(element[n_corners + i])
        idx = [mesh.index[n] for n in ring]
        polygons.append(mesh.xy[idx])
        values.append(sigma_xx[idx].mean())
    fig, ax = plt.subplots(figsize=(7, 6))
    coll = PolyCollection(polygons, array=np.array(values), cmap="jet", edgecolors="k", linewidths=0.2)
    ax.add_collection(coll)
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.set_title(title)
    fig.colorbar(coll, ax=ax, label="sigma_xx (MPa), element mean of nodal values")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def peterson_net(d_over_w):
    """Peterson's fit (Roark) of Howland's K_tn for a long strip with a central hole, and Heywood's."""
    r = d_over_w
    return 3.0 - 3.13 * r + 3.66 * r ** 2 - 1.53 * r ** 3, 2.0 + (1.0 - r) ** 3


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build_dir")
    parser.add_argument("shared_dir")
    parser.add_argument("--out", help="folder for the stress picture and the markdown table")
    args = parser.parse_args()
    cli = os.path.join(args.build_dir, "bin", "medialmesh")
    brep = os.path.join(args.shared_dir, "geometry", "plate_with_hole.brep")

    info = json.loads(run([cli, "info", brep, "--json"]))["faces"]
    if len(info) != 1 or info[0]["holes"] != 1:
        raise CheckFailed("%s: expected one face with one hole" % brep)
    face = info[0]
    corners = np.array([[c["x"], c["y"]] for c in face["corners"]])
    circles = [e for e in face["edges"] if e["type"] == "circle"]
    if len(corners) != 4 or len(circles) != 1:
        raise CheckFailed("%s: expected a rectangle with one circular hole" % brep)
    xmin, ymin = corners.min(axis=0)
    xmax, ymax = corners.max(axis=0)
    width, length = ymax - ymin, xmax - xmin  # the load pulls along x
    hole_radius = circles[0]["length"] / (2 * math.pi)
    area = length * width - math.pi * hole_radius ** 2
    if abs(area - face["area"]) > 1e-6 * area:
        raise CheckFailed("face area %g is not that of a %g x %g rectangle less a hole of radius %g" %
                          (face["area"], length, width, hole_radius))
    outer_box = (xmin, xmax, ymin, ymax)
    x_ends = (xmin, xmax)
    lower_corners = [np.array([xmin, ymin]), np.array([xmax, ymin])]
    d_over_w = 2 * hole_radius / width

    rows = []
    with tempfile.TemporaryDirectory(prefix="fem_plate_") as workdir:
        finest = None
        for fraction in SIZE_FRACTIONS:
            size = width / fraction
            inp = os.path.join(workdir, "ours_%d_mesh.inp" % fraction)
            run([cli, "mesh", brep, "--size", repr(size), "--order", str(ORDER), "-o", inp, "--json"])
            mesh = read_inp(inp)
            expected = "CPS8" if ORDER == 2 else "CPS4"
            if mesh.element_type != expected:
                raise CheckFailed("%s: element type %s, expected %s" % (inp, mesh.element_type, expected))
            if mesh.boundary_set is None or set(mesh.boundary_set) != mesh.boundary_nodes():
                raise CheckFailed("%s: NSET NBOUNDARY is not the mesh's boundary nodes" % inp)
            if mesh.flipped:
                raise CheckFailed("%s: %d elements run clockwise seen from +z; CalculiX rejects them" %
                                  (inp, mesh.flipped))
            sigma_xx = solve(mesh, "ours_%d" % fraction, workdir, x_ends, lower_corners, os.path.basename(inp))
            scf, where = net_scf(mesh, sigma_xx, outer_box, hole_radius, width)
            rows.append(("medialmesh H = W/%d" % fraction, mesh, scf, where))
            finest = (mesh, sigma_xx, fraction)
        reference = gmsh_reference(brep, width, hole_radius, workdir)
        sigma_ref = solve(reference, "gmsh_reference", workdir, x_ends, lower_corners)
        scf_ref, where_ref = net_scf(reference, sigma_ref, outer_box, hole_radius, width)
        rows.append(("Gmsh reference (CPS6, W/%d at the hole)" % round(1 / GMSH_SIZE_AT_HOLE), reference, scf_ref,
                     where_ref))

        peterson, heywood = peterson_net(d_over_w)
        lines = ["| mesh | elements | nodes | K_tn | K_tg | at (x, y) | vs Gmsh |", "|---|---|---|---|---|---|---|"]
        for name, mesh, scf, where in rows:
            lines.append("| %s | %d %s | %d | %.4f | %.4f | (%.3f, %.3f) | %+.2f%% |" %
                         (name, len(mesh.elements), mesh.element_type, len(mesh.node_ids), scf,
                          scf * width / (width - 2 * hole_radius), where[0], where[1], 100 * (scf / scf_ref - 1)))
        notes = [
            "",
            "Plate %g x %g (W = %g across the load), hole d = %g, d/W = %.3f; traction %g MPa on both ends, "
            "plane stress, E = %g MPa, nu = %g, t = %g." % (length, width, width, 2 * hole_radius, d_over_w, TRACTION,
                                                             E_MODULUS, POISSON, THICKNESS),
            "K_tn = max sigma_xx on the hole / (S W / (W - d)) (net section); K_tg = max sigma_xx / S (gross).",
            "Long-strip values for d/W = %.3f (information only, this plate is as long as it is wide): "
            "Peterson/Howland K_tn = %.4f, Heywood K_tn = 2 + (1 - d/W)^3 = %.4f." % (d_over_w, peterson, heywood),
        ]
        table = "\n".join(lines + notes)
        print(table)

        if args.out:
            os.makedirs(args.out, exist_ok=True)
            mesh, sigma_xx, fraction = finest
            picture = os.path.join(args.out, "plate_with_hole_sxx.png")
            draw_stress(mesh, sigma_xx, picture,
                        "medialmesh CPS8, H = W/%d, %g MPa pulling along x" % (fraction, TRACTION))
            with open(os.path.join(args.out, "plate_with_hole_fem.md"), "w") as f:
                f.write(table + "\n")
            print("picture: %s" % picture)

    ours = [scf for _, _, scf, _ in rows[:-1]]
    changes = [abs(b - a) for a, b in zip(ours, ours[1:])]
    if not all(later < earlier for earlier, later in zip(changes, changes[1:])):
        raise CheckFailed("K_tn does not converge under refinement: changes %s" %
                          ", ".join("%.4f" % c for c in changes))
    if abs(ours[-1] / scf_ref - 1) > AGREEMENT:
        raise CheckFailed("finest K_tn %.4f differs from Gmsh's %.4f by %.2f%% (more than %g%%)" %
                          (ours[-1], scf_ref, 100 * abs(ours[-1] / scf_ref - 1), 100 * AGREEMENT))
    print("fem_plate_with_hole: K_tn converges (changes %s) and the finest is within %g%% of Gmsh" %
          (", ".join("%.4f" % c for c in changes), 100 * AGREEMENT))


if __name__ == "__main__":
    try:
        main()
    except CheckFailed as failure:
        print("fem_plate_with_hole FAILED: %s" % failure, file=sys.stderr)
        sys.exit(1)

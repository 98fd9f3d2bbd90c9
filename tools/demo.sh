#!/usr/bin/env bash
# The main job on the bundled example face: installs what is missing, builds,
# and writes the face report (text and JSON), the medial axis (JSON), the mesh
# flow with its singularities (text and JSON), the block decomposition (JSON,
# picture and the block faces as BREP), the all-quad mesh (.inp, .msh, .vtu,
# its quality report as text and JSON, and its picture), and a FreeCAD
# document with the face analysed and decomposed plus a picture of its 3D
# view, and a FEM Analysis of a second face (quad mesh object, its Sketch,
# CalculiX result through FreeCAD's ccxtools) with pictures of the mesh and
# of the stress into out/.
#   tools/demo.sh [FACE_FILE [FEM_FACE_FILE]]
#   (defaults: Resources/examples/bracket.brep, Resources/examples/plate_with_hole.brep)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
input="${1:-$root/Resources/examples/bracket.brep}"
fem_input="${2:-$root/Resources/examples/plate_with_hole.brep}"
name="$(basename "${input%.*}")"
out="$root/out"

"$root/tools/build.sh"
mkdir -p "$out"
cli="$root/build/bin/medialmesh"
"$cli" info "$input" | tee "$out/$name.txt"
"$cli" info "$input" --json >"$out/$name.json"
"$cli" svg "$input" -o "$out/$name.svg"
rsvg-convert -o "$out/$name.png" "$out/$name.svg"
"$cli" medial "$input" --json --svg "$out/$name.medial.svg" >"$out/$name.medial.json"
rsvg-convert -o "$out/$name.medial.png" "$out/$name.medial.svg"
"$cli" singularities "$input" --svg "$out/$name.singularities.svg" | tee "$out/$name.singularities.txt"
"$cli" singularities "$input" --json >"$out/$name.singularities.json"
rsvg-convert -o "$out/$name.singularities.png" "$out/$name.singularities.svg"
"$cli" decompose "$input" --json --svg "$out/$name.decomposition.svg" --blocks "$out/$name.blocks.brep" \
  >"$out/$name.decomposition.json"
rsvg-convert -o "$out/$name.decomposition.png" "$out/$name.decomposition.svg"
python3 - "$out/$name.decomposition.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
kinds = [b["kind"] for b in d["blocks"]]
print(f"decomposition: {len(d['blocks'])} blocks ({kinds.count('polygon')} polygons, "
      f"{kinds.count('submap')} submappable), {len(d['splits'])} splits, {len(d['fixed'])} fixed singularities")
PY
# The all-quad mesh in the three file formats, its quality report and picture.
"$cli" mesh "$input" -o "$out/$name.mesh.inp" --svg "$out/$name.mesh.svg" | tee "$out/$name.mesh.txt"
"$cli" mesh "$input" -o "$out/$name.mesh.msh" --json >"$out/$name.mesh.json"
"$cli" mesh "$input" -o "$out/$name.mesh.vtu" >/dev/null
rsvg-convert -o "$out/$name.mesh.png" "$out/$name.mesh.svg"
# The same face analysed in FreeCAD, as a user would: a document and a picture.
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
HOME="$home" XDG_RUNTIME_DIR="$home" QTWEBENGINE_DISABLE_SANDBOX=1 \
  MEDIALMESH_DEMO_INPUT="$input" MEDIALMESH_DEMO_FEM_INPUT="$fem_input" MEDIALMESH_DEMO_OUT="$out/$name.freecad" \
  xvfb-run -a -s "-screen 0 1280x1024x24" freecad "$root/tools/freecad_demo.py" --module-path "$root" \
  </dev/null 2>&1 | tee "$home/log" | grep -E "^freecad-demo|Error|Traceback" || true
grep -q "^freecad-demo" "$home/log" || { echo "demo: the FreeCAD part failed" >&2; exit 1; }
echo "demo: wrote into $out: $name.txt, $name.json, $name.svg/.png (face and corners)," \
  "$name.medial.json, $name.medial.svg/.png (medial axis)," \
  "$name.singularities.txt/.json/.svg/.png (flow types and singularities)," \
  "$name.decomposition.json/.svg/.png and $name.blocks.brep (the blocks)," \
  "$name.mesh.inp/.msh/.vtu, $name.mesh.txt/.json (quality) and $name.mesh.svg/.png (the quad mesh)," \
  "$name.freecad.FCStd/.png (the analysis and decomposition in FreeCAD; the FEM Analysis of" \
  "$(basename "${fem_input%.*}") with its quad mesh and CalculiX result)," \
  "$name.freecad.quadmesh.png (the bracket meshed by the Quad mesh command)," \
  "$name.freecad.mesh.png/.stress.png (that mesh and its von Mises stress), $name.freecad.ccx/ (CalculiX files)"

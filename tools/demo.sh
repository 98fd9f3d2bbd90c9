#!/usr/bin/env bash
# The main job on the bundled example face: installs what is missing, builds,
# and writes the face report (text and JSON), the medial axis (JSON), the mesh
# flow with its singularities (text and JSON) and their pictures into out/.
#   tools/demo.sh [FACE_FILE]   (default: Resources/examples/bracket.brep)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
input="${1:-$root/Resources/examples/bracket.brep}"
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
echo "demo: wrote into $out: $name.txt, $name.json, $name.svg/.png (face and corners)," \
  "$name.medial.json, $name.medial.svg/.png (medial axis)," \
  "$name.singularities.txt/.json/.svg/.png (flow types and singularities)"

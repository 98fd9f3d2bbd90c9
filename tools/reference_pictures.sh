#!/usr/bin/env bash
# Pictures of every reference face (../shared/geometry): its mesh flow with
# the merged singularities beside its block decomposition and its quad mesh
# at the defaults, for the README's gallery. Needs a build (tools/build.sh).
#   tools/reference_pictures.sh [SHARED_DIR [OUT_DIR]]
#   (defaults: ../shared beside the repository, Resources/pictures/reference)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
shared="${1:-$root/../shared}"
out="${2:-$root/Resources/pictures/reference}"
cli="$root/build/bin/medialmesh"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
for face in "$shared"/geometry/*.brep; do
  name="$(basename "${face%.brep}")"
  "$cli" singularities "$face" --merge --svg "$work/$name.flow.svg" >/dev/null
  "$cli" decompose "$face" --svg "$work/$name.blocks.svg"
  "$cli" mesh "$face" -o "$work/$name.vtu" --svg "$work/$name.mesh.svg" >/dev/null
  for kind in flow blocks mesh; do
    rsvg-convert -w 300 -o "$out/${name}_$kind.png" "$work/$name.$kind.svg"
  done
done
echo "pictures of $(ls "$shared"/geometry/*.brep | wc -l) faces in $out"

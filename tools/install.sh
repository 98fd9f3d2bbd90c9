#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Build MedialMesh and make its workbench appear in FreeCAD for the current
# user: the repository root is linked into FreeCAD's user Mod folder as
# MedialMesh. Safe to run again.
#
#   tools/install.sh [--replace]
#
# When the link is there already and points to another clone, it is left
# alone unless the user says so: asked at a terminal, or --replace.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
replace=0
case "${1:-}" in
    --replace) replace=1 ;;
    "") ;;
    *) echo "usage: tools/install.sh [--replace]" >&2; exit 2 ;;
esac

echo "== building: tools/build.sh"
"$root/tools/build.sh"

# Ask FreeCAD where the user Mod folder is (0.20 on Linux: ~/.local/share/FreeCAD/Mod).
mod_dir="$(freecadcmd -c \
    'import FreeCAD; print("user-mod-dir=" + FreeCAD.getUserAppDataDir() + "Mod")' \
    </dev/null 2>/dev/null | sed -n 's/^user-mod-dir=//p' || true)"
if [[ -z $mod_dir ]]; then
    echo "install.sh: freecadcmd did not tell its user Mod folder; is FreeCAD installed?" >&2
    exit 1
fi
link="$mod_dir/MedialMesh"
mkdir -p "$mod_dir"
if [[ -L $link && $(readlink "$link") == "$root" ]]; then
    echo "== $link already links to $root"
elif [[ -e $link && ! -L $link ]]; then
    echo "install.sh: $link exists and is not a link (installed by the Addon Manager?);" \
        "remove it, then run this again" >&2
    exit 1
else
    if [[ -L $link ]]; then
        echo "install.sh: $link links to another MedialMesh: $(readlink "$link")"
        if [[ $replace == 0 && -t 0 ]]; then
            read -r -p "Make it link to $root instead? [y/N] " answer
            [[ $answer == [yY]* ]] && replace=1
        fi
        if [[ $replace == 0 ]]; then
            echo "install.sh: left as it is; to replace it, run: tools/install.sh --replace" >&2
            exit 1
        fi
        echo "== replacing $link -> $(readlink "$link")"
    fi
    ln -sfn "$root" "$link"
    echo "== linked $link -> $root"
fi

# The same start-up as the GUI's: Init.py of the linked addon puts MedialMesh on sys.path.
loaded="$(freecadcmd -c \
    'import MedialMesh; print("medialmesh-module=" + MedialMesh.module_path())' \
    </dev/null 2>&1 | sed -n 's/^medialmesh-module=//p' || true)"
if [[ -z $loaded ]]; then
    echo "install.sh: FreeCAD cannot import MedialMesh; try: freecadcmd -c 'import MedialMesh'" >&2
    exit 1
fi
echo "== FreeCAD loads the compiled core from $loaded"
echo "== done: start FreeCAD and pick the MedialMesh workbench"

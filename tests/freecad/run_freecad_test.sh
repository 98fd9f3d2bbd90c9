#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Run a unittest module inside FreeCAD and fail unless all of its tests pass.
#
#   run_freecad_test.sh [--gui] SCRIPT [BUILD_DIR [SHARED_DIR]]
#
# SCRIPT      a unittest module, e.g. tests/freecad/test_boundary_module.py
# BUILD_DIR   the build folder whose lib/ holds _medialmesh (default <repo>/build)
# SHARED_DIR  the folder holding geometry/*.brep (default $MEDIALMESH_SHARED or <repo>/../shared)
# --gui       run the FreeCAD GUI under xvfb-run instead of freecadcmd
# A run that takes longer than $MEDIALMESH_TEST_TIMEOUT seconds (default 600)
# prints the Python traceback of where it hangs and fails.
#
# freecadcmd exits 0 even when a script raises, so success is read from the
# summary line that freecad_runner.py prints.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"

gui=0
if [[ "${1:-}" == "--gui" ]]; then
    gui=1
    shift
fi
if [[ $# -lt 1 || $# -gt 3 ]]; then
    echo "usage: $0 [--gui] SCRIPT [BUILD_DIR [SHARED_DIR]]" >&2
    exit 2
fi
script="$(realpath -m "$1")"
build_dir="$(realpath -m "${2:-$repo/build}")"
shared_dir="$(realpath -m "${3:-${MEDIALMESH_SHARED:-$repo/../shared}}")"

# A fresh HOME: FreeCAD writes its config there, and no addon or setting of
# the user's can change what is tested. The addon under test is this repo.
home="$(mktemp -d)"
trap 'rm -rf "$home"' EXIT
export HOME="$home" XDG_RUNTIME_DIR="$home"
unset XDG_CONFIG_HOME XDG_DATA_HOME XDG_CACHE_HOME
export MEDIALMESH_TEST_SCRIPT="$script" MEDIALMESH_BUILD_DIR="$build_dir"
export MEDIALMESH_SHARED="$shared_dir"
export MEDIALMESH_TEST_TIMEOUT="${MEDIALMESH_TEST_TIMEOUT:-600}"

# FreeCAD 0.20.2 (Debian) only accepts its own options after the first file;
# before it, they go to Python's option parser and FreeCAD crashes.
if [[ $gui == 1 ]]; then
    # Qt WebEngine refuses to start as root unless its sandbox is off
    export QTWEBENGINE_DISABLE_SANDBOX=1
    command=(xvfb-run -a -s "-screen 0 1280x1024x24" freecad)
else
    command=(freecadcmd)
fi
log="$home/freecad.log"
status=0
timeout $((MEDIALMESH_TEST_TIMEOUT + 30)) \
    "${command[@]}" "$here/freecad_runner.py" --module-path "$repo" </dev/null 2>&1 \
    | tee "$log" || status=$?

summary="$(grep -E '^freecad-tests: [0-9]+ passed, [0-9]+ failed' "$log" | tail -n 1 || true)"
if [[ $status -ne 0 || ! $summary =~ ^freecad-tests:\ [1-9][0-9]*\ passed,\ 0\ failed ]]; then
    echo "FAILED: $(basename "$script") (exit status $status, summary: ${summary:-none})" >&2
    exit 1
fi

# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run one unittest module inside FreeCAD and exit with its result.

run_freecad_test.sh starts freecadcmd (or freecad) on this file. FreeCAD
imports a script given on its command line as a module and, if that raises,
runs it a second time and then exits with 0, so this file catches everything,
prints "freecad-tests: N passed, M failed, K skipped" and calls sys.exit().

Environment, set by run_freecad_test.sh:
  MEDIALMESH_TEST_SCRIPT  the test module to run (a .py file)
  MEDIALMESH_BUILD_DIR    the build folder; its lib/ holds _medialmesh
  MEDIALMESH_SHARED       the shared folder with geometry/*.brep (read by the tests)
  MEDIALMESH_TEST_TIMEOUT seconds after which a hung run prints where it hangs and exits
"""

import faulthandler
import os
import sys
import traceback
import unittest


REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run_tests(script, build_dir, out):
    # in front of anything Init.py added, so the tests see this build
    sys.path[0:0] = [
        os.path.dirname(os.path.abspath(script)),
        os.path.join(build_dir, "lib"),
        os.path.join(REPO, "Mod"),
    ]
    module_name = os.path.splitext(os.path.basename(script))[0]
    # an import error of the module becomes a failed test, not a lost exception
    suite = unittest.defaultTestLoader.loadTestsFromName(module_name)
    result = unittest.TextTestRunner(stream=out, verbosity=2).run(suite)
    failed = len(result.failures) + len(result.errors) + len(result.unexpectedSuccesses)
    skipped = len(result.skipped)
    return result.testsRun - failed - skipped, failed, skipped


# FreeCAD's GUI may redirect sys.stdout to its report view; the summary must
# reach the process's real stdout.
_out = sys.__stdout__
faulthandler.dump_traceback_later(int(os.environ["MEDIALMESH_TEST_TIMEOUT"]), exit=True, file=_out)
try:
    _passed, _failed, _skipped = run_tests(
        os.environ["MEDIALMESH_TEST_SCRIPT"], os.environ["MEDIALMESH_BUILD_DIR"], _out
    )
except BaseException:
    traceback.print_exc(file=_out)
    _passed, _failed, _skipped = 0, 1, 0
_out.write(f"freecad-tests: {_passed} passed, {_failed} failed, {_skipped} skipped\n")
_out.flush()
sys.exit(0 if _failed == 0 and _passed > 0 else 1)

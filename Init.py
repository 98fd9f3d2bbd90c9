# SPDX-License-Identifier: LGPL-2.1-or-later
"""MedialMesh App init script.

FreeCAD exec()s this file at start-up, in the GUI and in freecadcmd, from
inside a function of its own init script. So __file__ is not defined here,
and top-level names of this file are not visible inside functions defined
in it: the code stays flat.
"""

import os
import sys

import FreeCAD


# FreeCAD puts the addon folder on sys.path just before exec()ing this file;
# the user's and the system's Mod folders are the fallbacks.
_addon = None
for _folder in sys.path + [
    os.path.join(FreeCAD.getUserAppDataDir(), "Mod", "MedialMesh"),
    os.path.join(FreeCAD.getHomePath(), "Mod", "MedialMesh"),
]:
    if os.path.isfile(os.path.join(_folder, "Mod", "MedialMesh", "__init__.py")):
        # Not realpath: through the user Mod folder's link, as FreeCAD names
        # the addon in __ModDirs__. FreeCAD (0.20.2 as Debian patches it, and
        # later) restores a saved object's proxy only from a module under one
        # of those folders; under the link's target it would be refused.
        _addon = os.path.abspath(_folder)
        break

if _addon is None:
    FreeCAD.Console.PrintError("MedialMesh: cannot find the addon folder on sys.path\n")
else:
    # Mod: the MedialMesh package; build/lib: the compiled _medialmesh module.
    for _folder in (os.path.join(_addon, "Mod"), os.path.join(_addon, "build", "lib")):
        if os.path.isdir(_folder) and _folder not in sys.path:
            sys.path.append(_folder)
            FreeCAD.Console.PrintLog(f"MedialMesh: added {_folder} to sys.path\n")

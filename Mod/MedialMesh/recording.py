# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the workbench does to a document, run as lines of Python through
FreeCADGui.doCommand, as FreeCAD's own commands do: each line shows in the
Python console, and a macro being recorded takes it (GUI side only)."""

import FreeCADGui


def recorded(line):
    """Run a line of Python as FreeCAD's own commands do: it shows in the
    Python console and a macro being recorded takes it."""
    FreeCADGui.addModule("MedialMesh")
    FreeCADGui.doCommand(line)


def doc_ref(doc):
    return f"App.getDocument({doc.Name!r})"


def obj_ref(obj):
    return f"{doc_ref(obj.Document)}.getObject({obj.Name!r})"


def made_by(doc, line, type_name):
    """The object of Type type_name that running `line` (recorded) added."""
    before = {o.Name for o in doc.Objects}
    recorded(line)
    return next(o for o in doc.Objects if o.Name not in before and getattr(o, "Type", "") == type_name)

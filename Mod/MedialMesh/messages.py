# SPDX-License-Identifier: LGPL-2.1-or-later
"""What the user is told: the mesher's notes grouped and counted in plain
words (each saying what it means for the mesh and whether to act), and one
wording for a face that could not be meshed. The notes themselves stay as
the mesher wrote them in the object's Notes, for bug reports.

Plain functions of strings: no FreeCAD GUI here.
"""

import re
from dataclasses import dataclass
from typing import List

import _medialmesh

WARNING = "warning"  # the user should look at the mesh, or may act
INFO = "info"  # what was done; nothing to do


@dataclass
class Message:
    level: str  # WARNING or INFO
    text: str
    count: int  # notes it stands for


def counted(n, word, words=None):
    """'1 block', '3 blocks'."""
    return f"{n} {word if n == 1 else words or word + 's'}"


# (pattern of a note, level, what it means given how many notes matched).
# The first matching pattern takes a note; the order puts the specific first.
NOTE_GROUPS = [
    (r"as a fallback: .*(the worst element's shape was|its worst element's shape was)", WARNING,
     lambda n: "The first mesh had a very poor element, so it was made again another way (a fallback), keeping the "
     "better. Look at the worst elements (Colour by shape); a smaller element size usually helps."),
    (r"as a fallback: .*far coarser than asked", WARNING,
     lambda n: "The first mesh was far coarser than asked, so it was made again merging the irregular nodes as at "
     "the automatic size (a fallback). Look at its quality; a smaller merge factor may help."),
    (r"as a (last )?fallback|re-typed by its angles", WARNING,
     lambda n: "A fallback made this mesh: the usual way did not pass MedialMesh's own checks. The mesh is valid, "
     "but look at its quality; another element size or a merge factor of 0.5 may mesh it the usual way."),
    (r"^coarser than asked", WARNING,
     lambda n: "The mesh is coarser than the element size asks: a block's opposite sides held their element counts "
     "down. Try a smaller merge factor or element size."),
    (r"^order 2: .* bent less than their curve", WARNING,
     lambda n: "Some 8-node elements on curved edges follow the curve less closely than asked (their sides were "
     "bent less to keep the elements valid); a smaller element size there fixes it."),
    (r"^fixed a k = ", INFO,
     lambda n: f"{counted(n, 'irregular node')} placed at block corners or on the boundary rather than inside a "
     "block, where no split could free them. Nothing to do: the mesh is built round them."),
    (r"became a polygon round a k = ", INFO,
     lambda n: f"{counted(n, 'block')} meshed as a polygon round an irregular node of {'its' if n == 1 else 'their'} "
     "own. Nothing to do."),
    (r"^merged \d+ singularities|^parted \d+ singularities", INFO,
     lambda n: f"{counted(n, 'group')} of nearby irregular nodes merged into one or parted (the merge factor "
     "decides how near). Nothing to do."),
    (r"interior nodes of two elements", INFO,
     lambda n: "Interior nodes shared by only two elements were removed, their two elements joined. Nothing to do."),
    (r"fixed on its arc got the arc's sector|ran round a hole or bay was cut across|cusp that no typing", INFO,
     lambda n: f"{counted(n, 'block')} cut or shaped to fit a curved edge, a hole or a sharp tip. Nothing to do."),
    (r"^interval assignment:", INFO,
     lambda n: f"Element counts eased in {counted(n, 'block')} to agree with the neighbours'. Nothing to do."),
]


def group_notes(notes: List[str]) -> List[Message]:
    """The notes as messages for people: one per kind, counted, warnings
    first. A note of no known kind is shown as it is (counted when repeated)."""
    counts, first_seen = {}, {}
    for index, note in enumerate(notes):
        note = note.split(": ", 1)[1] if re.match(r"^\S+\.Face\d+: ", note) else note  # a face's name prefix
        key = next((i for i, (pattern, _, _) in enumerate(NOTE_GROUPS) if re.search(pattern, note)), note)
        counts[key] = counts.get(key, 0) + 1
        first_seen.setdefault(key, index)
    messages = []
    for key in sorted(counts, key=first_seen.get):
        n = counts[key]
        if isinstance(key, int):
            _, level, text = NOTE_GROUPS[key]
            messages.append(Message(level, text(n), n))
        else:
            messages.append(Message(INFO, key + (f" ({n} times)" if n > 1 else ""), n))
    return sorted(messages, key=lambda m: m.level != WARNING)


def fallback_message(fallbacks: List[str]) -> str:
    """The Status's words for a mesh a fallback made."""
    return f"ok (fallback: {', '.join(fallbacks)})"


HOW_TO_SEND = ("select the face, File > Export, save it as a .brep file, and send that file with the element size "
               "and merge factor used")


def failure_message(error, faces: str) -> str:
    """One wording of why `faces` ('Plate.Face1, ...') were not meshed, for
    the Status, the task panel and the report view: the problem, whose it
    is, and what to try."""
    text = str(error)
    if isinstance(error, _medialmesh.Cancelled):
        return f"{faces}: meshing cancelled"
    if isinstance(error, _medialmesh.SelfCheckError):
        check = text.split("self-check failed: ", 1)[-1]
        return (f"{faces}: MedialMesh could not mesh this: its own check of the result failed ({check}). "
                f"This is a defect of MedialMesh, not of your model. Try another element size or merge factor; "
                f"to report it, {HOW_TO_SEND}.")
    if isinstance(error, ValueError):  # InputError: a defect of the face or a bad parameter
        named = any(name.strip() in text for name in faces.split(","))
        return text if named else f"{faces}: {text}"
    return (f"{faces}: MedialMesh failed with an unexpected error ({error!r}). This is a defect of MedialMesh; "
            f"to report it, {HOW_TO_SEND}.")

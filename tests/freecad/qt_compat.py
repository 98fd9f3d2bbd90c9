# SPDX-License-Identifier: LGPL-2.1-or-later
"""Qt for the GUI tests through FreeCAD's PySide shim, as the workbench
imports it: PySide2 under FreeCAD 0.20, PySide2 or PySide6 under 1.0. The
0.20 shim has no PySide.QtWidgets (its QtGui holds the widgets too)."""

from PySide import QtCore, QtGui

try:
    from PySide import QtWidgets
except ImportError:
    QtWidgets = QtGui

__all__ = ["QtCore", "QtGui", "QtWidgets"]

"""livemod: procedural manifold mesh modeling in Python.

``livemod.dlfl`` is the DLFL modeling library (numpy only), ``livemod.runner``
runs and watches scripts, ``livemod.viewer`` is the live GL window and the
headless renderer. The command line is ``livemod`` (see ``livemod --help``).
"""

__version__ = "0.1.0"

"""One wireframe soccer ball; its thickness is a parameter (thesis figure 31, batch form).

    livemod batch scripts/wireframe_soccerball.py --param thickness=0.02:0.16:30 -o 'out/ball_{index:02d}.obj'

makes the thesis's 30 balls of increasing thickness on all cores.
"""

from livemod.dlfl import *

thickness = param("thickness", 0.06, min=0.005, max=0.3, doc="rod thickness")

load("soccerball")
wireframe(thickness)

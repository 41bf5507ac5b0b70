"""IGAView's VTK classes: readers, sources and filters of rational Bézier and NURBS volumes
(IGAViewFilters) and the mapper and offscreen image filter of the SST engine
(IGAViewRendering). Import after vtkmodules (pvpython, or python3 with Debian's
python3-paraview), e.g. `from igaview import vtkIGAGismoReader, vtkIGAIsosurfaceMapper`."""

from .IGAViewFilters import *  # noqa: F401,F403
from .IGAViewRendering import *  # noqa: F401,F403

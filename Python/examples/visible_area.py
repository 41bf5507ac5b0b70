"""The visible area of an isosurface, and of its part where another field exceeds a value, from
vtkIGAIsosurfaceImage: no window, no X server. Each pixel's first hit covers the area its
footprint takes on the surface: (2 d tan(angle / 2) / height)^2 on the plane facing the camera
at the hit's eye depth d (`angle` the camera's view angle), times |r.f| / |r.n| from that plane
onto the surface along the ray (r the ray's direction, f the view direction, n the normal).

    python3 visible_area.py FILE.vtu SURFACE_ARRAY ISOVALUE FIELD THRESHOLD [DISTANCE]

The camera looks at the origin from (0, 0, DISTANCE) (default 6) with a 30 degree view angle.
"""
import math
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.vtkRenderingCore import vtkCamera

from igaview import vtkIGAIsosurfaceImage


def visible_areas(path, surface_array, isovalue, field, threshold, distance=6.0, size=400):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    camera = vtkCamera()
    camera.SetPosition(0, 0, distance)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewAngle(30)
    camera.SetClippingRange(0.01 * distance, 10 * distance)
    image = vtkIGAIsosurfaceImage()
    image.SetInputConnection(reader.GetOutputPort())
    image.GetMapper().SetSurfaceArrayName(surface_array)
    image.GetMapper().SetNumberOfIsovalues(1)
    image.GetMapper().SetIsovalue(0, isovalue)
    image.SetCamera(camera)
    image.SetImageSize(size, size)
    image.Update()
    pixels = image.GetOutput().GetPointData()
    depth = vtk_to_numpy(pixels.GetArray("Depth"))
    normal = vtk_to_numpy(pixels.GetArray("Normal"))
    position = vtk_to_numpy(pixels.GetArray("Position"))
    values = vtk_to_numpy(pixels.GetArray(field))
    hit = np.isfinite(depth)
    ray = position[hit] - np.array(camera.GetPosition())
    ray /= np.linalg.norm(ray, axis=1)[:, None]
    forward = np.array(camera.GetDirectionOfProjection())
    slant = np.abs(ray @ forward) / np.abs(np.einsum("ij,ij->i", ray, normal[hit]))
    footprint = 2 * depth[hit] * math.tan(math.radians(camera.GetViewAngle()) / 2) / size
    area = footprint**2 * slant
    return area.sum(), area[values[hit] > threshold].sum()


if __name__ == "__main__":
    if len(sys.argv) not in (6, 7):
        sys.exit(__doc__)
    path, surface_array, isovalue, field, threshold = sys.argv[1:6]
    distance = float(sys.argv[6]) if len(sys.argv) == 7 else 6.0
    total, above = visible_areas(path, surface_array, float(isovalue), field, float(threshold),
                                 distance)
    print(f"visible area {total:.6g}, where {field} > {threshold}: {above:.6g}")

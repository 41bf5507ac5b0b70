/**
 * @class   vtkIGABoundarySurface
 * @brief   The boundary of rational Bézier hexahedra as rational Bézier quadrilaterals, exactly.
 *
 * The input is a vtkUnstructuredGrid of VTK_BEZIER_HEXAHEDRON cells (see vtkIGABezierHexahedra).
 * Every face of a cell that no other cell shares (the same control points, in any orientation)
 * and that is not collapsed onto a curve or a point (a cylinder's axis) becomes a
 * VTK_BEZIER_QUADRILATERAL whose control points are that face's slice of the cell's net: the
 * same rational surface, with the point attributes, RationalWeights and HigherOrderDegrees.
 * Cell arrays "BoundaryCell" (the input cell) and "BoundaryFace" (2 * direction + side, the
 * cell's parametric direction across the face and 0 or 1 for its end) say where each face comes
 * from. A geometry-only file (G+Smo, GeoPDEs) so shows the shape of its body; ParaView draws the
 * quadrilaterals by its own tessellation. An input that is not Bézier hexahedra gives one error
 * and an empty output.
 */
#ifndef vtkIGABoundarySurface_h
#define vtkIGABoundarySurface_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class IGAVIEWFILTERS_EXPORT vtkIGABoundarySurface : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkIGABoundarySurface* New();
  vtkTypeMacro(vtkIGABoundarySurface, vtkUnstructuredGridAlgorithm);

protected:
  vtkIGABoundarySurface() = default;
  ~vtkIGABoundarySurface() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkIGABoundarySurface(const vtkIGABoundarySurface&) = delete;
  void operator=(const vtkIGABoundarySurface&) = delete;
};

#endif

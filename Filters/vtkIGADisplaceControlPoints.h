/**
 * @class   vtkIGADisplaceControlPoints
 * @brief   Moves the control points of rational Bézier hexahedra by a displacement point array
 *          times a scale factor, as IGA solvers output displacements on control points.
 *
 * The input is a vtkUnstructuredGrid of VTK_BEZIER_HEXAHEDRON cells (see vtkIGABezierHexahedra:
 * Euclidean points, weights in RationalWeights). Every point p becomes p + ScaleFactor * d(p); the
 * weights stay, so the output cells are the splines with the moved control points. All arrays
 * are passed unchanged. The displacement is input array 0 (a 3-component point array; by
 * default the active vectors). A missing array, a cell array, another component count or a
 * non-finite value is reported as one error naming the array and the point, and the output is
 * left empty.
 */
#ifndef vtkIGADisplaceControlPoints_h
#define vtkIGADisplaceControlPoints_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class IGAVIEWFILTERS_EXPORT vtkIGADisplaceControlPoints : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkIGADisplaceControlPoints* New();
  vtkTypeMacro(vtkIGADisplaceControlPoints, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Multiplies the displacement (1: the solver's result as is).
  vtkSetMacro(ScaleFactor, double);
  vtkGetMacro(ScaleFactor, double);
  ///@}

protected:
  vtkIGADisplaceControlPoints();
  ~vtkIGADisplaceControlPoints() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double ScaleFactor = 1.0;

private:
  vtkIGADisplaceControlPoints(const vtkIGADisplaceControlPoints&) = delete;
  void operator=(const vtkIGADisplaceControlPoints&) = delete;
};

#endif

/**
 * @class   vtkIGADefaultVolumeSource
 * @brief   The bundled default dataset: a twisted and bent thick-walled tube of 8 tri-quadratic
 *          rational Bézier patches with "temperature" and "radius" attributes.
 *
 * Produces VTK_BEZIER_HEXAHEDRON cells (see vtkIGABezierHexahedra). The deformation amplitude
 * follows the pipeline's update time, or `Time` when no time is requested, over the time steps
 * 0..1 it advertises. Piece requests get whole patches: piece p of n holds patches
 * [8p/n, 8(p+1)/n), possibly none.
 */
#ifndef vtkIGADefaultVolumeSource_h
#define vtkIGADefaultVolumeSource_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class IGAVIEWFILTERS_EXPORT vtkIGADefaultVolumeSource : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkIGADefaultVolumeSource* New();
  vtkTypeMacro(vtkIGADefaultVolumeSource, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Deformation amplitude in [0, 1] used when the pipeline requests no time.
  vtkSetClampMacro(Time, double, 0.0, 1.0);
  vtkGetMacro(Time, double);
  ///@}

protected:
  vtkIGADefaultVolumeSource();
  ~vtkIGADefaultVolumeSource() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double Time = 0.5;

private:
  vtkIGADefaultVolumeSource(const vtkIGADefaultVolumeSource&) = delete;
  void operator=(const vtkIGADefaultVolumeSource&) = delete;
};

#endif

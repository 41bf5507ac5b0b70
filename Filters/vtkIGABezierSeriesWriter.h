/**
 * @class   vtkIGABezierSeriesWriter
 * @brief   Writes every time step of a Bézier-cell source as a .vtu file and a .pvd collection
 *          that ParaView's PVD reader (vtkPVDReader) opens as a time series.
 *
 * The producer of the input connection (a NURBS reader, the default volume source, a deformation
 * filter) is updated on that output port at each of its TIME_STEPS (once, without a time, when it
 * advertises none) and each grid is written by vtkXMLUnstructuredGridWriter as FILE_STEM_<i>.vtu
 * beside the .pvd FileName, which lists them with their times. VTK's XML writer keeps the rational
 * weights, higher-order degrees (with their active flags) and field data, so each step's NURBS
 * description survives (see vtkIGANurbsData).
 */
#ifndef vtkIGABezierSeriesWriter_h
#define vtkIGABezierSeriesWriter_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for the input

class vtkAlgorithmOutput;

class IGAVIEWFILTERS_EXPORT vtkIGABezierSeriesWriter : public vtkObject
{
public:
  static vtkIGABezierSeriesWriter* New();
  vtkTypeMacro(vtkIGABezierSeriesWriter, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .pvd file to write; the .vtu files go beside it.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// The source of vtkUnstructuredGrid time steps.
  void SetInputConnection(vtkAlgorithmOutput* input);

  /// Writes all time steps. Returns 1 on success; on failure reports one error and returns 0.
  int Write();

protected:
  vtkIGABezierSeriesWriter() = default;
  ~vtkIGABezierSeriesWriter() override;

  char* FileName = nullptr;
  vtkSmartPointer<vtkAlgorithmOutput> Input;

private:
  vtkIGABezierSeriesWriter(const vtkIGABezierSeriesWriter&) = delete;
  void operator=(const vtkIGABezierSeriesWriter&) = delete;
};

#endif

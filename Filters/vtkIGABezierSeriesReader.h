/**
 * @class   vtkIGABezierSeriesReader
 * @brief   Reads a .pvd collection of Bézier-cell .vtu files (vtkIGABezierSeriesWriter's, the
 *          data generator's --series, ParaView's) as one source with time steps.
 *
 * RequestInformation parses the collection and advertises its DataSet elements' `timestep`s as
 * TIME_STEPS; RequestData reads the step at or before the requested time (the first one before
 * all of them, like VTK's readers) through vtkIGABezierFileReading, so a malformed or oversized
 * step is refused with one error naming its file instead of aborting in VTK's XML reader. The
 * files are relative to the collection's directory. Several parts at one time step (a parallel
 * writer's pieces) are refused: each time step is one file.
 */
#ifndef vtkIGABezierSeriesReader_h
#define vtkIGABezierSeriesReader_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <string> // for the steps' files
#include <vector> // for the steps

class IGAVIEWFILTERS_EXPORT vtkIGABezierSeriesReader : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkIGABezierSeriesReader* New();
  vtkTypeMacro(vtkIGABezierSeriesReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .pvd collection file.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);
  ///@}

  /// 1 when `name` is a regular file starting like a VTK XML collection (`<VTKFile
  /// type="Collection"`, either quotes, in its first KiB), 0 otherwise.
  static int CanReadFile(const char* name);

  /// The time steps of the collection, sorted, after UpdateInformation (none before or on error).
  int GetNumberOfTimeSteps() const { return int(this->Times.size()); }
  double GetTimeStep(int i) const { return this->Times[size_t(i)]; }

protected:
  vtkIGABezierSeriesReader();
  ~vtkIGABezierSeriesReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Parses the collection into Times and Files; false with `error` set on bad input.
  bool ParseCollection(std::string& error);

  char* FileName = nullptr;
  std::vector<double> Times;
  std::vector<std::string> Files; ///< per time step, resolved against the collection's directory

private:
  vtkIGABezierSeriesReader(const vtkIGABezierSeriesReader&) = delete;
  void operator=(const vtkIGABezierSeriesReader&) = delete;
};

#endif

/**
 * @class   vtkIGAIsosurfaceProbeLine
 * @brief   Where a line segment meets the isosurfaces the mapper draws, solved exactly, with
 *          every attribute there: a probe for IGA data (ParaView's *IGA Probe Line*).
 *
 * Input: what vtkIGAIsosurfaceMapper draws. The engine's settings are those of GetMapper()
 * (surface array, isovalues, draw mode, CSG, clipping planes, backend, ...). The segment from
 * Point1 to Point2 is the ray of the one pixel of a parallel view whose clipping range is the
 * segment (vtkIGAIsosurfaceImage, 1 x 1 pixels), so its hits are the engine's, each solved on
 * that ray as a pixel's is: the first MaximumHits of them from Point1 (MaximumHits above 1
 * turns the mapper's AllLayers on). The near clipping plane lies 1e-9 of the segment's length
 * past Point1: a hit closer to it is not reported. No OpenGL and no X server are needed.
 *
 * Output: a vtkPolyData of one vertex per hit, nearest Point1 first, at the hit's world
 * position, with point arrays Distance (from Point1 along the segment), Normal (facing Point1),
 * UVW (the parameter in the cell), Cell (its id in its grid), Block (composite input) and every
 * point attribute of the input evaluated at the hit from its cell (not interpolated; one named
 * as a fixed array yields to it). A segment
 * that meets nothing gives no points; Point1 equal to Point2 is refused.
 */
#ifndef vtkIGAIsosurfaceProbeLine_h
#define vtkIGAIsosurfaceProbeLine_h

#include "IGAViewRenderingModule.h" // for export macro
#include "vtkNew.h"                 // for the image filter
#include "vtkPolyDataAlgorithm.h"

class vtkIGAIsosurfaceImage;
class vtkIGAIsosurfaceMapper;

class IGAVIEWRENDERING_EXPORT vtkIGAIsosurfaceProbeLine : public vtkPolyDataAlgorithm
{
public:
  static vtkIGAIsosurfaceProbeLine* New();
  vtkTypeMacro(vtkIGAIsosurfaceProbeLine, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The engine's settings (isovalues, surface array, draw mode, ...).
  vtkIGAIsosurfaceMapper* GetMapper();

  ///@{
  /// The segment's ends (default (0, 0, 0) and (1, 0, 0)).
  vtkSetVector3Macro(Point1, double);
  vtkGetVector3Macro(Point1, double);
  vtkSetVector3Macro(Point2, double);
  vtkGetVector3Macro(Point2, double);
  ///@}

  ///@{
  /// Hits reported at most, nearest Point1 first (default 16, at most 64).
  vtkSetClampMacro(MaximumHits, int, 1, 64);
  vtkGetMacro(MaximumHits, int);
  ///@}

  ///@{
  /// The mapper's surface array and single isovalue; SetSurfaceArray is the name's form that
  /// ParaView's array properties call.
  void SetSurfaceArrayName(const char* name);
  void SetSurfaceArray(int index, int port, int connection, int association, const char* name);
  void SetIsovalue(double value);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkIGAIsosurfaceProbeLine();
  ~vtkIGAIsosurfaceProbeLine() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkIGAIsosurfaceProbeLine(const vtkIGAIsosurfaceProbeLine&) = delete;
  void operator=(const vtkIGAIsosurfaceProbeLine&) = delete;

  double Point1[3] = { 0, 0, 0 };
  double Point2[3] = { 1, 0, 0 };
  int MaximumHits = 16;
  vtkNew<vtkIGAIsosurfaceImage> Image;
};

#endif

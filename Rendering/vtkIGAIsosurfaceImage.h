/**
 * @class   vtkIGAIsosurfaceImage
 * @brief   The mapper's frame as an image, for analysis: no OpenGL, no X server, no window.
 *
 * Input: what vtkIGAIsosurfaceMapper draws (a grid of Bézier hexahedra and quadrilaterals, or a
 * composite dataset of them). The engine's settings are those of the mapper GetMapper() returns
 * (isovalues, surface array, draw mode, CSG, clipping planes, backend, threads, AllLayers,
 * ...); the shading's colour, edges and opacity those of GetProperty(), coloured by the
 * mapper's colour array and lookup table as it draws; the view that of SetCamera (by default a
 * camera looking down -z at the input's bounds, as vtkRenderer::ResetCamera frames them) at
 * ImageSize pixels; a headlight lights it. The engine runs as the mapper's does: on CUDA where
 * available, else on CPU threads.
 *
 * Output: a vtkImageData of ImageSize[0] x ImageSize[1] points (spacing 1, origin 0, row 0 at
 * the bottom, as a VTK image shows) with point arrays describing each pixel's first hit:
 * Depth (eye-space depth, the distance from the eye along the view direction), Position and
 * Normal (world, the normal facing the viewer), UVW (the parameter in the cell), Cell (the
 * cell's id in its grid), Block (the composite block's flat index, composite input only),
 * HitCount (every hit along the pixel's ray with the mapper's AllLayers on or a translucent
 * property, else 1), RGBA (the shaded colour, 8 bits a channel) and every point attribute of
 * the input evaluated exactly at the hit (not interpolated), under its own name. Pixels with no
 * hit hold NaN (Cell -1, HitCount 0, RGBA 0).
 *
 * With Layers above 1 (and the mapper's AllLayers on, so that the frame keeps every hit) the
 * hits behind the first come too: for layer k = 1 .. Layers - 1, the k-th hit behind the first
 * along the ray, its arrays named as the first hit's with "_k" appended (Depth_1, Position_1,
 * ..., an attribute "T" as T_1); NaN (Cell -1) where the ray has fewer hits.
 */
#ifndef vtkIGAIsosurfaceImage_h
#define vtkIGAIsosurfaceImage_h

#include "IGAViewRenderingModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkNew.h" // for members

#include <string> // for WriteLayer

class vtkActor;
class vtkCamera;
class vtkDataObject;
class vtkImageData;
class vtkIGAIsosurfaceMapper;
class vtkProperty;

class IGAVIEWRENDERING_EXPORT vtkIGAIsosurfaceImage : public vtkImageAlgorithm
{
public:
  static vtkIGAIsosurfaceImage* New();
  vtkTypeMacro(vtkIGAIsosurfaceImage, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The engine's settings (isovalues, surface and colour arrays, draw mode, ...).
  vtkIGAIsosurfaceMapper* GetMapper();

  /// The shading's colour, edges and opacity.
  vtkProperty* GetProperty();

  ///@{
  /// The view; null (the default): the input framed as vtkRenderer::ResetCamera frames it,
  /// looking down -z.
  void SetCamera(vtkCamera* camera);
  vtkCamera* GetCamera() { return this->Camera; }
  ///@}

  ///@{
  /// The image's width and height in pixels (default 512 x 512).
  vtkSetVector2Macro(ImageSize, int);
  vtkGetVector2Macro(ImageSize, int);
  ///@}

  ///@{
  /// Hits a pixel reports, nearest first (default 1, the first hit alone; at most 64).
  vtkSetClampMacro(Layers, int, 1, 64);
  vtkGetMacro(Layers, int);
  ///@}

  vtkMTimeType GetMTime() override;

protected:
  vtkIGAIsosurfaceImage();
  ~vtkIGAIsosurfaceImage() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkIGAIsosurfaceImage(const vtkIGAIsosurfaceImage&) = delete;
  void operator=(const vtkIGAIsosurfaceImage&) = delete;

  /// The mapper's frame of `input` for the camera; false when nothing was computed.
  bool ComputeFrame(vtkDataObject* input);
  /// The output's arrays from the mapper's last frame (empty pixels only when not computed).
  void WritePixels(vtkImageData* image, bool composite, bool computed);
  /// The arrays of each pixel's hit `layer` (0 the first), named with `suffix`.
  void WriteLayer(vtkImageData* image, bool composite, int layer, const std::string& suffix);

  vtkNew<vtkIGAIsosurfaceMapper> Mapper;
  vtkNew<vtkActor> Actor;
  vtkCamera* Camera = nullptr;
  int ImageSize[2] = { 512, 512 };
  int Layers = 1;
};

#endif

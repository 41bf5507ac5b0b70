/**
 * @class   vtkIGAGBufferImage
 * @brief   The engine's G-buffer (first hits) as a vtkImageData, ready for vtkIGAEXRWriter.
 *
 * Point-data arrays, one value per pixel (row 0 at the bottom, as in VTK):
 * R, G, B, A (the shaded colour given by the caller, premultiplied, 0 where nothing is hit);
 * Z (eye-space depth, +inf where nothing is hit); P (world position) and N (world normal),
 * 3 components each; u, v, w (parameter in the patch); patch (patch index, -1 for none); and,
 * when the engine sampled a colour attribute, that attribute under its own name; on request,
 * operand (Hit::isovalue: the CSG operand whose surface the hit is, -1 for none). Position,
 * normal, parameter and attribute are NaN where nothing is hit.
 */
#ifndef vtkIGAGBufferImage_h
#define vtkIGAGBufferImage_h

#include "IGAViewFiltersModule.h" // for export macro
#include "iga/sst/GBuffer.h"      // for GBuffer
#include "vtkSmartPointer.h"      // for return value

#include <string>

class vtkImageData;

class IGAVIEWFILTERS_EXPORT vtkIGAGBufferImage
{
public:
  /// `rgba` holds width * height * 4 floats (row 0 at the bottom) or is null (all 0).
  /// `colorName` names the colour attribute's array; empty for none. `operands` adds the
  /// operand array.
  static vtkSmartPointer<vtkImageData> Convert(const iga::sst::GBuffer& gbuffer, const float* rgba,
    const std::string& colorName, bool operands = false);
};

#endif

/**
 * @class   vtkIGADeepEXR
 * @brief   Every layer of the engine's G-buffer as a deep OpenEXR image (deep scan lines): the
 *          geometry of each sample (no colour) for compositing and analysis tools.
 *
 * Per pixel its hits front to back as deep samples (row 0 of the G-buffer, the bottom, is the
 * image's last row, as EXR rows run top to bottom), FLOAT channels: Z (eye depth), P.X P.Y
 * P.Z (world position), N.X N.Y N.Z (world normal, facing the viewer), u v w (parameter in the
 * patch), patch, operand (Hit::isovalue: the isovalue's index, the CSG operand, -1 for a
 * surface) and entering (1 where the ray enters the region below the isovalue or, for CSG, the
 * solid, else 0). A pixel without hits has no samples.
 */
#ifndef vtkIGADeepEXR_h
#define vtkIGADeepEXR_h

#include "IGAViewFiltersModule.h" // for export macro
#include "iga/sst/GBuffer.h"      // for GBuffer

#include <string>

class IGAVIEWFILTERS_EXPORT vtkIGADeepEXR
{
public:
  /// Writes `gbuffer` to `file`; false with `error` set when it cannot.
  static bool Write(const iga::sst::GBuffer& gbuffer, const std::string& file, std::string& error);
};

#endif

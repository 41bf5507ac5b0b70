/**
 * @class   vtkIGAEXRWriter
 * @brief   Writes a 2D vtkImageData as an OpenEXR file with one float channel per component.
 *
 * Every point-data array becomes channels: a 1-component array is named as the array, an array
 * of 2 to 4 components gives NAME.X, NAME.Y, NAME.Z, NAME.W. Values are stored as 32-bit floats;
 * integer arrays are converted. EXR's row 0 is the top row, so rows are flipped from VTK's
 * bottom-up order. Errors (no input, not 2D, unwritable file) are reported with the file name.
 */
#ifndef vtkIGAEXRWriter_h
#define vtkIGAEXRWriter_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkWriter.h"

class vtkImageData;

class IGAVIEWFILTERS_EXPORT vtkIGAEXRWriter : public vtkWriter
{
public:
  static vtkIGAEXRWriter* New();
  vtkTypeMacro(vtkIGAEXRWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  /// The last error, empty when the last write succeeded.
  const char* GetLastError() const { return this->LastError.c_str(); }

protected:
  vtkIGAEXRWriter();
  ~vtkIGAEXRWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  char* FileName = nullptr;
  std::string LastError;

private:
  vtkIGAEXRWriter(const vtkIGAEXRWriter&) = delete;
  void operator=(const vtkIGAEXRWriter&) = delete;
};

#endif

/**
 * @class   vtkIGAGeoPDEsReader
 * @brief   Reads GeoPDEs NURBS geometry text files ("nurbs geometry v.2.1", "nurbs mesh v.2.1"
 *          and the older v.0.7 form), single patch or multipatch, volumes and surfaces.
 *
 * After '#' comment lines, the header line is "ndim rdim Np [Ni Ns]" (v.2.1; also assumed when
 * the comments name no version) or "N Np [Ni Ns]" (v.0.6 / v.0.7, where ndim = rdim = N). Each
 * patch is an optional name line ("PATCH 1"), the degrees, the numbers of control points, one
 * knot vector per parametric direction, rdim lines of weighted coordinates (w*x, w*y[, w*z]) and
 * one line of weights, first parametric direction fastest. The sections that follow are read
 * as GeoPDEs reads them: Ni interfaces, Ns subdomains, then boundaries to the end, each after a
 * name line of free text ("INTERFACE 1", "EXTERNAL BOUNDARY"); they are checked (patch and
 * side numbers, the header's counts) but not used.
 * rdim = 2 puts the patches in z = 0.
 *
 * Like vtkIGAGismoReader, the output has the attributes "x", "y", "z" and "parameter_u/v/w"
 * (iga::setGeometryNet). Errors name the file, the line and the problem.
 */
#ifndef vtkIGAGeoPDEsReader_h
#define vtkIGAGeoPDEsReader_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkIGANurbsReader.h"

class IGAVIEWFILTERS_EXPORT vtkIGAGeoPDEsReader : public vtkIGANurbsReader
{
public:
  static vtkIGAGeoPDEsReader* New();
  vtkTypeMacro(vtkIGAGeoPDEsReader, vtkIGANurbsReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkIGAGeoPDEsReader() = default;
  ~vtkIGAGeoPDEsReader() override = default;

  std::string ReadNurbs(const std::string& text, vtkIGANurbsData* data) override;
  bool IsOwnFormat(const std::string& head) const override;

private:
  vtkIGAGeoPDEsReader(const vtkIGAGeoPDEsReader&) = delete;
  void operator=(const vtkIGAGeoPDEsReader&) = delete;
};

#endif

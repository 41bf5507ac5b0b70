/**
 * @class   vtkIGAGismoReader
 * @brief   Reads G+Smo XML geometry files: TensorBSpline3 / TensorNurbs3 volumes and
 *          TensorBSpline2 / TensorNurbs2 surfaces, single or in a MultiPatch.
 *
 * G+Smo stores Euclidean coefficients (<coefs geoDim="3">, geoDim 2 puts the patch in z = 0) and,
 * for NURBS, the weights separately (<weights> in the TensorNurbsBasis), first parametric
 * direction fastest, with one <KnotVector degree="p"> per direction. When the file has a
 * <MultiPatch>, the first one's patches are read (<patches type="id_range"> first..last ids,
 * type="id_index" a list of ids, or Geometry elements nested in it); otherwise every top-level
 * <Geometry>. Volumes become VTK_BEZIER_HEXAHEDRON cells, surfaces VTK_BEZIER_QUADRILATERAL.
 *
 * The reader adds attributes that can be contoured (iga::setGeometryNet): "x", "y", "z" (exact
 * everywhere) and "parameter_u/v/w" (exact on polynomial patches, and everywhere with
 * ExactParameters on, see vtkIGANurbsData). Solutions: G+Smo writes a
 * field as a further MultiPatch whose patches share the geometry's basis (fd << geometry <<
 * solution, fd.addWithLabel for a name); every MultiPatch after the geometry's becomes
 * attributes, named by its label ("field1", "field2", ... without one), a vector field's
 * components NAME_0, NAME_1, NAME_2 (and, from the grid, a 3-component array NAME, e.g. for
 * vtkIGADisplaceControlPoints). A field patch must have its geometry patch's degrees, knots and
 * weights (to a common factor): a B-spline field on a NURBS geometry is not in the geometry's
 * rational basis and is refused. Errors name the file, the line of the offending element and
 * the problem.
 */
#ifndef vtkIGAGismoReader_h
#define vtkIGAGismoReader_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkIGANurbsReader.h"

class IGAVIEWFILTERS_EXPORT vtkIGAGismoReader : public vtkIGANurbsReader
{
public:
  static vtkIGAGismoReader* New();
  vtkTypeMacro(vtkIGAGismoReader, vtkIGANurbsReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkIGAGismoReader() = default;
  ~vtkIGAGismoReader() override = default;

  std::string ReadNurbs(const std::string& text, vtkIGANurbsData* data) override;
  bool IsOwnFormat(const std::string& head) const override;

private:
  vtkIGAGismoReader(const vtkIGAGismoReader&) = delete;
  void operator=(const vtkIGAGismoReader&) = delete;
};

#endif

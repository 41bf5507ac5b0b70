/**
 * @class   vtkIGAAlgebraicSource
 * @brief   An algebraic surface f(x, y, z) = 0 over a box, as the exact Bernstein volume of f:
 *          one VTK_BEZIER_HEXAHEDRON cell with affine geometry and the point attribute "f".
 *
 * f is a polynomial expression in x, y and z (+ - * / by constants, ^ by whole exponents,
 * parentheses, decimal constants; degree up to 16 in total), or one of the gallery's surfaces
 * of Reimers-Seland and Seland-Dokken (GallerySurface), which brings its own box. The surface is
 * the isosurface f = 0, which vtkIGAIsosurfaceMapper draws by ray composition (affine geometry);
 * the cell's degree per direction is f's (at least 1). A bad expression, an empty or non-finite
 * box, or coefficients that overflow are reported as one error naming the problem (the
 * expression's position), with an empty output (the request itself succeeds, so that views
 * draw again once the setting is good).
 *
 * With SplineCells n > 0 the output is instead an algebraic B-spline (ABS) field, Wei and
 * Feng's scenes: f fitted on n x n x n uniform elements of degree SplineDegree
 * (iga::makeAbsField: coefficients f's values at the Greville points), each element a cell with
 * affine geometry, those whose coefficients share a sign (no surface inside) dropped.
 * Piece requests: piece p of n holds the cells [p N / n, (p + 1) N / n) of the N.
 */
#ifndef vtkIGAAlgebraicSource_h
#define vtkIGAAlgebraicSource_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <string> // for the expression

class IGAVIEWFILTERS_EXPORT vtkIGAAlgebraicSource : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkIGAAlgebraicSource* New();
  vtkTypeMacro(vtkIGAAlgebraicSource, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The polynomial f (default the unit sphere, "x^2 + y^2 + z^2 - 1"), used when
  /// GallerySurface is -1.
  void SetExpression(const char* expression);
  const char* GetExpression() const { return this->Expression.c_str(); }
  ///@}

  ///@{
  /// The box x0, x1, y0, y1, z0, z1 the expression is drawn over (default [-1.2, 1.2]^3).
  vtkSetVector6Macro(Box, double);
  vtkGetVector6Macro(Box, double);
  ///@}

  ///@{
  /// A surface of the gallery (its index, GetGallerySurfaceName's order) with its own
  /// expression and box, or -1 (default) for Expression over Box. SetGallerySurfaceByName takes
  /// its name ("kummer", "super-sphere", ...) and reports an unknown one as an error.
  vtkSetClampMacro(GallerySurface, int, -1, 1023);
  vtkGetMacro(GallerySurface, int);
  void SetGallerySurfaceByName(const char* name);
  static int GetNumberOfGallerySurfaces();
  static const char* GetGallerySurfaceName(int index);
  ///@}

  ///@{
  /// 0 (default): the exact Bernstein volume of f; 1..64: an ABS field of that many elements
  /// per direction.
  vtkSetClampMacro(SplineCells, int, 0, 64);
  vtkGetMacro(SplineCells, int);
  ///@}

  ///@{
  /// The ABS field's degree per direction, 1..3 (default 3).
  vtkSetClampMacro(SplineDegree, int, 1, 3);
  vtkGetMacro(SplineDegree, int);
  ///@}

protected:
  vtkIGAAlgebraicSource();
  ~vtkIGAAlgebraicSource() override = default;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string Expression = "x^2 + y^2 + z^2 - 1";
  double Box[6] = { -1.2, 1.2, -1.2, 1.2, -1.2, 1.2 };
  int GallerySurface = -1;
  int SplineCells = 0;
  int SplineDegree = 3;

private:
  vtkIGAAlgebraicSource(const vtkIGAAlgebraicSource&) = delete;
  void operator=(const vtkIGAAlgebraicSource&) = delete;
};

#endif

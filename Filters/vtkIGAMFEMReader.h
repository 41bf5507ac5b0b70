/**
 * @class   vtkIGAMFEMReader
 * @brief   Reads MFEM NURBS meshes ("MFEM NURBS mesh v1.0"), volumes and surfaces, and MFEM
 *          GridFunction files on them as attributes.
 *
 * Both forms MFEM writes are read. The patch-topology form: the patches as elements of a coarse
 * mesh (elements, boundary, edges with their knot vectors, vertices), the knot vectors, one
 * weight per control point and the control points as the nodes of a NURBS finite element space
 * ("FiniteElementSpace", Ordering 0 or 1); the control points of a patch are gathered from its
 * corners, the interiors of its edges and faces and its own interior as MFEM numbers them
 * (NURBSExtension: vertices, then edges, faces and patches in the order the mesh meets them,
 * shared edges and faces oriented by their vertices). The "patches" form: per patch its knot
 * vectors and its control points (homogeneous, "controlpoints" and
 * "controlpoints_homogeneous", or "controlpoints_cartesian"). Meshes of dimension 3 give
 * VTK_BEZIER_HEXAHEDRON cells, dimension 2 VTK_BEZIER_QUADRILATERAL cells (in z = 0 when the
 * nodes have 2 components); curves (dimension 1) are refused.
 *
 * Attributes: "x", "y", "z" and "parameter_u/v/w" as the other NURBS readers add them
 * (iga::setGeometryNet), and one per GridFunction file given (AddGridFunctionFileName; the
 * patch-topology form only): named after the file without its folder and extension ("u" for
 * u.gf), a vector field's components NAME_0, NAME_1, ... Its coefficients are read on the mesh's
 * control points, so its NURBS order must be the mesh's. Errors name the file, the line and
 * the problem.
 */
#ifndef vtkIGAMFEMReader_h
#define vtkIGAMFEMReader_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkIGANurbsReader.h"

#include <string> // for the file names
#include <vector> // for the file names

class IGAVIEWFILTERS_EXPORT vtkIGAMFEMReader : public vtkIGANurbsReader
{
public:
  static vtkIGAMFEMReader* New();
  vtkTypeMacro(vtkIGAMFEMReader, vtkIGANurbsReader);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// MFEM GridFunction files (.gf) whose fields become attributes.
  void AddGridFunctionFileName(const char* name);
  void RemoveAllGridFunctionFileNames();
  int GetNumberOfGridFunctionFileNames() const;
  const char* GetGridFunctionFileName(int index) const;
  ///@}

protected:
  vtkIGAMFEMReader() = default;
  ~vtkIGAMFEMReader() override = default;

  std::string ReadNurbs(const std::string& text, vtkIGANurbsData* data) override;
  bool IsOwnFormat(const std::string& head) const override;
  std::string InputStamp() const override;

private:
  vtkIGAMFEMReader(const vtkIGAMFEMReader&) = delete;
  void operator=(const vtkIGAMFEMReader&) = delete;

  std::vector<std::string> GridFunctionFileNames;
};

#endif

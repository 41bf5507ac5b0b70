/**
 * @class   vtkIGABezierHexahedra
 * @brief   Converts between Kernels rational Bézier volumes and vtkUnstructuredGrid cells of type
 *          VTK_BEZIER_HEXAHEDRON.
 *
 * The grid side follows VTK's conventions: points in VTK's higher-order hexahedron ordering
 * (vtkHigherOrderHexahedron::PointIndexFromIJK), Euclidean coordinates, a point array
 * "RationalWeights" and a 3-component cell array "HigherOrderDegrees" (left out when VTK can infer
 * the degrees, see CellLayout), both flagged as the active rational weights / higher-order
 * degrees (VTK silently ignores them otherwise), and one point array per attribute. Patches do not
 * share points: each cell owns its control points, so patches of different degrees and
 * discontinuous attributes convert without loss. Cells are right-handed, as VTK's filters assume: a
 * left-handed patch (negative signed volume) becomes the cell of the same volume with its first
 * parametric direction reversed (see CellLayout).
 *
 * Reading accepts VTK_BEZIER_HEXAHEDRON (and linear VTK_HEXAHEDRON as degree 1) as volumes and
 * VTK_BEZIER_QUADRILATERAL (and VTK_QUAD) as surfaces, whose HigherOrderDegrees' third
 * component is not read. Every
 * single-component point array other than the weights becomes an attribute. Problems are
 * reported as one sentence naming the cell and the problem; missing or inactive weight and
 * degree arrays are reported as warnings, as VTK would otherwise drop them without a word;
 * so are left-handed (inside-out) cells, read as they are.
 */
#ifndef vtkIGABezierHexahedra_h
#define vtkIGABezierHexahedra_h

#include "IGAViewFiltersModule.h" // for export macro
#include "iga/Datasets.h"         // for VolumeSet
#include "vtkSmartPointer.h"      // for return value

#include <functional> // for the cell source
#include <string>
#include <vector>

class vtkDataArray;
class vtkUnstructuredGrid;

class IGAVIEWFILTERS_EXPORT vtkIGABezierHexahedra
{
public:
  /// How ToUnstructuredGrid lays out the cells.
  enum class CellLayout
  {
    /// For VTK's filters: right-handed cells, and no degree array when every cell has one
    /// degree in all directions (VTK infers it from the point count). VTK 9.2's Contour and
    /// Clip of higher-order cells read each cell's data at the input cell id from a copy that
    /// holds only that cell's sub-cells (vtkHigherOrderHexahedron::Contour passes `cellId` to
    /// its linear approximations with `ApproxCD`), out of bounds and, for large grids, into a
    /// crash; a grid without cell arrays is safe from it.
    ForVTK,
    /// The patches as given, with the degree array (NURBS elements that carry cell data of
    /// their own and are oriented patch by patch).
    AsGiven,
  };

  /// Patches (standard layout, every attribute named) to a grid of Bézier hexahedra.
  static vtkSmartPointer<vtkUnstructuredGrid> ToUnstructuredGrid(
    const iga::VolumeSet<double>& set, CellLayout layout = CellLayout::ForVTK);

  /// The same for cells made one at a time, so that only the grid and one cell are held:
  /// `cell(c)` gives cell c (valid until the next call; called for c = 0, 1, ... in order),
  /// `pointCount` their points in all.
  static vtkSmartPointer<vtkUnstructuredGrid> ToUnstructuredGrid(vtkIdType cellCount,
    vtkIdType pointCount, const std::vector<std::string>& attributeNames,
    const std::function<const iga::BezierVolume<double>&(vtkIdType)>& cell, CellLayout layout);

  /// Surfaces (standard layout, every attribute named) to a grid of Bézier quadrilaterals.
  static vtkSmartPointer<vtkUnstructuredGrid> ToUnstructuredGrid(
    const iga::SurfaceSet<double>& set);

  /// Appends a rational Bézier surface (standard layout) as a VTK_BEZIER_QUADRILATERAL cell:
  /// its points, weights (the grid's RationalWeights), attribute channels (into `attributes`,
  /// in order) and degrees (the grid's HigherOrderDegrees, third component 0). Returns its id.
  static vtkIdType AppendQuadrilateral(vtkUnstructuredGrid* grid,
    const iga::PatchView<const double, 2>& surface, const std::vector<vtkDataArray*>& attributes);

  /// A grid's cells as patches: its hexahedra as volumes, its quadrilaterals as surfaces, each
  /// with the id of the cell it came from, all with every attribute (volumes.attributeNames).
  struct Patches
  {
    iga::VolumeSet<double> volumes;
    std::vector<iga::BezierSurface<double>> surfaces;
    std::vector<vtkIdType> volumeCells;
    std::vector<vtkIdType> surfaceCells;
  };

  /// Grid to patches (hexahedra and quadrilaterals). Returns false and sets `error` when the
  /// grid cannot be converted; appends non-fatal notes to `warnings`.
  static bool FromUnstructuredGrid(vtkUnstructuredGrid* grid, Patches& patches, std::string& error,
    std::vector<std::string>& warnings);

  /// The same for a grid of hexahedra only: a quadrilateral is an error.
  static bool FromUnstructuredGrid(vtkUnstructuredGrid* grid, iga::VolumeSet<double>& set,
    std::string& error, std::vector<std::string>& warnings);
};

#endif

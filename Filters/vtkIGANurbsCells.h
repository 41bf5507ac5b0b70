/**
 * @class   vtkIGANurbsCells
 * @brief   The NURBS volumes behind a grid's Bézier cells, for engines that take NURBS nets.
 *
 * A grid written by vtkIGANurbsData (readers, sources) carries the NURBS description of the
 * volumes its Bézier cells were extracted from. Collect() rebuilds those volumes and accepts
 * them only where the engine would take their nets (checkNurbsVolumes) and their elements are
 * exactly the grid's cells: the same count, degrees and attributes, and coefficients equal to
 * 1e-9 of each cell's largest (the cells went through Euclidean points and weights). A filter that
 * moved the points or dropped cells but passed the field data on, or an MPI rank holding part of
 * the cells, leaves the cells the only form.
 *
 * The extraction operators keep a version that changes only with the knots, degrees and net
 * sizes: a new time step that moves the nets keeps it, so an engine holding the operators on a
 * GPU sends only the nets.
 */
#ifndef vtkIGANurbsCells_h
#define vtkIGANurbsCells_h

#include "IGAViewFiltersModule.h" // for export macro
#include "iga/BSpline.h"          // for BezierExtraction
#include "iga/Datasets.h"         // for VolumeSet
#include "iga/sst/NurbsVolumes.h" // for NurbsVolumes

#include <cstdint> // for versions
#include <memory>  // for shared_ptr
#include <vector>  // for nets

class vtkDataObject;

struct IGAVIEWFILTERS_EXPORT vtkIGANurbsCells
{
  std::vector<std::shared_ptr<const iga::BezierExtraction<double, 3>>> Extractions;
  std::vector<double> ExtractionKey; ///< degrees, net sizes and knots the operators belong to
  uint64_t ExtractionVersion = 0;
  std::vector<std::vector<double>> Nets; ///< as the input has them
  int Channels = 0;

  /// Fills this from `input` when it is one grid carrying a NURBS description whose volumes'
  /// elements are exactly `cells` (the grid's cells, in order); false, and this not to be used,
  /// for anything else.
  bool Collect(vtkDataObject* input, const iga::VolumeSet<double>& cells);

  /// The volumes as the engine takes them, with these nets or `nets` (the same sizes) instead.
  iga::sst::NurbsVolumes Volumes(const std::vector<std::vector<double>>* nets = nullptr) const;
};

#endif

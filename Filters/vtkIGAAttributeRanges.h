/**
 * @class   vtkIGAAttributeRanges
 * @brief   The ranges a Bézier grid's attributes take, cached where VTK and ParaView read ranges.
 *
 * A point array of a grid of Bézier cells holds control values, whose range passes the range
 * the field takes over the cells where weights or degrees let it (the unit sphere's x has
 * control values up to 1.28; the Marsden sphere's f = r^2 - 1 takes -1 .. 5.75, its control
 * values reach -7.75). Attach() finds each one-component point array's range over the grid's
 * hexahedra and quadrilaterals (iga::attributeExtremes, to 1e-5 of its spread) and stores it as
 * the array's cached range and finite range (vtkDataArray::COMPONENT_RANGE under PER_COMPONENT
 * and PER_FINITE_COMPONENT), which GetRange and GetFiniteRange return until the array is
 * modified. Where the subdivision's budget runs out first (iga::attributeExtremes' `complete`),
 * the array keeps its control values' range, with a warning. ParaView's data information, colour
 * maps and the IGA representations' default isovalue (the range's middle) then take the field's
 * range. The IGAView readers and sources attach it to what they put out; VTK's own readers do
 * not (a .vtu opened with ParaView's XML reader shows the control values' range).
 *
 * Multi-component arrays keep their control values' range: their magnitude's range would need a
 * search of its own.
 */
#ifndef vtkIGAAttributeRanges_h
#define vtkIGAAttributeRanges_h

#include "IGAViewFiltersModule.h" // for export macro
#include "vtkObject.h"

class vtkUnstructuredGrid;

#ifndef __VTK_WRAP__
#include <string> // for attribute names
#include <vector> // for attribute names
namespace iga
{
namespace sst
{
class Scene;
}
}
#endif

class IGAVIEWFILTERS_EXPORT vtkIGAAttributeRanges : public vtkObject
{
public:
  static vtkIGAAttributeRanges* New();
  vtkTypeMacro(vtkIGAAttributeRanges, vtkObject);

  /// Caches the field's range in each one-component point array of `grid` that is one of its
  /// Bézier cells' attributes. Returns the number of arrays given a range; 0 for a grid that is
  /// not one of Bézier cells (nothing is changed then).
  static int Attach(vtkUnstructuredGrid* grid);

#ifndef __VTK_WRAP__
  /// The same from the patches the grid was made of, whose attribute k (channel
  /// kFirstAttributeChannel + k) is the grid's point array names[k]: for the readers and
  /// sources that hold them, so that the grid is not read back.
  static int Attach(vtkUnstructuredGrid* grid, const iga::sst::Scene& patches,
    const std::vector<std::string>& names);
#endif

protected:
  vtkIGAAttributeRanges() = default;
  ~vtkIGAAttributeRanges() override = default;

private:
  vtkIGAAttributeRanges(const vtkIGAAttributeRanges&) = delete;
  void operator=(const vtkIGAAttributeRanges&) = delete;
};

#endif

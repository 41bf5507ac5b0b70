#include "vtkIGAAttributeRanges.h"

#include "vtkDataArray.h"
#include "vtkIGABezierHexahedra.h"
#include "vtkInformation.h"
#include "vtkInformationInformationVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkUnstructuredGrid.h"

#include "iga/AttributeRange.h"
#include "iga/sst/Engine.h"

#include <string>
#include <vector>

vtkStandardNewMacro(vtkIGAAttributeRanges);

namespace
{
/// Stores `range` as the one-component array's cached range, plain and finite (VTK reads a
/// scalar's norm range as its component's).
void cacheRange(vtkDataArray* array, const double range[2])
{
  vtkInformation* info = array->GetInformation();
  for (vtkInformationInformationVectorKey* key :
    { vtkAbstractArray::PER_COMPONENT(), vtkAbstractArray::PER_FINITE_COMPONENT() })
  {
    vtkNew<vtkInformationVector> components;
    components->SetNumberOfInformationObjects(1);
    components->GetInformationObject(0)->Set(vtkDataArray::COMPONENT_RANGE(), range, 2);
    info->Set(key, components);
  }
}
}

int vtkIGAAttributeRanges::Attach(vtkUnstructuredGrid* grid)
{
  vtkIGABezierHexahedra::Patches patches;
  std::string error;
  std::vector<std::string> warnings;
  if (!grid || grid->GetNumberOfCells() == 0 ||
      !vtkIGABezierHexahedra::FromUnstructuredGrid(grid, patches, error, warnings))
  {
    return 0;
  }
  return Attach(grid, iga::sst::Scene(patches.volumes.patches, patches.surfaces),
    patches.volumes.attributeNames);
}

int vtkIGAAttributeRanges::Attach(
  vtkUnstructuredGrid* grid, const iga::sst::Scene& scene, const std::vector<std::string>& names)
{
  int attached = 0;
  for (size_t k = 0; k < names.size(); ++k)
  {
    vtkDataArray* array = grid->GetPointData()->GetArray(names[k].c_str());
    if (!array || array->GetNumberOfComponents() != 1)
    {
      continue;
    }
    const auto extremes = iga::attributeExtremes<double, 3>(
      long(scene.size()), [&](long p) { return scene[size_t(p)]; },
      iga::kFirstAttributeChannel + int(k));
    if (!extremes.complete)
    {
      vtkWarningWithObjectMacro(array, << "the range of '" << names[k]
                                       << "' stays its control values': its subdivision budget "
                                          "ran out before 1e-5 of the spread");
    }
    else if (!extremes.empty())
    {
      const double range[2] = { extremes.min.value, extremes.max.value };
      cacheRange(array, range);
      ++attached;
    }
  }
  return attached;
}

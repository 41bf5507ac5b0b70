#include "vtkIGANurbsCells.h"

#include "vtkIGANurbsData.h"

#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

namespace
{

/// The degrees, net sizes and knots of the volumes: what their extraction operators depend on.
std::vector<double> extractionKey(const iga::NurbsSet<double>& set)
{
  std::vector<double> key;
  for (const auto& volume : set.volumes)
  {
    for (int d = 0; d < 3; ++d)
    {
      key.push_back(volume.degree[d]);
      key.push_back(volume.netSize[d]);
      key.push_back(double(volume.knots[d].size()));
      key.insert(key.end(), volume.knots[d].begin(), volume.knots[d].end());
    }
  }
  return key;
}

/// Whether a cell equals an extracted element to 1e-9 of the cell's largest coefficient.
bool sameCoefficients(const double* element, const iga::VolumeView<const double>& cell)
{
  double scale = 0;
  for (int v = 0; v < cell.valueCount(); ++v)
  {
    scale = std::max(scale, std::abs(cell.coeffs[v]));
  }
  for (int v = 0; v < cell.valueCount(); ++v)
  {
    if (!(std::abs(element[v] - cell.coeffs[v]) <= 1e-9 * scale))
    {
      return false;
    }
  }
  return true;
}

} // namespace

bool vtkIGANurbsCells::Collect(vtkDataObject* input, const iga::VolumeSet<double>& cells)
{
  auto* grid = vtkUnstructuredGrid::SafeDownCast(input);
  if (!grid || !grid->GetFieldData()->GetAbstractArray("NurbsPatchInfo"))
  {
    return false;
  }
  vtkNew<vtkIGANurbsData> data;
  if (!vtkIGANurbsData::FromUnstructuredGrid(grid, data).empty())
  {
    return false;
  }
  iga::NurbsSet<double> set = data->GetPatches(0);
  if (set.volumes.empty() || !set.surfaces.empty() || set.attributeNames != cells.attributeNames)
  {
    return false;
  }
  std::vector<double> key = extractionKey(set);
  this->Extractions.clear();
  for (size_t v = 0; v < set.volumes.size(); ++v)
  {
    this->Extractions.push_back(data->GetVolumeExtraction(int(v)));
  }
  if (key != this->ExtractionKey || !this->ExtractionVersion)
  {
    static std::atomic<uint64_t> versions{ 0 };
    this->ExtractionKey.swap(key);
    this->ExtractionVersion = ++versions;
  }
  this->Channels = set.channels();
  this->Nets.clear();
  for (auto& volume : set.volumes)
  {
    this->Nets.push_back(std::move(volume.net));
  }
  // Nets the engine would refuse (wrong size, non-finite values, non-positive weights) leave
  // the cells, which the engine takes.
  try
  {
    iga::sst::checkNurbsVolumes(this->Volumes());
  }
  catch (const std::invalid_argument&)
  {
    return false;
  }
  // The elements must be the cells, volume by volume in each extraction's element order.
  size_t first = 0;
  for (size_t v = 0; v < this->Extractions.size(); ++v)
  {
    const iga::BezierExtraction<double, 3>& extraction = *this->Extractions[v];
    const size_t count = size_t(extraction.elementCount());
    int degree[3];
    for (int d = 0; d < 3; ++d)
    {
      degree[d] = extraction.direction(d).degree;
    }
    if (first + count > cells.patches.size())
    {
      return false;
    }
    std::atomic<bool> equal{ true };
    vtkSMPThreadLocal<std::vector<double>> buffers;
    vtkSMPTools::For(0, vtkIdType(count),
      [&](vtkIdType begin, vtkIdType end)
      {
        std::vector<double>& buffer = buffers.Local();
        for (vtkIdType e = begin; e < end && equal; ++e)
        {
          const auto cell = cells.patches[first + size_t(e)].view();
          if (cell.channels != this->Channels || !std::equal(degree, degree + 3, cell.degree))
          {
            equal = false;
            break;
          }
          buffer.resize(3 * size_t(cell.valueCount()));
          extraction.extract(int(e), this->Nets[v].data(), this->Channels, buffer.data(),
            buffer.data() + cell.valueCount());
          if (!sameCoefficients(buffer.data(), cell))
          {
            equal = false; // only ever lowered: threads race to say no
            break;
          }
        }
      });
    if (!equal)
    {
      return false;
    }
    first += count;
  }
  return first == cells.patches.size();
}

iga::sst::NurbsVolumes vtkIGANurbsCells::Volumes(const std::vector<std::vector<double>>* nets) const
{
  iga::sst::NurbsVolumes volumes;
  volumes.channels = this->Channels;
  volumes.extractionVersion = this->ExtractionVersion;
  for (size_t v = 0; v < this->Extractions.size(); ++v)
  {
    volumes.extractions.push_back(this->Extractions[v].get());
    volumes.nets.push_back(nets ? &(*nets)[v] : &this->Nets[v]);
  }
  return volumes;
}

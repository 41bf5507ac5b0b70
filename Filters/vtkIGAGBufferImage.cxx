#include "vtkIGAGBufferImage.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"

#include <limits>

vtkSmartPointer<vtkImageData> vtkIGAGBufferImage::Convert(
  const iga::sst::GBuffer& gbuffer, const float* rgba, const std::string& colorName, bool operands)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(gbuffer.width, gbuffer.height, 1);
  const vtkIdType pixels = vtkIdType(gbuffer.width) * gbuffer.height;
  auto makeArray = [&](const char* name, int components)
  {
    auto array = vtkSmartPointer<vtkFloatArray>::New();
    array->SetName(name);
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(pixels);
    image->GetPointData()->AddArray(array);
    return array;
  };
  const char* colourNames[4] = { "R", "G", "B", "A" };
  vtkSmartPointer<vtkFloatArray> colour[4];
  for (int c = 0; c < 4; ++c)
  {
    colour[c] = makeArray(colourNames[c], 1);
  }
  auto depth = makeArray("Z", 1);
  auto position = makeArray("P", 3);
  auto normal = makeArray("N", 3);
  auto u = makeArray("u", 1), v = makeArray("v", 1), w = makeArray("w", 1);
  vtkSmartPointer<vtkFloatArray> attribute =
    colorName.empty() ? nullptr : makeArray(colorName.c_str(), 1);
  auto makeIndices = [&](const char* name)
  {
    auto array = vtkSmartPointer<vtkIntArray>::New();
    array->SetName(name);
    array->SetNumberOfTuples(pixels);
    image->GetPointData()->AddArray(array);
    return array;
  };
  auto patch = makeIndices("patch");
  vtkSmartPointer<vtkIntArray> operand = operands ? makeIndices("operand") : nullptr;

  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int j = 0; j < gbuffer.height; ++j)
  {
    for (int i = 0; i < gbuffer.width; ++i)
    {
      const vtkIdType p = vtkIdType(j) * gbuffer.width + i;
      for (int c = 0; c < 4; ++c)
      {
        colour[c]->SetValue(p, rgba ? rgba[4 * p + c] : 0.0f);
      }
      const iga::sst::Hit* hit = gbuffer.firstHit(i, j);
      depth->SetValue(p, hit ? float(hit->eyeDepth) : std::numeric_limits<float>::infinity());
      for (int d = 0; d < 3; ++d)
      {
        position->SetComponent(p, d, hit ? float(hit->position[d]) : nan);
        normal->SetComponent(p, d, hit ? float(hit->normal[d]) : nan);
      }
      u->SetValue(p, hit ? float(hit->uvw[0]) : nan);
      v->SetValue(p, hit ? float(hit->uvw[1]) : nan);
      w->SetValue(p, hit ? float(hit->uvw[2]) : nan);
      patch->SetValue(p, hit ? hit->patch : -1);
      if (operand)
      {
        operand->SetValue(p, hit ? hit->isovalue : -1);
      }
      if (attribute)
      {
        attribute->SetValue(p, hit ? float(hit->color) : nan);
      }
    }
  }
  return image;
}

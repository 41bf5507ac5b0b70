#include "vtkIGAIsosurfaceMapper.h"

#include "vtkIGABezierHexahedra.h"
#include "vtkIGANurbsData.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkFieldData.h"
#include "vtkHardwareSelector.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnstructuredGrid.h"
#include "vtk_glew.h"

#include "iga/NurbsSet.h"
#include "iga/sst/Engine.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <set>

vtkStandardNewMacro(vtkIGAIsosurfaceMapper);

namespace
{

/// True the first time this process sees `message`.
bool firstInProcess(const std::string& message)
{
  static std::mutex mutex;
  static std::set<std::string> seen;
  std::lock_guard<std::mutex> lock(mutex);
  return seen.insert(message).second;
}

/// Moves homogeneous control points (4 leading channels of `channels` per point) by a matrix:
/// exact for the rational volume they span, whatever the matrix.
void moveControlPoints(vtkMatrix4x4* matrix, double* points, size_t count, int channels)
{
  for (size_t p = 0; p < count; ++p)
  {
    double* cp = points + p * channels;
    double moved[4];
    matrix->MultiplyPoint(cp, moved);
    std::copy(moved, moved + 4, cp);
  }
}

/// The NURBS form of an input whose cells are the Bézier elements of NURBS volumes.
struct NurbsForm
{
  std::vector<std::shared_ptr<const iga::BezierExtraction<double, 3>>> Extractions;
  std::vector<double> ExtractionKey; ///< degrees, net sizes and knots the operators belong to
  uint64_t ExtractionVersion = 0;
  std::vector<std::vector<double>> Nets;  ///< as the input has them
  std::vector<std::vector<double>> World; ///< moved by the actor's matrix (empty: identity)
  uint64_t WorldVersion = 0;              ///< the data version World was made for
  int Channels = 0;

  iga::sst::NurbsVolumes volumes(bool moved) const
  {
    iga::sst::NurbsVolumes volumes;
    volumes.channels = this->Channels;
    volumes.extractionVersion = this->ExtractionVersion;
    for (size_t v = 0; v < this->Nets.size(); ++v)
    {
      volumes.extractions.push_back(this->Extractions[v].get());
      volumes.nets.push_back(moved ? &this->World[v] : &this->Nets[v]);
    }
    return volumes;
  }
};

/// Fills `form` from a grid that carries a NURBS description (vtkIGANurbsData) of volumes whose
/// extracted elements are exactly `cells` (the grid's cells, in order, same attributes, equal
/// to rounding). False, and `form` not to be used, for anything else.
bool collectNurbs(vtkDataObject* input, const iga::VolumeSet<double>& cells, NurbsForm& form)
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
  // The data's extraction operators; a new version only when the knots change.
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
  form.Extractions.clear();
  for (size_t v = 0; v < set.volumes.size(); ++v)
  {
    form.Extractions.push_back(data->GetVolumeExtraction(int(v)));
  }
  if (key != form.ExtractionKey || !form.ExtractionVersion)
  {
    static std::atomic<uint64_t> versions{ 0 };
    form.ExtractionKey.swap(key);
    form.ExtractionVersion = ++versions;
  }
  form.Channels = set.channels();
  form.Nets.clear();
  for (auto& volume : set.volumes)
  {
    form.Nets.push_back(std::move(volume.net));
  }
  form.World.clear();
  form.WorldVersion = 0;
  // The elements must be the cells: same count, degrees and coefficients to rounding (the
  // cells went through Euclidean points and weights).
  std::vector<iga::BezierVolume<double>> elements;
  try
  {
    elements = iga::sst::extractElements(form.volumes(false));
  }
  catch (const std::invalid_argument&)
  {
    return false;
  }
  if (elements.size() != cells.patches.size())
  {
    return false;
  }
  for (size_t e = 0; e < elements.size(); ++e)
  {
    const auto a = elements[e].view();
    const auto b = cells.patches[e].view();
    if (a.channels != b.channels || a.pointCount() != b.pointCount() ||
        !std::equal(a.degree, a.degree + 3, b.degree))
    {
      return false;
    }
    double scale = 0;
    for (int v = 0; v < b.valueCount(); ++v)
    {
      scale = std::max(scale, std::abs(b.coeffs[v]));
    }
    for (int v = 0; v < b.valueCount(); ++v)
    {
      if (!(std::abs(a.coeffs[v] - b.coeffs[v]) <= 1e-9 * scale))
      {
        return false;
      }
    }
  }
  return true;
}

} // namespace

struct vtkIGAIsosurfaceMapper::Internals
{
  // Data, converted when the input changes; per patch, its block's flat index (composite
  // input) and its cell id in the block, for hardware selection.
  iga::VolumeSet<double> Set;
  std::vector<unsigned int> PatchBlock;
  std::vector<vtkIdType> PatchCell;
  vtkMTimeType SetTime = 0;
  bool SetValid = false;
  // The last frame: what it depended on, and its colour and window depth.
  std::vector<double> FrameKey;
  int Size[2] = { 0, 0 };
  iga::sst::GBuffer GBuffer;
  std::vector<float> Colour; // RGBA, premultiplied, row 0 at the bottom
  std::vector<float> Depth;  // window depth in [0, 1]
  // OpenGL.
  vtkNew<vtkTextureObject> ColourTexture;
  vtkNew<vtkTextureObject> DepthTexture;
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  std::vector<vtkOpenGLRenderPass*> ShaderPasses; ///< the render passes Quad's shader has
  vtkMTimeType ShaderTime = 0;
  vtkTimeStamp UploadTime;
  vtkTimeStamp FrameTime;
  // Where the last frame ran, and why not where it was asked to.
  std::string LastBackend;
  std::string LastNotice;
  // Messages reported since the settings or the input last changed (their keys), and the
  // modification times they were reported for; engine notices reported (never repeated).
  std::set<std::string> Reported;
  vtkMTimeType ReportedFor[2] = { 0, 0 };
  std::set<std::string> Notices;
  // Names the world patches the engine sees (data and actor matrix) for engines that keep a
  // copy (CUDA): this mapper's number in the process, then a count of changes.
  uint64_t DataVersion = 0;
  vtkMTimeType VersionSetTime = 0;
  double VersionMatrix[16] = {};
  /// The data's patches moved by that matrix (empty for the identity).
  std::vector<iga::BezierVolume<double>> World;
  // The NURBS form of the input, collected when a frame is tried on a GPU; valid for the input
  // of NurbsTime.
  NurbsForm Nurbs;
  bool NurbsValid = false;
  vtkMTimeType NurbsTime = 0;
  std::string LastEngineInput;
  uint64_t LastExtractionVersion = 0;
};

vtkIGAIsosurfaceMapper::vtkIGAIsosurfaceMapper()
  : Internal(new Internals)
{
}

vtkIGAIsosurfaceMapper::~vtkIGAIsosurfaceMapper() = default;

void vtkIGAIsosurfaceMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Isovalues:";
  for (double v : this->Isovalues)
  {
    os << " " << v;
  }
  os << "\n" << indent << "SurfaceArrayName: " << this->SurfaceArrayName << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "Backend: " << this->Backend << "\n";
  os << indent << "MaximumSubdivisionDepth: " << this->MaximumSubdivisionDepth << "\n";
  os << indent << "MemoryBudgetMB: " << this->MemoryBudgetMB << "\n";
  os << indent << "LastBackend: " << this->Internal->LastBackend << "\n";
  os << indent << "LastUnresolvedPixels: " << this->LastUnresolvedPixels << "\n";
}

void vtkIGAIsosurfaceMapper::SetInputData(vtkDataObject* input)
{
  this->SetInputDataInternal(0, input);
}

void vtkIGAIsosurfaceMapper::SetNumberOfIsovalues(int count)
{
  if (count >= 0 && size_t(count) != this->Isovalues.size())
  {
    this->Isovalues.resize(size_t(count), 0.0);
    this->Modified();
  }
}

int vtkIGAIsosurfaceMapper::GetNumberOfIsovalues() const
{
  return static_cast<int>(this->Isovalues.size());
}

void vtkIGAIsosurfaceMapper::SetIsovalue(int index, double value)
{
  if (index < 0)
  {
    return;
  }
  if (size_t(index) >= this->Isovalues.size())
  {
    this->Isovalues.resize(size_t(index) + 1, 0.0);
  }
  if (this->Isovalues[index] != value || size_t(index) + 1 == this->Isovalues.size())
  {
    this->Isovalues[index] = value;
    this->Modified();
  }
}

double vtkIGAIsosurfaceMapper::GetIsovalue(int index) const
{
  return index >= 0 && size_t(index) < this->Isovalues.size() ? this->Isovalues[index] : 0.0;
}

void vtkIGAIsosurfaceMapper::SetSurfaceArrayName(const char* name)
{
  const std::string value = name ? name : "";
  if (value != this->SurfaceArrayName)
  {
    this->SurfaceArrayName = value;
    this->Modified();
  }
}

const iga::sst::GBuffer& vtkIGAIsosurfaceMapper::GetLastGBuffer() const
{
  return this->Internal->GBuffer;
}

const std::vector<float>& vtkIGAIsosurfaceMapper::GetLastColours() const
{
  return this->Internal->Colour;
}

const char* vtkIGAIsosurfaceMapper::GetLastBackend() const
{
  return this->Internal->LastBackend.c_str();
}

vtkTypeUInt64 vtkIGAIsosurfaceMapper::GetLastDataVersion() const
{
  return this->Internal->DataVersion;
}

const char* vtkIGAIsosurfaceMapper::GetLastEngineInput() const
{
  return this->Internal->LastEngineInput.c_str();
}

vtkTypeUInt64 vtkIGAIsosurfaceMapper::GetLastExtractionVersion() const
{
  return this->Internal->LastExtractionVersion;
}

const char* vtkIGAIsosurfaceMapper::GetLastNotice() const
{
  return this->Internal->LastNotice.c_str();
}

void vtkIGAIsosurfaceMapper::ReportOnce(
  const std::string& key, const std::string& message, bool error)
{
  if (!this->Internal->Reported.insert(key).second)
  {
    return;
  }
  if (error)
  {
    vtkErrorMacro(<< message);
  }
  else
  {
    vtkWarningMacro(<< message);
  }
}

int vtkIGAIsosurfaceMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

void vtkIGAIsosurfaceMapper::UpdateInput()
{
  // The producer, not this sink: the mapper's own pipeline pass would do nothing but fire
  // progress 0 and 1, which would interleave with the engine's progress.
  int port = 0;
  if (vtkAlgorithm* producer = this->GetInputAlgorithm(0, 0, port))
  {
    producer->Update(port);
  }
}

double* vtkIGAIsosurfaceMapper::GetBounds()
{
  // The control points bound the patches (convex hull): what ResetCamera needs.
  vtkMath::UninitializeBounds(this->Bounds);
  if (!this->GetInputDataObject(0, 0))
  {
    return this->Bounds;
  }
  this->UpdateInput();
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  if (auto* grid = vtkDataSet::SafeDownCast(input))
  {
    grid->GetBounds(this->Bounds);
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    composite->GetBounds(this->Bounds);
  }
  return this->Bounds;
}

void vtkIGAIsosurfaceMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internal->ColourTexture->ReleaseGraphicsResources(window);
  this->Internal->DepthTexture->ReleaseGraphicsResources(window);
  if (this->Internal->Quad)
  {
    this->Internal->Quad->ReleaseGraphicsResources(window);
    this->Internal->Quad.reset();
  }
  this->Internal->UploadTime = vtkTimeStamp();
  // The window is going away: the engine's idle host blocks go too.
  iga::sst::releaseHostCache();
}

namespace
{

/// Converts the input (one grid, or the grid leaves of a composite dataset, which must share
/// their attribute names) to patches; per patch, its block's flat index and cell id.
bool collectPatches(vtkDataObject* input, iga::VolumeSet<double>& set,
  std::vector<unsigned int>& patchBlock, std::vector<vtkIdType>& patchCell, std::string& error,
  std::vector<std::string>& warnings)
{
  set = iga::VolumeSet<double>();
  patchBlock.clear();
  patchCell.clear();
  auto append = [&](vtkUnstructuredGrid* grid, unsigned int block, const std::string& where)
  {
    iga::VolumeSet<double> part;
    if (!vtkIGABezierHexahedra::FromUnstructuredGrid(grid, part, error, warnings))
    {
      error = where + error;
      return false;
    }
    if (!set.patches.empty() && part.attributeNames != set.attributeNames)
    {
      error = where + "its point arrays differ from the first block's";
      return false;
    }
    set.attributeNames = part.attributeNames;
    for (size_t c = 0; c < part.patches.size(); ++c)
    {
      set.patches.push_back(std::move(part.patches[c]));
      patchBlock.push_back(block);
      patchCell.push_back(vtkIdType(c));
    }
    return true;
  };
  if (auto* grid = vtkUnstructuredGrid::SafeDownCast(input))
  {
    return append(grid, 0, "");
  }
  auto* composite = vtkCompositeDataSet::SafeDownCast(input);
  if (!composite)
  {
    error = "the input is neither an unstructured grid nor a composite dataset";
    return false;
  }
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(composite->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* grid = vtkUnstructuredGrid::SafeDownCast(it->GetCurrentDataObject());
    if (grid && grid->GetNumberOfCells() > 0 &&
        !append(grid, it->GetCurrentFlatIndex(),
          "block " + std::to_string(it->GetCurrentFlatIndex()) + ": "))
    {
      return false;
    }
  }
  return true;
}

/// A light as the shading needs it: towards the light (directional) or its position, and the
/// positional light's attenuation and spot cone.
struct ShadingLight
{
  vtkLight* light;
  bool positional;
  double position[3];  ///< positional lights
  double towards[3];   ///< directional lights: unit vector towards the light
  double direction[3]; ///< positional lights: unit direction the light shines along
  double cosCone;
};

/// Phong shading of one hit with VTK's property and the renderer's lights (vtkLight semantics:
/// directional, or positional with attenuation and spot cone).
void shadeHit(const iga::sst::Hit& hit, const double* base, vtkProperty* property,
  const std::vector<ShadingLight>& lights, const double* toEye, float* rgba)
{
  double colour[3];
  const double ambient = property->GetAmbient(), diffuse = property->GetDiffuse(),
               specular = property->GetSpecular(), power = property->GetSpecularPower();
  double specularColour[3];
  property->GetSpecularColor(specularColour);
  for (int c = 0; c < 3; ++c)
  {
    colour[c] = ambient * base[c];
  }
  for (const auto& light : lights)
  {
    double lightColour[3];
    light.light->GetDiffuseColor(lightColour);
    double intensity = light.light->GetIntensity();
    double L[3] = { light.towards[0], light.towards[1], light.towards[2] };
    if (light.positional)
    {
      double distance2 = 0;
      for (int d = 0; d < 3; ++d)
      {
        L[d] = light.position[d] - hit.position[d];
        distance2 += L[d] * L[d];
      }
      iga::normalize3(L);
      const double* a = light.light->GetAttenuationValues();
      const double distance = std::sqrt(distance2);
      intensity /= std::max(1e-12, a[0] + a[1] * distance + a[2] * distance2);
      if (light.cosCone > -1)
      {
        const double spot = -iga::dot3(L, light.direction);
        intensity *= spot < light.cosCone ? 0.0 : std::pow(spot, light.light->GetExponent());
      }
    }
    const double ndotl = std::max(0.0, iga::dot3(hit.normal, L));
    double halfway[3] = { L[0] + toEye[0], L[1] + toEye[1], L[2] + toEye[2] };
    iga::normalize3(halfway);
    const double ndoth = std::max(0.0, iga::dot3(hit.normal, halfway));
    const double shine = ndotl > 0 ? std::pow(ndoth, power) : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      colour[c] += intensity * lightColour[c] *
                   (diffuse * ndotl * base[c] + specular * shine * specularColour[c]);
    }
  }
  const double opacity = property->GetOpacity();
  for (int c = 0; c < 3; ++c)
  {
    rgba[c] = float(std::min(1.0, colour[c]) * opacity);
  }
  rgba[3] = float(opacity);
}

/// The colour VTK's hardware selector expects for a 24-bit id (vtkHardwareSelector::Convert).
void selectionColour(vtkIdType id, float* rgba)
{
  vtkHardwareSelector::Convert(id, rgba);
  rgba[3] = 1.0f;
}

} // namespace

void vtkIGAIsosurfaceMapper::Render(vtkRenderer* renderer, vtkActor* actor)
{
  Internals& in = *this->Internal;
  if (!this->GetInputDataObject(0, 0) || this->Isovalues.empty())
  {
    return;
  }
  this->UpdateInput();
  vtkDataObject* input = this->GetInputDataObject(0, 0);

  // Patches, when the data changed.
  if (input->GetMTime() > in.SetTime || !in.SetTime)
  {
    std::string error;
    std::vector<std::string> warnings;
    in.SetValid = collectPatches(input, in.Set, in.PatchBlock, in.PatchCell, error, warnings);
    in.SetTime = input->GetMTime();
    for (const auto& warning : warnings)
    {
      vtkWarningMacro(<< warning);
    }
    if (!in.SetValid)
    {
      vtkErrorMacro(<< "cannot draw the input: " << error);
    }
  }
  if (!in.SetValid)
  {
    return;
  }
  // Messages are reported once until the settings (the mapper's own, not the lookup table's)
  // or the input change.
  const vtkMTimeType reportFor[2] = { this->vtkAbstractMapper::GetMTime(), input->GetMTime() };
  if (reportFor[0] != in.ReportedFor[0] || reportFor[1] != in.ReportedFor[1])
  {
    in.Reported.clear();
    std::copy(reportFor, reportFor + 2, in.ReportedFor);
  }
  const auto& names = in.Set.attributeNames;
  auto indexOf = [&](const std::string& name)
  { return int(std::find(names.begin(), names.end(), name) - names.begin()); };
  const int surfaceAttribute = this->SurfaceArrayName.empty() ? 0 : indexOf(this->SurfaceArrayName);
  if (names.empty() || surfaceAttribute >= int(names.size()))
  {
    this->ReportOnce("surface array",
      "no point array named '" + this->SurfaceArrayName + "' to draw isosurfaces of", true);
    in.FrameKey.clear();
    return;
  }

  int width, height, origin[2];
  renderer->GetTiledSizeAndOrigin(&width, &height, &origin[0], &origin[1]);
  if (width < 1 || height < 1)
  {
    return;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkProperty* property = actor->GetProperty();
  vtkScalarsToColors* lut = this->GetLookupTable();

  // Recompute only when something the frame depends on changed: modification times of the
  // objects owned here, values of those VTK touches every render (camera, matrix, lights).
  vtkMatrix4x4* worldToClip =
    camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1, 1);
  std::vector<double> key = { double(this->GetMTime()), double(input->GetMTime()),
    double(property->GetMTime()), double(lut->GetMTime()), double(width), double(height),
    double(this->Backend), double(this->MaximumSubdivisionDepth), double(this->MemoryBudgetMB),
    double(this->NumberOfThreads) };
  key.insert(key.end(), worldToClip->GetData(), worldToClip->GetData() + 16);
  key.insert(key.end(), actor->GetMatrix()->GetData(), actor->GetMatrix()->GetData() + 16);
  double eye[3];
  camera->GetPosition(eye);
  key.insert(key.end(), eye, eye + 3);
  vtkLightCollection* lightCollection = renderer->GetLights();
  std::vector<ShadingLight> lights;
  vtkCollectionSimpleIterator it;
  lightCollection->InitTraversal(it);
  while (vtkLight* light = lightCollection->GetNextLight(it))
  {
    if (light->GetSwitch() && light->GetIntensity() > 0)
    {
      ShadingLight shading{ light, light->GetPositional() != 0, {}, {}, {}, -2 };
      double focal[3], colour[3];
      light->GetTransformedPosition(shading.position);
      light->GetTransformedFocalPoint(focal);
      light->GetDiffuseColor(colour);
      for (int d = 0; d < 3; ++d)
      {
        shading.towards[d] = shading.position[d] - focal[d];
        shading.direction[d] = -shading.towards[d];
      }
      iga::normalize3(shading.towards);
      iga::normalize3(shading.direction);
      if (shading.positional && light->GetConeAngle() < 90)
      {
        shading.cosCone = std::cos(vtkMath::RadiansFromDegrees(light->GetConeAngle()));
      }
      lights.push_back(shading);
      key.insert(key.end(), shading.position, shading.position + 3);
      key.insert(key.end(), focal, focal + 3);
      key.insert(key.end(), colour, colour + 3);
      key.insert(key.end(), light->GetAttenuationValues(), light->GetAttenuationValues() + 3);
      key.insert(key.end(), { light->GetIntensity(), double(shading.positional),
                              light->GetConeAngle(), light->GetExponent() });
    }
  }
  // Clipping planes (world coordinates, as vtkOpenGLPolyDataMapper takes them).
  std::vector<std::array<double, 4>> clipPlanes(size_t(this->GetNumberOfClippingPlanes()));
  vtkNew<vtkMatrix4x4> identity;
  for (size_t k = 0; k < clipPlanes.size(); ++k)
  {
    this->GetClippingPlaneInDataCoords(identity, int(k), clipPlanes[k].data());
    key.insert(key.end(), clipPlanes[k].begin(), clipPlanes[k].end());
  }
  // VTK recomputes the camera's matrices every render with changes at single-precision level
  // (1e-8 relative, 1e-5 of a pixel); those cannot change the image.
  const bool sameFrame =
    key.size() == in.FrameKey.size() &&
    std::equal(key.begin(), key.end(), in.FrameKey.begin(),
      [](double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(a)); });
  if (!sameFrame)
  {

    in.FrameKey = key;
    // Patches in world space, made again only when the data or the actor's matrix change (a
    // new data version): the matrix acts linearly on homogeneous control points, exactly,
    // whatever the matrix.
    vtkMatrix4x4* matrix = actor->GetMatrix();
    if (!in.DataVersion || in.VersionSetTime != in.SetTime ||
        !std::equal(in.VersionMatrix, in.VersionMatrix + 16, matrix->GetData()))
    {
      static std::atomic<uint64_t> mappers{ 0 };
      const uint64_t mapper = in.DataVersion ? in.DataVersion >> 40 : ++mappers;
      const uint64_t changes = in.DataVersion ? (in.DataVersion & ((uint64_t(1) << 40) - 1)) : 0;
      in.DataVersion = (mapper << 40) | (changes + 1);
      in.VersionSetTime = in.SetTime;
      std::copy(matrix->GetData(), matrix->GetData() + 16, in.VersionMatrix);
      // The identity (the usual case) needs no copy.
      in.World.clear();
      if (!matrix->IsIdentity())
      {
        in.World = in.Set.patches;
      }
      for (auto& patch : in.World)
      {
        const auto view = patch.view();
        moveControlPoints(matrix, view.coeffs, size_t(view.pointCount()), view.channels);
      }
    }
    const std::vector<iga::BezierVolume<double>>& world =
      matrix->IsIdentity() ? in.Set.patches : in.World;

    iga::sst::View view;
    for (int i = 0; i < 4; ++i)
    {
      for (int j = 0; j < 4; ++j)
      {
        view.worldToClip.m[i][j] = worldToClip->GetElement(i, j);
      }
    }
    camera->GetPosition(view.eye);
    camera->GetDirectionOfProjection(view.forward);
    view.parallel = camera->GetParallelProjection() != 0;
    view.pixelFootprint =
      view.parallel
        ? 2 * camera->GetParallelScale() / height
        : 2 * std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2) / height;

    iga::sst::Settings settings;
    settings.width = width;
    settings.height = height;
    settings.threads = this->NumberOfThreads;
    settings.isovalues = this->Isovalues;
    settings.clipPlanes = clipPlanes;
    settings.surfaceAttribute = surfaceAttribute;
    const bool byScalars = this->ScalarVisibility && this->ArrayName && *this->ArrayName &&
                           indexOf(this->ArrayName) < int(names.size());
    settings.colorAttribute = byScalars ? indexOf(this->ArrayName) : -1;
    settings.dataVersion = in.DataVersion;
    settings.maxSubdivisionDepth = this->MaximumSubdivisionDepth;
    settings.memoryBudgetBytes = size_t(this->MemoryBudgetMB) << 20;
    settings.backend = this->Backend == BACKEND_CPU    ? iga::sst::Backend::Cpu
                       : this->Backend == BACKEND_CUDA ? iga::sst::Backend::Cuda
                                                       : iga::sst::Backend::Automatic;
    // Progress after every subdivision round (on this thread): the share of the most (pixel,
    // sub-patch) pairs seen in this frame that is done, never decreasing, below 1 until the
    // frame is over.
    double mostPairs = 0, progress = 0;
    settings.progress = [this, &mostPairs, &progress](int, size_t pairsLeft)
    {
      mostPairs = std::max(mostPairs, double(pairsLeft));
      const double done = mostPairs > 0 ? 1.0 - double(pairsLeft) / mostPairs : 0.0;
      progress = std::max(progress, std::min(done, 0.99));
      this->UpdateProgress(progress);
    };

    iga::sst::GBuffer& gbuffer = in.GBuffer;
    this->UpdateProgress(0.0);
    try
    {
      // A GPU takes NURBS volumes as their nets (elements extracted there), checked once per
      // input; CPU threads take the cells the mapper already has.
      const bool gpu = iga::sst::triesGpu(settings.backend);
      if (gpu && in.NurbsTime != in.SetTime)
      {
        in.NurbsValid = collectNurbs(input, in.Set, in.Nurbs);
        in.NurbsTime = in.SetTime;
      }
      const bool nurbs = gpu && in.NurbsValid;
      if (nurbs && !matrix->IsIdentity() && in.Nurbs.WorldVersion != in.DataVersion)
      {
        in.Nurbs.World = in.Nurbs.Nets;
        for (auto& net : in.Nurbs.World)
        {
          moveControlPoints(matrix, net.data(), net.size() / in.Nurbs.Channels, in.Nurbs.Channels);
        }
        in.Nurbs.WorldVersion = in.DataVersion;
      }
      in.LastEngineInput = nurbs ? "NURBS volumes" : "Bezier cells";
      in.LastExtractionVersion = nurbs ? in.Nurbs.ExtractionVersion : 0;
      const auto report = nurbs ? iga::sst::render(in.Nurbs.volumes(!matrix->IsIdentity()), view,
                                    settings, iga::sst::Method::SharedSubdivisionTree, gbuffer)
                                : iga::sst::render(world, view, settings,
                                    iga::sst::Method::SharedSubdivisionTree, gbuffer);
      this->UpdateProgress(1.0);
      this->LastEngineTime = report.msTotal;
      this->LastUnresolvedPixels = vtkIdType(report.unresolvedPixels);
      in.LastBackend = report.backend;
      in.LastNotice = report.notice;
      if (!report.notice.empty() && in.Notices.insert(report.notice).second)
      {
        // A warning when CUDA was asked for (here or by IGAVIEW_BACKEND) or failed; the
        // automatic choice of CPU threads is only worth a plain message.
        const bool asked = this->Backend == BACKEND_CUDA ||
                           report.notice.rfind("CUDA asked for", 0) == 0 ||
                           report.notice.rfind("CUDA frame failed", 0) == 0;
        if (asked)
        {
          vtkWarningMacro(<< report.notice);
        }
        else if (firstInProcess(report.notice))
        {
          // Once per process: every mapper of a session without a GPU would say the same.
          vtkOutputWindowDisplayText(
            (std::string(this->GetClassName()) + ": " + report.notice + "\n").c_str());
        }
      }
      if (report.unresolvedPixels > 0)
      {
        // Once per cap hit, whatever the count (it changes with every camera move). The
        // report counts the (pixel, sub-patch) pairs each cap gave up.
        const bool depth = report.unresolvedAtDepthCap > 0, budget = report.unresolvedAtBudget > 0;
        std::string caps;
        if (depth)
        {
          caps += " at the subdivision depth cap (MaximumSubdivisionDepth " +
                  std::to_string(this->MaximumSubdivisionDepth) + ": " +
                  std::to_string(report.unresolvedAtDepthCap) + " pixel/sub-patch pairs given up)";
        }
        if (budget)
        {
          caps += std::string(depth ? " and" : "") + " at the memory budget (MemoryBudgetMB " +
                  std::to_string(this->MemoryBudgetMB) + ": " +
                  std::to_string(report.unresolvedAtBudget) + " pairs given up)";
        }
        this->ReportOnce(
          std::string("unresolved") + (depth ? " depth" : "") + (budget ? " budget" : ""),
          std::to_string(report.unresolvedPixels) + " pixels left unresolved" + caps +
            "; not reported again until the settings or the input change",
          false);
      }
    }
    catch (const std::exception& e)
    {
      this->UpdateProgress(1.0);
      this->ReportOnce(std::string("engine: ") + e.what(), e.what(), true);
      in.FrameKey.clear();
      return;
    }

    // vtkMapper's rule (vtkOpenGLPolyDataMapper's): the table's own range when asked to.
    if (byScalars && !this->UseLookupTableScalarRange)
    {
      lut->SetRange(this->ScalarRange);
    }
    double baseColour[3];
    property->GetDiffuseColor(baseColour);
    in.Size[0] = width;
    in.Size[1] = height;
    in.Colour.assign(size_t(width) * height * 4, 0.0f);
    in.Depth.assign(size_t(width) * height, 1.0f);
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        const iga::sst::Hit* hit = gbuffer.firstHit(i, j);
        if (!hit)
        {
          continue;
        }
        const size_t p = size_t(j) * width + i;
        double base[3] = { baseColour[0], baseColour[1], baseColour[2] };
        if (byScalars)
        {
          const unsigned char* mapped = lut->MapValue(hit->color);
          for (int c = 0; c < 3; ++c)
          {
            base[c] = mapped[c] / 255.0;
          }
        }
        double toEye[3];
        for (int d = 0; d < 3; ++d)
        {
          toEye[d] = view.parallel ? -view.forward[d] : view.eye[d] - hit->position[d];
        }
        iga::normalize3(toEye);
        shadeHit(*hit, base, property, lights, toEye, &in.Colour[4 * p]);
        in.Depth[p] = float(0.5 * (hit->ndcDepth + 1.0));
      }
    }
    in.FrameTime.Modified();
  }

  // Hardware selection (vtkHardwareSelector, vtkPropPicker): the pass's ids instead of colours,
  // in VTK's encoding (0 is "nothing"): prop, composite block, process or cell (= patch) id + 1.
  // Point ids are not drawn: a pixel of the isosurface is no control point.
  vtkHardwareSelector* selector = renderer->GetSelector();
  std::vector<float> ids;
  if (selector)
  {
    selector->BeginRenderProp();
    const int pass = selector->GetCurrentPass();
    const bool composite = vtkCompositeDataSet::SafeDownCast(input) != nullptr;
    if (!in.PatchCell.empty())
    {
      selector->UpdateMaximumCellId(*std::max_element(in.PatchCell.begin(), in.PatchCell.end()));
    }
    ids.assign(in.Colour.size(), 0.0f);
    for (int j = 0; j < in.Size[1]; ++j)
    {
      for (int i = 0; i < in.Size[0]; ++i)
      {
        const iga::sst::Hit* hit = in.GBuffer.firstHit(i, j);
        float* rgba = &ids[4 * (size_t(j) * in.Size[0] + i)];
        if (!hit)
        {
          continue;
        }
        const vtkIdType cellId = in.PatchCell[hit->patch];
        switch (pass)
        {
          case vtkHardwareSelector::CELL_ID_LOW24:
            selectionColour(cellId & 0xffffff, rgba);
            break;
          case vtkHardwareSelector::CELL_ID_HIGH24:
            selectionColour(cellId >> 24, rgba);
            break;
          case vtkHardwareSelector::POINT_ID_LOW24:
          case vtkHardwareSelector::POINT_ID_HIGH24:
            selectionColour(0, rgba);
            break;
          case vtkHardwareSelector::COMPOSITE_INDEX_PASS:
            selector->RenderCompositeIndex(composite ? in.PatchBlock[hit->patch] : 1);
            VTK_FALLTHROUGH;
          default: // actor and process passes
            std::copy(selector->GetPropColorValue(), selector->GetPropColorValue() + 3, rgba);
            rgba[3] = 1.0f;
        }
      }
    }
  }

  // Draw: upload when the frame changed (or ids were drawn instead), then a full-screen pass
  // with gl_FragDepth.
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    if (selector)
    {
      selector->EndRenderProp();
    }
    return;
  }
  if (selector || in.UploadTime < in.FrameTime || in.ColourTexture->GetContext() != window)
  {
    in.ColourTexture->SetContext(window);
    in.DepthTexture->SetContext(window);
    in.ColourTexture->Create2DFromRaw(
      in.Size[0], in.Size[1], 4, VTK_FLOAT, selector ? ids.data() : in.Colour.data());
    in.DepthTexture->Create2DFromRaw(in.Size[0], in.Size[1], 1, VTK_FLOAT, in.Depth.data());
    for (vtkTextureObject* texture : { in.ColourTexture.Get(), in.DepthTexture.Get() })
    {
      texture->SetMinificationFilter(vtkTextureObject::Nearest);
      texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    }
    in.UploadTime.Modified();
    if (selector)
    {
      in.UploadTime = vtkTimeStamp(); // the colours go back up next time
    }
  }
  // Render passes (order-independent translucency, dual and classic depth peeling) hook into
  // the shader as into vtkOpenGLPolyDataMapper's, through the DepthPeeling markers, at every
  // peel; their depth tests read gl_FragDepth, set before the PreColor hook, and gl_FragCoord.z
  // would be the quad's: it is replaced by the surface's depth igaDepth.
  std::vector<vtkOpenGLRenderPass*> passes;
  vtkMTimeType passTime = 0;
  vtkInformation* keys = actor->GetPropertyKeys();
  if (keys && keys->Has(vtkOpenGLRenderPass::RenderPasses()))
  {
    for (int k = 0; k < keys->Length(vtkOpenGLRenderPass::RenderPasses()); ++k)
    {
      passes.push_back(
        static_cast<vtkOpenGLRenderPass*>(keys->Get(vtkOpenGLRenderPass::RenderPasses(), k)));
      passTime = std::max(passTime, passes.back()->GetShaderStageMTime());
    }
  }
  // VTK 9.2's depth peeling passes copy the opaque depth through a multisample resolve into a
  // 24-bit depth buffer (vtkTextureObject::CopyFromFrameBuffer) that the window's 32-bit one
  // cannot be blitted to; where the driver holds to that (Mesa: GL_INVALID_OPERATION), the copy
  // fails and every translucent fragment, this surface's and polydata's alike, is culled.
  // vtkRenderer asks for SetMultiSamples(0) with depth peeling (ParaView does it): say so.
  if (window->GetMultiSamples() > 0 &&
      std::any_of(passes.begin(), passes.end(),
        [](vtkOpenGLRenderPass* pass)
        { return pass->IsA("vtkDualDepthPeelingPass") || pass->IsA("vtkDepthPeelingPass"); }))
  {
    this->ReportOnce("multisampled depth peeling",
      "depth peeling on a window with " + std::to_string(window->GetMultiSamples()) +
        " multisamples: VTK 9.2 may draw no translucent geometry at all there (this surface "
        "included); call SetMultiSamples(0) on the render window, as vtkRenderer's "
        "UseDepthPeeling requires",
      false);
  }
  if (!in.Quad || passes != in.ShaderPasses || passTime > in.ShaderTime)
  {
    std::string vertex = vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader();
    std::string geometry;
    std::string fragment = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
    vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Decl",
      "uniform sampler2D colourTexture;\n"
      "uniform sampler2D depthTexture;\n"
      "float igaDepth;\n"
      "//VTK::DepthPeeling::Dec\n");
    vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Impl",
      "  vec4 colour = texture(colourTexture, texCoord);\n"
      "  if (colour.a <= 0.0) { discard; }\n"
      "  igaDepth = texture(depthTexture, texCoord).r;\n"
      "  gl_FragDepth = igaDepth;\n"
      "  //VTK::DepthPeeling::PreColor\n"
      "  gl_FragData[0] = vec4(colour.rgb / colour.a, colour.a);\n"
      "  //VTK::DepthPeeling::Impl\n");
    for (vtkOpenGLRenderPass* pass : passes)
    {
      pass->PreReplaceShaderValues(vertex, geometry, fragment, this, actor);
    }
    for (vtkOpenGLRenderPass* pass : passes)
    {
      pass->PostReplaceShaderValues(vertex, geometry, fragment, this, actor);
    }
    vtkShaderProgram::Substitute(fragment, "gl_FragCoord.z", "igaDepth", true);
    if (in.Quad)
    {
      in.Quad->ReleaseGraphicsResources(window);
    }
    in.Quad.reset(new vtkOpenGLQuadHelper(window, vertex.c_str(), fragment.c_str(), nullptr));
    in.ShaderPasses = passes;
    in.ShaderTime = passTime;
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(in.Quad->Program);
  }
  if (!in.Quad->Program)
  {
    vtkErrorMacro(<< "the isosurface shader did not compile");
    if (selector)
    {
      selector->EndRenderProp();
    }
    return;
  }
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  if (passes.empty()) // render passes set up the depth state they need
  {
    state->vtkglEnable(GL_DEPTH_TEST);
    state->vtkglDepthFunc(GL_LEQUAL);
  }
  in.ColourTexture->Activate();
  in.DepthTexture->Activate();
  in.Quad->Program->SetUniformi("colourTexture", in.ColourTexture->GetTextureUnit());
  in.Quad->Program->SetUniformi("depthTexture", in.DepthTexture->GetTextureUnit());
  for (vtkOpenGLRenderPass* pass : passes)
  {
    pass->SetShaderParameters(in.Quad->Program, this, actor, in.Quad->VAO);
  }
  in.Quad->Render();
  in.ColourTexture->Deactivate();
  in.DepthTexture->Deactivate();
  if (selector)
  {
    selector->EndRenderProp();
  }
}

#include "vtkIGAIsosurfaceMapper.h"

#include "vtkIGABezierHexahedra.h"
#include "vtkIGADeepEXR.h"
#include "vtkIGANurbsCells.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataObjectTreeIterator.h"
#include "vtkDoubleArray.h"
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
#include "vtkSMPTools.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnstructuredGrid.h"
#include "vtk_glew.h"

#include "iga/AttributeRange.h"
#include "iga/Boundary.h"
#include "iga/Csg.h"
#include "iga/Curvature.h"
#include "iga/NurbsSet.h"
#include "iga/sst/Csg.h"
#include "iga/sst/ElementEdges.h"
#include "iga/sst/Engine.h"
#include "iga/sst/Supersampling.h"

#include "vtkIGAIsosurfaceDeclFS.h"
#include "vtkIGAIsosurfaceImplFS.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <set>
#include <string>

vtkStandardNewMacro(vtkIGAIsosurfaceMapper);

namespace
{
/// Colour names that stand for the isosurface's curvature at the hits.
const char* const kCurvatureMean = "curvature_mean";
const char* const kCurvatureGauss = "curvature_gauss";

/// The mapper's own image: colour (RGBA) and depth as floats, in host memory and as textures.
size_t mapperImageBytes(int width, int height)
{
  return 2 * (4 + 1) * sizeof(float) * size_t(std::max(width, 0)) * size_t(std::max(height, 0));
}

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

} // namespace

/// One layer of a frame's image: the k-th hit of every pixel shaded, as drawn.
struct LayerImage
{
  std::vector<float> Colour; // RGBA, premultiplied, row 0 at the bottom
  std::vector<float> Depth;  // window depth in [0, 1]
  vtkNew<vtkTextureObject> ColourTexture;
  vtkNew<vtkTextureObject> DepthTexture;
};

/// Most layers of a translucent surface drawn (the nearest ones): each takes a full image and a
/// full-screen pass.
constexpr int kMaxLayers = 8;

struct vtkIGAIsosurfaceMapper::Internals
{
  // Data, converted when the input changes: the hexahedra (Set) and the quadrilaterals (Quads);
  // per patch of each, its block's flat index (composite input) and its cell id in the block,
  // for hardware selection; what the topology of the grids is (their cell arrays).
  iga::VolumeSet<double> Set;
  std::vector<unsigned int> PatchBlock;
  std::vector<vtkIdType> PatchCell;
  std::vector<iga::BezierSurface<double>> Quads;
  std::vector<unsigned int> QuadBlock;
  std::vector<vtkIdType> QuadCell;
  std::vector<uint64_t> Topology;
  // The input they came from (its identity only: another data object, even an older one, is
  // converted again) and its modification time.
  const vtkDataObject* SetInput = nullptr;
  vtkMTimeType SetTime = 0;
  bool SetValid = false;
  std::string SetError; ///< why the input cannot be drawn, when it cannot
  // The surfaces drawn (the quadrilaterals, then in DRAW_SURFACES the volumes' boundary faces)
  // for the data of SurfacesTime and the draw mode SurfacesMode; the faces, found again only
  // when the topology changes.
  std::vector<iga::BezierSurface<double>> Surfaces;
  vtkMTimeType SurfacesTime = 0;
  int SurfacesMode = -1;
  std::vector<iga::PatchFace> Faces;
  std::vector<uint64_t> FacesTopology;
  // DRAW_CSG: each block of the input is an input of its own (overlapping blocks are solids of
  // their own), with its boundary faces, for the topology BlockFacesTopology.
  std::vector<std::vector<iga::PatchFace>> BlockFaces;
  std::vector<uint64_t> BlockFacesTopology;
  // The last frame: what it depended on, and its layers (the first hits; behind them, for a
  // translucent surface, the further hits), LayerCount of them in use.
  std::vector<double> FrameKey;
  int Size[2] = { 0, 0 };
  iga::sst::GBuffer GBuffer;
  iga::sst::GBuffer SeedGBuffer; ///< the frame before, with FrameCoherency
  std::vector<std::unique_ptr<LayerImage>> Layers;
  int LayerCount = 0;
  // OpenGL.
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
  std::vector<vtkOpenGLRenderPass*> ShaderPasses; ///< the render passes Quad's shader has
  vtkMTimeType ShaderTime = 0;
  vtkTimeStamp UploadTime;
  vtkTimeStamp FrameTime;
  // Where the last frame ran, and why not where it was asked to.
  std::string LastBackend;
  std::string LastNotice;
  std::string LastRefusal;
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
  /// The data's patches and surfaces moved by that matrix (empty for the identity).
  std::vector<iga::BezierVolume<double>> World;
  std::vector<iga::BezierSurface<double>> SurfaceWorld;
  int VersionMode = -1;
  /// Whether the last frame's engine scene held the volumes (their isosurfaces).
  bool DrewVolumes = false;
  // The NURBS form of the input, collected when the engine prefers it; valid for the input of
  // NurbsTime. Its nets moved by the actor's matrix, for the data version NurbsWorldVersion.
  vtkIGANurbsCells Nurbs;
  bool NurbsValid = false;
  vtkMTimeType NurbsTime = 0;
  std::vector<std::vector<double>> NurbsWorld;
  uint64_t NurbsWorldVersion = 0;
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
  os << indent << "DrawMode: " << this->DrawMode << "\n";
  os << indent << "AllLayers: " << this->AllLayers << "\n";
  os << indent << "CsgExpression: " << this->CsgExpression << "\n";
  os << indent << "Slices: " << this->Slices.size() << "\n";
  os << indent << "CappedClips: " << this->CappedClips.size() << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "Backend: " << this->Backend << "\n";
  os << indent << "Method: " << this->Method << "\n";
  os << indent << "RootFinder: " << iga::rootFinderName(iga::RootFinder(this->RootFinder)) << "\n";
  os << indent << "FrameCoherency: " << this->FrameCoherency << "\n";
  os << indent << "Antialiasing: " << this->Antialiasing << " (threshold "
     << this->AntialiasingThreshold << ")\n";
  os << indent << "MaximumSubdivisionDepth: " << this->MaximumSubdivisionDepth << "\n";
  os << indent << "MemoryBudgetMB: " << this->MemoryBudgetMB << "\n";
  os << indent << "FrameDeadline: " << this->FrameDeadline << "\n";
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

void vtkIGAIsosurfaceMapper::SetCsgExpression(const char* expression)
{
  std::string text = expression ? expression : "";
  if (text.find_first_not_of(" \t\n\r\v\f") == std::string::npos)
  {
    text.clear(); // blank: no solid, only the slices
  }
  if (text == this->CsgExpression)
  {
    return;
  }
  if (!text.empty())
  {
    try
    {
      iga::csg::parseExpression(text);
    }
    catch (const iga::csg::ExpressionError& e)
    {
      vtkErrorMacro(<< "CSG expression \"" << text << "\" refused: " << e.what()
                    << "; the previous one is kept");
      return;
    }
  }
  this->CsgExpression = text;
  this->Modified();
}

namespace
{

/// Resizes a list of planes, the new ones x = 0; whether it changed.
bool resizePlanes(std::vector<std::array<double, 4>>& planes, int count)
{
  if (count < 0 || size_t(count) == planes.size())
  {
    return false;
  }
  planes.resize(size_t(count), { 1, 0, 0, 0 });
  return true;
}

/// Sets plane `index` of a list, growing it as needed; whether it changed.
bool setPlane(
  std::vector<std::array<double, 4>>& planes, int index, double a, double b, double c, double d)
{
  if (index < 0)
  {
    return false;
  }
  const bool grown = size_t(index) >= planes.size() && resizePlanes(planes, index + 1);
  const std::array<double, 4> plane = { a, b, c, d };
  if (planes[size_t(index)] == plane)
  {
    return grown;
  }
  planes[size_t(index)] = plane;
  return true;
}

} // namespace

void vtkIGAIsosurfaceMapper::SetNumberOfSlices(int count)
{
  if (resizePlanes(this->Slices, count))
  {
    this->Modified();
  }
}

void vtkIGAIsosurfaceMapper::SetSlice(int index, double a, double b, double c, double d)
{
  if (setPlane(this->Slices, index, a, b, c, d))
  {
    this->Modified();
  }
}

void vtkIGAIsosurfaceMapper::SetNumberOfCappedClips(int count)
{
  if (resizePlanes(this->CappedClips, count))
  {
    this->Modified();
  }
}

void vtkIGAIsosurfaceMapper::SetCappedClip(int index, double a, double b, double c, double d)
{
  if (a == 0 && b == 0 && c == 0)
  {
    vtkErrorMacro(<< "capped clip " << index << ": the normal (a, b, c) is zero; ignored");
    return;
  }
  if (setPlane(this->CappedClips, index, a, b, c, d))
  {
    this->Modified();
  }
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
  static const std::vector<float> none;
  return this->Internal->Layers.empty() ? none : this->Internal->Layers[0]->Colour;
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

const char* vtkIGAIsosurfaceMapper::GetLastRefusal() const
{
  return this->Internal->LastRefusal.c_str();
}

void vtkIGAIsosurfaceMapper::DrawNothing(const std::string& refusal)
{
  Internals& in = *this->Internal;
  in.LastRefusal = refusal;
  in.FrameKey.clear();
  in.GBuffer = iga::sst::GBuffer();
  this->LastEngineTime = 0;
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

void vtkIGAIsosurfaceMapper::ReportEmptyFrame(const iga::sst::FrameReport& report)
{
  Internals& in = *this->Internal;
  // Pixels left at a cap and constant fields have their own messages.
  if (in.GBuffer.coveredPixels() > 0 || report.constantAttributeRoots > 0 ||
      report.unresolvedPixels > 0)
  {
    return;
  }
  if (this->DrawMode == DRAW_CSG)
  {
    this->ReportOnce("empty solid",
      "nothing drawn: the CSG solid and the slices lie outside the view, the clipping planes cut "
      "them away, or the solid is empty; not reported again until the settings or the input "
      "change",
      false);
    return;
  }
  if (!in.DrewVolumes)
  {
    this->ReportOnce("empty surfaces",
      "nothing drawn: the surfaces lie outside the view or the clipping planes cut them away; "
      "not reported again until the settings or the input change",
      false);
    return;
  }
  const double lo = report.attributeRange[0], hi = report.attributeRange[1];
  std::string isovalues;
  bool inRange = false;
  for (double iso : this->Isovalues)
  {
    char text[32];
    std::snprintf(text, sizeof text, "%s%g", isovalues.empty() ? "" : ", ", iso);
    isovalues += text;
    inRange = inRange || (iso >= lo && iso <= hi);
  }
  char range[96];
  std::snprintf(range, sizeof range, "[%g, %g]", lo, hi);
  const std::string surface = "'" + this->SurfaceArrayName + "' = " + isovalues;
  if (!inRange)
  {
    this->ReportOnce("empty range",
      "nothing to draw: the isosurface " + surface + " lies outside the attribute's range " +
        range + "; not reported again until the settings or the input change",
      false);
  }
  else
  {
    // The range is that of the Bézier coefficients, which may pass the attribute's values.
    this->ReportOnce("empty view",
      "nothing drawn: the isosurface " + surface +
        " lies outside the view, the clipping planes cut it away, or the attribute does not "
        "reach that value; not reported again until the settings or the input change",
      false);
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
  for (const auto& layer : this->Internal->Layers)
  {
    layer->ColourTexture->ReleaseGraphicsResources(window);
    layer->DepthTexture->ReleaseGraphicsResources(window);
  }
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

/// The input's cells as patches: the hexahedra, the quadrilaterals, per patch its block's flat
/// index and cell id, and the grids' topology (their cell arrays and sizes).
struct CollectedPatches
{
  iga::VolumeSet<double> volumes;
  std::vector<unsigned int> volumeBlocks;
  std::vector<vtkIdType> volumeCells;
  std::vector<iga::BezierSurface<double>> surfaces;
  std::vector<unsigned int> surfaceBlocks;
  std::vector<vtkIdType> surfaceCells;
  std::vector<uint64_t> topology;
};

/// Converts the input (one grid, or the grid leaves of a composite dataset, which must share
/// their attribute names) to patches.
bool collectPatches(vtkDataObject* input, CollectedPatches& out, std::string& error,
  std::vector<std::string>& warnings)
{
  out = CollectedPatches();
  bool first = true;
  auto append = [&](vtkUnstructuredGrid* grid, unsigned int block, const std::string& where)
  {
    vtkIGABezierHexahedra::Patches part;
    if (!vtkIGABezierHexahedra::FromUnstructuredGrid(grid, part, error, warnings))
    {
      error = where + error;
      return false;
    }
    if (!first && part.volumes.attributeNames != out.volumes.attributeNames)
    {
      error = where + "its point arrays differ from the first block's";
      return false;
    }
    first = false;
    out.volumes.attributeNames = part.volumes.attributeNames;
    for (size_t c = 0; c < part.volumes.patches.size(); ++c)
    {
      out.volumes.patches.push_back(std::move(part.volumes.patches[c]));
      out.volumeBlocks.push_back(block);
      out.volumeCells.push_back(part.volumeCells[c]);
    }
    for (size_t c = 0; c < part.surfaces.size(); ++c)
    {
      out.surfaces.push_back(std::move(part.surfaces[c]));
      out.surfaceBlocks.push_back(block);
      out.surfaceCells.push_back(part.surfaceCells[c]);
    }
    vtkCellArray* cells = grid->GetCells();
    out.topology.insert(out.topology.end(),
      { uint64_t(block), uint64_t(reinterpret_cast<uintptr_t>(cells)), uint64_t(cells->GetMTime()),
        uint64_t(grid->GetNumberOfCells()), uint64_t(grid->GetNumberOfPoints()) });
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
  glm::dvec3 position;  ///< positional lights
  glm::dvec3 towards;   ///< directional lights: unit vector towards the light
  glm::dvec3 direction; ///< positional lights: unit direction the light shines along
  double cosCone;
};

/// What one light adds to a hit's Phong colour (vtkLight semantics: directional, or positional
/// with attenuation and spot cone).
void addLight(const ShadingLight& light, const iga::sst::Hit& hit, const double* base,
  vtkProperty* property, const glm::dvec3& toEye, double* colour)
{
  double lightColour[3], specularColour[3];
  light.light->GetDiffuseColor(lightColour);
  property->GetSpecularColor(specularColour);
  double intensity = light.light->GetIntensity();
  glm::dvec3 L = light.towards;
  if (light.positional)
  {
    L = light.position - hit.position;
    const double distance2 = glm::dot(L, L), distance = std::sqrt(distance2);
    L = iga::normalizedOrZero(L);
    const double* a = light.light->GetAttenuationValues();
    intensity /= std::max(1e-12, a[0] + a[1] * distance + a[2] * distance2);
    if (light.cosCone > -1)
    {
      const double spot = -glm::dot(L, light.direction);
      intensity *= spot < light.cosCone ? 0.0 : std::pow(spot, light.light->GetExponent());
    }
  }
  const double ndotl = std::max(0.0, glm::dot(hit.normal, L));
  const double ndoth = std::max(0.0, glm::dot(hit.normal, iga::normalizedOrZero(L + toEye)));
  const double shine = ndotl > 0 ? std::pow(ndoth, property->GetSpecularPower()) : 0.0;
  for (int c = 0; c < 3; ++c)
  {
    colour[c] += intensity * lightColour[c] *
                 (property->GetDiffuse() * ndotl * base[c] +
                   property->GetSpecular() * shine * specularColour[c]);
  }
}

/// vtkSMPTools::For over [0, count) on `threads` threads (0: all), on the application's SMP
/// backend, or on VTK's STDThread where that is Sequential (ParaView's VTK's default), as the
/// engine's own threads are.
template<class Fn>
void smpFor(vtkIdType count, int threads, Fn&& fn)
{
  const std::string backend = vtkSMPTools::GetBackend();
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ threads, backend == "Sequential" ? "STDThread" : backend, false },
    [&] { vtkSMPTools::For(0, count, fn); });
}

/// A hit's colour before shading: its colour mapped through the table (`mapped`, RGBA bytes),
/// or without one the property's diffuse colour.
void baseColour(vtkProperty* property, const unsigned char* mapped, double* base)
{
  property->GetDiffuseColor(base);
  for (int c = 0; mapped && c < 3; ++c)
  {
    base[c] = mapped[c] / 255.0;
  }
}

/// Every hit's colour through the table (RGBA bytes, a hit's four at 4 * its index), at once
/// before the rows are shaded side by side: a table's MapValue keeps its answer in the table.
std::vector<unsigned char> mappedColours(vtkScalarsToColors* lut, const iga::sst::GBuffer& gbuffer)
{
  std::vector<unsigned char> mapped(4 * gbuffer.hits.size());
  if (gbuffer.hits.empty())
  {
    return mapped;
  }
  vtkNew<vtkDoubleArray> colours;
  colours->SetNumberOfTuples(vtkIdType(gbuffer.hits.size()));
  for (size_t h = 0; h < gbuffer.hits.size(); ++h)
  {
    colours->SetValue(vtkIdType(h), gbuffer.hits[h].color);
  }
  lut->MapScalarsThroughTable(colours, mapped.data(), VTK_RGBA);
  return mapped;
}

/// Phong shading of one hit with VTK's property and the renderer's lights, seen from `view`.
/// With no light switched on, or lighting off in the property, the hit is unlit: ambient plus
/// diffuse times its colour, as vtkOpenGLPolyDataMapper draws (ParaView's view with its light
/// kit off).
void shadeHit(const iga::sst::Hit& hit, const double* base, vtkProperty* property,
  const std::vector<ShadingLight>& lights, const iga::sst::View& view, float* rgba)
{
  const glm::dvec3 toEye =
    iga::normalizedOrZero(view.parallel ? -view.forward : view.eye - hit.position);
  const bool unlit = lights.empty() || !property->GetLighting();
  const double ambient = property->GetAmbient();
  double colour[3];
  for (int c = 0; c < 3; ++c)
  {
    colour[c] = (unlit ? ambient + property->GetDiffuse() : ambient) * base[c];
  }
  for (size_t k = 0; !unlit && k < lights.size(); ++k)
  {
    addLight(lights[k], hit, base, property, toEye, colour);
  }
  const double opacity = property->GetOpacity();
  for (int c = 0; c < 3; ++c)
  {
    rgba[c] = float(std::min(1.0, colour[c]) * opacity);
  }
  rgba[3] = float(opacity);
}

/// A hit's window depth in [0, 1], as the depth buffer holds it.
float windowDepth(const iga::sst::Hit& hit)
{
  return float(0.5 * (hit.ndcDepth + 1.0));
}

/// The colour VTK's hardware selector expects for a 24-bit id (vtkHardwareSelector::Convert).
void selectionColour(vtkIdType id, float* rgba)
{
  vtkHardwareSelector::Convert(id, rgba);
  rgba[3] = 1.0f;
}

} // namespace

/// What one render of the mapper computes and draws from.
struct vtkIGAIsosurfaceMapper::Frame
{
  vtkDataObject* Input = nullptr;
  int Width = 0, Height = 0;
  double Aspect = 1; ///< of the viewport, as the camera's projection takes it
  std::vector<ShadingLight> Lights;
  /// Everything the frame depends on: modification times of the objects owned here, values
  /// of those VTK touches every render (camera, matrices, lights, clipping planes).
  std::vector<double> Key;
  iga::sst::View View;
  iga::sst::Settings Settings;
  bool ByScalars = false;
  /// Colour by the isosurface's curvature ("curvature_mean", "curvature_gauss"): 0 none,
  /// 1 mean, 2 Gaussian (computed at the hits, not an attribute of the engine's).
  int Curvature = 0;
  bool Translucent = false;           ///< the actor's opacity is below 1: every layer is drawn
  bool Volumes = false;               ///< the hexahedra's isosurfaces are drawn
  bool Identity = true;               ///< the actor's matrix is the identity
  bool Nurbs = false;                 ///< the engine draws the input's NURBS form
  double MostPairs = 0, Progress = 0; ///< of the progress reported during the frame
};

void vtkIGAIsosurfaceMapper::Render(vtkRenderer* renderer, vtkActor* actor)
{
  int size[2], origin[2];
  renderer->GetTiledSizeAndOrigin(&size[0], &size[1], &origin[0], &origin[1]);
  if (this->UpdateFrame(renderer, actor, size, renderer->GetTiledAspectRatio()))
  {
    this->DrawFrame(renderer, actor, this->GetInputDataObject(0, 0));
  }
}

bool vtkIGAIsosurfaceMapper::ComputeImage(
  vtkRenderer* renderer, vtkActor* actor, int width, int height)
{
  const int size[2] = { width, height };
  return height > 0 && this->UpdateFrame(renderer, actor, size, double(width) / height);
}

bool vtkIGAIsosurfaceMapper::UpdateFrame(
  vtkRenderer* renderer, vtkActor* actor, const int size[2], double aspect)
{
  Frame frame;
  frame.Width = size[0];
  frame.Height = size[1];
  frame.Aspect = aspect;
  if (!this->CollectInput(frame) || !this->DescribeFrame(renderer, actor, frame))
  {
    return false;
  }
  this->Internal->LastRefusal.clear();
  if (!this->SameFrame(frame.Key))
  {
    if (!this->ComputeFrame(actor, frame))
    {
      return false;
    }
    this->ShadeFrame(actor, frame);
  }
  return true;
}

bool vtkIGAIsosurfaceMapper::CollectInput(Frame& frame)
{
  Internals& in = *this->Internal;
  if (!this->GetInputDataObject(0, 0))
  {
    return false;
  }
  this->UpdateInput();
  vtkDataObject* input = frame.Input = this->GetInputDataObject(0, 0);
  // Patches, when the data changed.
  if (input != in.SetInput || input->GetMTime() != in.SetTime)
  {
    std::string error;
    std::vector<std::string> warnings;
    CollectedPatches collected;
    in.SetValid = collectPatches(input, collected, error, warnings);
    in.Set = std::move(collected.volumes);
    in.PatchBlock = std::move(collected.volumeBlocks);
    in.PatchCell = std::move(collected.volumeCells);
    in.Quads = std::move(collected.surfaces);
    in.QuadBlock = std::move(collected.surfaceBlocks);
    in.QuadCell = std::move(collected.surfaceCells);
    in.Topology = std::move(collected.topology);
    in.SetInput = input;
    in.SetTime = input->GetMTime();
    for (const auto& warning : warnings)
    {
      vtkWarningMacro(<< warning);
    }
    if (!in.SetValid)
    {
      in.SetError = "cannot draw the input: " + error;
      vtkErrorMacro(<< in.SetError);
    }
  }
  if (!in.SetValid)
  {
    this->DrawNothing(in.SetError);
    return false;
  }
  this->UpdateSurfaces();
  const bool csg =
    this->DrawMode == DRAW_CSG &&
    (!this->CsgExpression.empty() || !this->Slices.empty() || !this->CappedClips.empty());
  frame.Volumes = !in.Set.patches.empty() &&
                  ((this->DrawMode == DRAW_ISOSURFACES && !this->Isovalues.empty()) || csg);
  // Messages are reported once until the settings (the mapper's own, not the lookup table's)
  // or the input change.
  const vtkMTimeType reportFor[2] = { this->vtkAbstractMapper::GetMTime(), input->GetMTime() };
  if (reportFor[0] != in.ReportedFor[0] || reportFor[1] != in.ReportedFor[1])
  {
    in.Reported.clear();
    std::copy(reportFor, reportFor + 2, in.ReportedFor);
  }
  if (csg && in.Set.patches.empty())
  {
    this->ReportOnce("csg without volumes",
      "DRAW_CSG draws solids of hexahedra, and the input has none; not reported again until the "
      "settings or the input change",
      false);
  }
  if (!frame.Volumes && in.Surfaces.empty())
  {
    this->DrawNothing(std::string());
    return false;
  }
  return true;
}

void vtkIGAIsosurfaceMapper::UpdateSurfaces()
{
  Internals& in = *this->Internal;
  if (in.SurfacesTime == in.SetTime && in.SurfacesMode == this->DrawMode)
  {
    return;
  }
  in.SurfacesTime = in.SetTime;
  in.SurfacesMode = this->DrawMode;
  in.Surfaces = this->DrawMode == DRAW_CSG ? std::vector<iga::BezierSurface<double>>() : in.Quads;
  if (this->DrawMode == DRAW_ISOSURFACES)
  {
    return;
  }
  if (this->DrawMode == DRAW_CSG)
  {
    this->UpdateBlockFaces();
    return;
  }
  // Which faces are outer depends on the topology alone: found again only when it changes.
  if (in.FacesTopology != in.Topology || in.Faces.empty())
  {
    in.Faces = iga::boundaryFaces(in.Set.patches);
    in.FacesTopology = in.Topology;
  }
  for (const iga::PatchFace& face : in.Faces)
  {
    in.Surfaces.push_back(
      iga::faceSurface(in.Set.patches[size_t(face.patch)], face.direction, face.side));
  }
}

namespace
{
/// The blocks of the hexahedra as ranges [first, end) of their patches (a composite input's
/// blocks are collected one after the other).
std::vector<std::pair<size_t, size_t>> blockRanges(const std::vector<unsigned int>& blocks)
{
  std::vector<std::pair<size_t, size_t>> ranges;
  for (size_t p = 0; p < blocks.size(); ++p)
  {
    if (ranges.empty() || blocks[p] != blocks[ranges.back().first])
    {
      ranges.emplace_back(p, p);
    }
    ranges.back().second = p + 1;
  }
  return ranges;
}

/// Patches [first, end) of `patches`.
std::vector<iga::BezierVolume<double>> patchRange(
  const std::vector<iga::BezierVolume<double>>& patches, const std::pair<size_t, size_t>& range)
{
  return std::vector<iga::BezierVolume<double>>(
    patches.begin() + long(range.first), patches.begin() + long(range.second));
}
} // namespace

void vtkIGAIsosurfaceMapper::UpdateBlockFaces()
{
  Internals& in = *this->Internal;
  if (in.BlockFacesTopology == in.Topology && !in.BlockFaces.empty())
  {
    return;
  }
  in.BlockFaces.clear();
  for (const auto& range : blockRanges(in.PatchBlock))
  {
    in.BlockFaces.push_back(iga::boundaryFaces(patchRange(in.Set.patches, range)));
  }
  in.BlockFacesTopology = in.Topology;
}

iga::sst::Scene vtkIGAIsosurfaceMapper::EngineScene(bool identity) const
{
  static const std::vector<iga::BezierVolume<double>> noVolumes;
  const Internals& in = *this->Internal;
  const auto& volumes = !in.DrewVolumes ? noVolumes : identity ? in.Set.patches : in.World;
  return iga::sst::Scene(volumes, identity ? in.Surfaces : in.SurfaceWorld);
}

void vtkIGAIsosurfaceMapper::PatchSource(int patch, vtkIdType& cell, unsigned int& block) const
{
  // The engine numbers the volumes drawn, then the quadrilaterals, then the boundary faces.
  const Internals& in = *this->Internal;
  size_t k = size_t(patch);
  const size_t volumes = in.DrewVolumes ? in.Set.patches.size() : 0;
  if (k < volumes)
  {
    cell = in.PatchCell[k];
    block = in.PatchBlock[k];
    return;
  }
  k -= volumes;
  if (k < in.Quads.size())
  {
    cell = in.QuadCell[k];
    block = in.QuadBlock[k];
    return;
  }
  const size_t owner = size_t(in.Faces[k - in.Quads.size()].patch);
  cell = in.PatchCell[owner];
  block = in.PatchBlock[owner];
}

void vtkIGAIsosurfaceMapper::CellParameter(const iga::sst::Hit& hit, double uvw[3]) const
{
  // A boundary face's hit is at (s, t) of the face; its cell is the volume the face bounds.
  const Internals& in = *this->Internal;
  const size_t firstFace = (in.DrewVolumes ? in.Set.patches.size() : 0) + in.Quads.size();
  const size_t k = size_t(hit.patch);
  if (this->DrawMode != DRAW_SURFACES || k < firstFace)
  {
    std::copy(&hit.uvw[0], &hit.uvw[0] + 3, uvw);
    return;
  }
  iga::faceParameterInVolume(in.Faces[k - firstFace], false, hit.uvw[0], hit.uvw[1], uvw);
}

void vtkIGAIsosurfaceMapper::HitAttributes(const iga::sst::Hit& hit, double* values) const
{
  // CSG numbers the volumes alone; the other modes the engine scene's patches (its surfaces
  // carry the volumes' channels).
  const Internals& in = *this->Internal;
  const auto patch = this->DrawMode == DRAW_CSG ? in.Set.patches[size_t(hit.patch)].view()
                                                : this->EngineScene(true)[size_t(hit.patch)];
  std::vector<double> channels(size_t(patch.channels));
  iga::evaluateHomogeneous(patch, &hit.uvw[0], channels.data(), static_cast<double*>(nullptr));
  for (size_t a = 0; a < in.Set.attributeNames.size(); ++a)
  {
    values[a] = channels[iga::kFirstAttributeChannel + a] / channels[iga::kWeightChannel];
  }
}

int vtkIGAIsosurfaceMapper::GetNumberOfAttributes() const
{
  return int(this->Internal->Set.attributeNames.size());
}

const char* vtkIGAIsosurfaceMapper::GetAttributeName(int index) const
{
  const auto& names = this->Internal->Set.attributeNames;
  return index >= 0 && size_t(index) < names.size() ? names[size_t(index)].c_str() : nullptr;
}

bool vtkIGAIsosurfaceMapper::GetAttributeRange(const char* name, double range[2]) const
{
  const Internals& in = *this->Internal;
  const auto& names = in.Set.attributeNames;
  const auto named = name ? std::find(names.begin(), names.end(), name) : names.end();
  if (named == names.end())
  {
    return false;
  }
  const iga::sst::Scene scene(in.Set.patches, in.Quads);
  const auto extremes = iga::attributeExtremes<double, 3>(
    long(scene.size()), [&](long p) { return scene[size_t(p)]; },
    iga::kFirstAttributeChannel + int(named - names.begin()));
  if (extremes.empty())
  {
    return false;
  }
  range[0] = extremes.min.value;
  range[1] = extremes.max.value;
  return true;
}

bool vtkIGAIsosurfaceMapper::WriteDeepEXR(const char* fileName)
{
  std::string error = "no file name given";
  if (!fileName || !vtkIGADeepEXR::Write(this->GetLastGBuffer(), fileName, error))
  {
    vtkErrorMacro(<< "deep OpenEXR: " << error);
    return false;
  }
  return true;
}

vtkIdType vtkIGAIsosurfaceMapper::ProbePixel(
  int x, int y, double position[3], double uvw[3], vtkFieldData* attributes)
{
  const iga::sst::GBuffer& gbuffer = this->Internal->GBuffer;
  if (x < 0 || y < 0 || x >= gbuffer.width || y >= gbuffer.height)
  {
    return -1;
  }
  const iga::sst::Hit* hit = gbuffer.firstHit(x, y);
  if (!hit)
  {
    return -1;
  }
  vtkIdType cell = -1;
  this->PatchSource(hit->patch, cell, this->LastProbedBlock);
  std::copy(&hit->position[0], &hit->position[0] + 3, position);
  this->CellParameter(*hit, uvw);
  if (attributes)
  {
    std::vector<double> values(size_t(this->GetNumberOfAttributes()));
    this->HitAttributes(*hit, values.data());
    attributes->Initialize();
    for (size_t a = 0; a < values.size(); ++a)
    {
      vtkNew<vtkDoubleArray> value;
      value->SetName(this->GetAttributeName(int(a)));
      value->InsertNextValue(values[a]);
      attributes->AddArray(value);
    }
  }
  return cell;
}

bool vtkIGAIsosurfaceMapper::DescribeFrame(vtkRenderer* renderer, vtkActor* actor, Frame& frame)
{
  Internals& in = *this->Internal;
  const auto& names = in.Set.attributeNames;
  auto indexOf = [&](const std::string& name)
  { return int(std::find(names.begin(), names.end(), name) - names.begin()); };
  const int surfaceAttribute = this->SurfaceArrayName.empty() ? 0 : indexOf(this->SurfaceArrayName);
  if (frame.Volumes && this->DrawMode == DRAW_ISOSURFACES &&
      (names.empty() || surfaceAttribute >= int(names.size())))
  {
    const std::string why =
      "no point array named '" + this->SurfaceArrayName + "' to draw isosurfaces of";
    this->ReportOnce("surface array", why, true);
    this->DrawNothing(why);
    return false;
  }
  if (frame.Width < 1 || frame.Height < 1)
  {
    return false;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkMatrix4x4* worldToClip = camera->GetCompositeProjectionTransformMatrix(frame.Aspect, -1, 1);
  frame.Key = { double(this->GetMTime()), double(frame.Input->GetMTime()),
    double(actor->GetProperty()->GetMTime()), double(this->GetLookupTable()->GetMTime()),
    double(frame.Width), double(frame.Height), double(this->Backend),
    double(this->MaximumSubdivisionDepth), double(this->MemoryBudgetMB),
    double(this->NumberOfThreads), this->FrameDeadline, double(this->Method),
    double(this->RootFinder) };
  frame.Key.insert(frame.Key.end(), worldToClip->GetData(), worldToClip->GetData() + 16);
  frame.Key.insert(
    frame.Key.end(), actor->GetMatrix()->GetData(), actor->GetMatrix()->GetData() + 16);
  this->DescribeLights(renderer, frame);

  iga::sst::View& view = frame.View;
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      view.worldToClip[j][i] = worldToClip->GetElement(i, j);
    }
  }
  camera->GetPosition(glm::value_ptr(view.eye));
  frame.Key.insert(frame.Key.end(), glm::value_ptr(view.eye), glm::value_ptr(view.eye) + 3);
  camera->GetDirectionOfProjection(glm::value_ptr(view.forward));
  view.parallel = camera->GetParallelProjection() != 0;
  view.pixelFootprint =
    view.parallel
      ? 2 * camera->GetParallelScale() / frame.Height
      : 2 * std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2) / frame.Height;

  iga::sst::Settings& settings = frame.Settings;
  settings.width = frame.Width;
  settings.height = frame.Height;
  settings.threads = this->NumberOfThreads;
  settings.isovalues = frame.Volumes ? this->Isovalues : std::vector<double>();
  // A translucent surface shows every layer (AllocateLayers), an opaque one its first.
  frame.Translucent = actor->GetProperty()->GetOpacity() < 1.0;
  settings.firstHitOnly = !(frame.Translucent || this->AllLayers);
  // Clipping planes (world coordinates, as vtkOpenGLPolyDataMapper takes them).
  settings.clipPlanes.resize(size_t(this->GetNumberOfClippingPlanes()));
  vtkNew<vtkMatrix4x4> identity;
  for (size_t k = 0; k < settings.clipPlanes.size(); ++k)
  {
    this->GetClippingPlaneInDataCoords(identity, int(k), settings.clipPlanes[k].data());
    frame.Key.insert(frame.Key.end(), settings.clipPlanes[k].begin(), settings.clipPlanes[k].end());
  }
  // Capped clips cut the slices like clipping planes; the solid, cut by them too, keeps its cap
  // on them (ComputeCsgFrame).
  if (this->DrawMode == DRAW_CSG)
  {
    settings.clipPlanes.insert(
      settings.clipPlanes.end(), this->CappedClips.begin(), this->CappedClips.end());
  }
  settings.surfaceAttribute = frame.Volumes ? surfaceAttribute : 0;
  const std::string colourName = this->ArrayName ? this->ArrayName : "";
  frame.Curvature = !this->ScalarVisibility || this->DrawMode != DRAW_ISOSURFACES ? 0
                    : colourName == kCurvatureMean                                ? 1
                    : colourName == kCurvatureGauss                               ? 2
                                                                                  : 0;
  frame.ByScalars = this->ScalarVisibility && !colourName.empty() &&
                    (frame.Curvature > 0 || indexOf(this->ArrayName) < int(names.size()));
  settings.colorAttribute = frame.ByScalars && frame.Curvature == 0 ? indexOf(this->ArrayName) : -1;
  settings.maxSubdivisionDepth = this->MaximumSubdivisionDepth;
  const vtkTypeUInt64 budget = vtkTypeUInt64(this->MemoryBudgetMB) << 20;
  if (vtkIGAIsosurfaceMapper::GetImageBytes(frame.Width, frame.Height) > budget)
  {
    this->ReportImageOverBudget(frame);
    return false;
  }
  settings.memoryBudgetBytes = budget - mapperImageBytes(frame.Width, frame.Height);
  settings.deadlineMs = 1000 * this->FrameDeadline;
  settings.backend = this->Backend == BACKEND_CPU    ? iga::sst::Backend::Cpu
                     : this->Backend == BACKEND_CUDA ? iga::sst::Backend::Cuda
                                                     : iga::sst::Backend::Automatic;
  settings.rootFinder = iga::RootFinder(this->RootFinder);
  // Progress after every subdivision round (on this thread): the share of the most (pixel,
  // sub-patch) pairs seen in this frame that is done, never decreasing, below 1 until the frame
  // is over.
  settings.progress = [this, &frame](int, size_t pairsLeft)
  {
    frame.MostPairs = std::max(frame.MostPairs, double(pairsLeft));
    const double done = frame.MostPairs > 0 ? 1.0 - double(pairsLeft) / frame.MostPairs : 0.0;
    frame.Progress = std::max(frame.Progress, std::min(done, 0.99));
    this->UpdateProgress(frame.Progress);
  };
  return true;
}

vtkTypeUInt64 vtkIGAIsosurfaceMapper::GetImageBytes(int width, int height)
{
  iga::sst::Settings size;
  size.width = width;
  size.height = height;
  return iga::sst::imageBytes(size) + mapperImageBytes(width, height);
}

void vtkIGAIsosurfaceMapper::ReportImageOverBudget(const Frame& frame)
{
  const double needed = vtkIGAIsosurfaceMapper::GetImageBytes(frame.Width, frame.Height);
  char why[256];
  std::snprintf(why, sizeof why,
    "a %dx%d image needs %.0f MiB (%.0f bytes a pixel), more than the memory budget "
    "(MemoryBudgetMB %d): raise it or make the view smaller",
    frame.Width, frame.Height, std::ceil(needed / 1048576.0),
    needed / (double(frame.Width) * frame.Height), this->MemoryBudgetMB);
  this->ReportOnce(
    "image over budget " + std::to_string(frame.Width) + "x" + std::to_string(frame.Height),
    std::string("nothing drawn: ") + why, true);
  this->DrawNothing(why);
}

void vtkIGAIsosurfaceMapper::DescribeLights(vtkRenderer* renderer, Frame& frame)
{
  vtkLightCollection* lightCollection = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lightCollection->InitTraversal(it);
  while (vtkLight* light = lightCollection->GetNextLight(it))
  {
    if (!light->GetSwitch() || light->GetIntensity() <= 0)
    {
      continue;
    }
    ShadingLight shading{ light, light->GetPositional() != 0, {}, {}, {}, -2 };
    glm::dvec3 focal;
    double colour[3];
    light->GetTransformedPosition(glm::value_ptr(shading.position));
    light->GetTransformedFocalPoint(glm::value_ptr(focal));
    light->GetDiffuseColor(colour);
    shading.towards = iga::normalizedOrZero(shading.position - focal);
    shading.direction = -shading.towards;
    if (shading.positional && light->GetConeAngle() < 90)
    {
      shading.cosCone = std::cos(vtkMath::RadiansFromDegrees(light->GetConeAngle()));
    }
    frame.Lights.push_back(shading);
    std::vector<double>& key = frame.Key;
    key.insert(key.end(), glm::value_ptr(shading.position), glm::value_ptr(shading.position) + 3);
    key.insert(key.end(), glm::value_ptr(focal), glm::value_ptr(focal) + 3);
    key.insert(key.end(), colour, colour + 3);
    key.insert(key.end(), light->GetAttenuationValues(), light->GetAttenuationValues() + 3);
    key.insert(key.end(), { light->GetIntensity(), double(shading.positional),
                            light->GetConeAngle(), light->GetExponent() });
  }
}

bool vtkIGAIsosurfaceMapper::SameFrame(const std::vector<double>& key)
{
  // VTK recomputes the camera's matrices every render with changes at single-precision level
  // (1e-8 relative, 1e-5 of a pixel); those cannot change the image.
  std::vector<double>& last = this->Internal->FrameKey;
  const bool same =
    key.size() == last.size() &&
    std::equal(key.begin(), key.end(), last.begin(),
      [](double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(a)); });
  if (!same)
  {
    last = key;
  }
  return same;
}

void vtkIGAIsosurfaceMapper::UpdateDataVersion(vtkMatrix4x4* matrix)
{
  // Patches in world space, made again only when the data, what is drawn of it or the actor's
  // matrix change (a new data version): the matrix acts linearly on homogeneous control
  // points, exactly, whatever the matrix.
  Internals& in = *this->Internal;
  const int mode = 2 * this->DrawMode + (in.DrewVolumes ? 1 : 0);
  if (in.DataVersion && in.VersionSetTime == in.SetTime && in.VersionMode == mode &&
      std::equal(in.VersionMatrix, in.VersionMatrix + 16, matrix->GetData()))
  {
    return;
  }
  in.VersionMode = mode;
  static std::atomic<uint64_t> mappers{ 0 };
  const uint64_t mapper = in.DataVersion ? in.DataVersion >> 40 : ++mappers;
  const uint64_t changes = in.DataVersion ? (in.DataVersion & ((uint64_t(1) << 40) - 1)) : 0;
  in.DataVersion = (mapper << 40) | (changes + 1);
  in.VersionSetTime = in.SetTime;
  std::copy(matrix->GetData(), matrix->GetData() + 16, in.VersionMatrix);
  // The identity (the usual case) needs no copy.
  in.World.clear();
  in.SurfaceWorld.clear();
  if (!matrix->IsIdentity())
  {
    if (in.DrewVolumes)
    {
      in.World = in.Set.patches;
    }
    in.SurfaceWorld = in.Surfaces;
  }
  for (auto& patch : in.World)
  {
    const auto view = patch.view();
    moveControlPoints(matrix, view.coeffs, size_t(view.pointCount()), view.channels);
  }
  for (auto& surface : in.SurfaceWorld)
  {
    const auto view = surface.view();
    moveControlPoints(matrix, view.coeffs, size_t(view.pointCount()), view.channels);
  }
}

void vtkIGAIsosurfaceMapper::SetRootFinderByName(const char* name)
{
  try
  {
    this->SetRootFinder(int(iga::parseRootFinder(name ? name : "")));
  }
  catch (const std::invalid_argument& e)
  {
    vtkErrorMacro(<< e.what());
  }
}

namespace
{
iga::sst::Method engineMethod(int method)
{
  return method == vtkIGAIsosurfaceMapper::METHOD_SHARED_SUBDIVISION_TREE
           ? iga::sst::Method::SharedSubdivisionTree
         : method == vtkIGAIsosurfaceMapper::METHOD_RAY_COMPOSITION
           ? iga::sst::Method::RayComposition
           : iga::sst::Method::Automatic;
}
} // namespace

bool vtkIGAIsosurfaceMapper::ComputeFrame(vtkActor* actor, Frame& frame)
{
  Internals& in = *this->Internal;
  vtkMatrix4x4* matrix = actor->GetMatrix();
  in.DrewVolumes = frame.Volumes;
  this->UpdateDataVersion(matrix);
  frame.Settings.dataVersion = in.DataVersion;
  frame.Identity = matrix->IsIdentity() != 0;
  this->UpdateProgress(0.0);
  try
  {
    // The engine says which form it runs best on: NURBS nets (elements extracted on a GPU),
    // checked once per input, or the cells the mapper already has.
    frame.Nurbs =
      frame.Volumes && in.Surfaces.empty() && this->DrawMode == DRAW_ISOSURFACES &&
      iga::sst::preferredInput(frame.Settings.backend) == iga::sst::InputForm::NurbsVolumes &&
      this->UpdateNurbs(matrix);
    in.LastEngineInput = frame.Nurbs ? "NURBS volumes" : "Bezier cells";
    in.LastExtractionVersion = frame.Nurbs ? in.Nurbs.ExtractionVersion : 0;
    in.SeedGBuffer = this->FrameCoherency ? std::move(in.GBuffer) : iga::sst::GBuffer();
    frame.Settings.seedFrame = this->FrameCoherency ? &in.SeedGBuffer : nullptr;
    const auto report = this->RunEngine(frame, frame.View, frame.Settings, in.GBuffer);
    this->UpdateProgress(1.0);
    this->ReportEngine(report);
  }
  catch (const std::exception& e)
  {
    this->UpdateProgress(1.0);
    this->ReportOnce(std::string("engine: ") + e.what(), e.what(), true);
    this->DrawNothing(e.what());
    return false;
  }
  return true;
}

iga::sst::FrameReport vtkIGAIsosurfaceMapper::RunEngine(const Frame& frame,
  const iga::sst::View& view, const iga::sst::Settings& settings, iga::sst::GBuffer& out)
{
  Internals& in = *this->Internal;
  const auto method = engineMethod(this->Method);
  const auto report =
    this->DrawMode == DRAW_CSG ? this->ComputeCsgFrame(frame, view, settings, out)
    : frame.Nurbs
      ? iga::sst::render(
          in.Nurbs.Volumes(frame.Identity ? nullptr : &in.NurbsWorld), view, settings, method, out)
      : iga::sst::render(this->EngineScene(frame.Identity), view, settings, method, out);
  if (frame.Curvature > 0)
  {
    this->ColourByCurvature(frame, out);
  }
  return report;
}

void vtkIGAIsosurfaceMapper::ColourByCurvature(const Frame& frame, iga::sst::GBuffer& gbuffer)
{
  Internals& in = *this->Internal;
  const auto& volumes = frame.Identity ? in.Set.patches : in.World;
  const int channel = iga::kFirstAttributeChannel + frame.Settings.surfaceAttribute;
  const bool mean = frame.Curvature == 1;
  std::vector<iga::sst::Hit>& hits = gbuffer.hits;
  smpFor(vtkIdType(hits.size()), this->NumberOfThreads,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType h = begin; h < end; ++h)
      {
        iga::sst::Hit& hit = hits[size_t(h)];
        const auto curvature =
          iga::isosurfaceCurvature(volumes[size_t(hit.patch)].view(), channel, &hit.uvw[0]);
        hit.color = mean ? curvature.mean : curvature.gauss;
      }
    });
}

iga::sst::FrameReport vtkIGAIsosurfaceMapper::ComputeCsgFrame(const Frame& frame,
  const iga::sst::View& view, const iga::sst::Settings& settings, iga::sst::GBuffer& out)
{
  Internals& in = *this->Internal;
  iga::sst::CsgScene scene;
  const auto& volumes = frame.Identity ? in.Set.patches : in.World;
  const auto ranges = blockRanges(in.PatchBlock);
  std::vector<std::vector<iga::BezierVolume<double>>> blocks(ranges.size() > 1 ? ranges.size() : 0);
  for (size_t b = 0; b < ranges.size(); ++b)
  {
    if (ranges.size() > 1)
    {
      blocks[b] = patchRange(volumes, ranges[b]);
    }
    scene.inputs.push_back(
      { ranges.size() > 1 ? &blocks[b] : &volumes, in.Set.attributeNames, &in.BlockFaces[b] });
  }
  const std::string solid = iga::csg::cutByHalfSpaces(this->CsgExpression, this->CappedClips);
  try
  {
    if (!solid.empty())
      scene.expression = iga::csg::parseExpression(solid);
  }
  catch (const iga::csg::ExpressionError& e)
  {
    // The expression parsed alone; cut, it can pass the limits on operands and nesting.
    this->ReportOnce("capped clips",
      std::string("the solid cut by the capped clips is refused: ") + e.what() +
        "; drawn cut open, without the cut faces",
      true);
    if (!this->CsgExpression.empty())
      scene.expression = iga::csg::parseExpression(this->CsgExpression);
  }
  scene.slices = this->Slices;
  scene.colorAttribute = frame.ByScalars ? this->ArrayName : "";
  return iga::sst::renderCsg(scene, view, settings, engineMethod(this->Method), out);
}

bool vtkIGAIsosurfaceMapper::UpdateNurbs(vtkMatrix4x4* matrix)
{
  Internals& in = *this->Internal;
  if (in.NurbsTime != in.SetTime)
  {
    in.NurbsValid = in.Nurbs.Collect(this->GetInputDataObject(0, 0), in.Set);
    in.NurbsTime = in.SetTime;
    in.NurbsWorldVersion = 0;
  }
  if (in.NurbsValid && !matrix->IsIdentity() && in.NurbsWorldVersion != in.DataVersion)
  {
    in.NurbsWorld = in.Nurbs.Nets;
    for (auto& net : in.NurbsWorld)
    {
      moveControlPoints(matrix, net.data(), net.size() / in.Nurbs.Channels, in.Nurbs.Channels);
    }
    in.NurbsWorldVersion = in.DataVersion;
  }
  return in.NurbsValid;
}

void vtkIGAIsosurfaceMapper::ReportEngine(const iga::sst::FrameReport& report)
{
  Internals& in = *this->Internal;
  this->LastEngineTime = report.msTotal;
  this->LastSeededRays = vtkIdType(report.seededRays);
  this->LastUnresolvedPixels = vtkIdType(report.unresolvedPixels);
  this->LastRayCompositionPatches = vtkIdType(report.rayCompositionPatches);
  this->LastSstPatches = vtkIdType(report.sstPatches);
  in.LastBackend = report.backend;
  in.LastNotice = report.notice;
  if (!report.notice.empty() && in.Notices.insert(report.notice).second)
  {
    if (report.noticeSeverity == iga::sst::NoticeSeverity::Warning)
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
  if (report.constantAttributeRoots > 0)
  {
    char value[64] = " at an isovalue";
    const bool csg = this->DrawMode == DRAW_CSG;
    if (this->Isovalues.size() == 1 && !csg)
    {
      std::snprintf(value, sizeof value, " (= %g)", this->Isovalues[0]);
    }
    this->ReportOnce("constant",
      (csg ? std::string("an operand's attribute") : "attribute '" + this->SurfaceArrayName + "'") +
        " is constant" + value + " on " + std::to_string(report.constantAttributeRoots) +
        (csg ? std::string(" patches of its operands")
             : " of " + std::to_string(in.Set.patches.size()) + " patches") +
        ": a constant field has no isosurface there, so they are not drawn; not "
        "reported again until the settings or the input change",
      false);
  }
  this->ReportEmptyFrame(report);
  this->ReportDeadline(report);
  if (report.unresolvedAtDepthCap == 0 && report.unresolvedAtBudget == 0)
  {
    return;
  }
  // Once per cap hit, whatever the count (it changes with every camera move). The report counts
  // the (pixel, sub-patch) pairs each cap gave up.
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
  this->ReportOnce(std::string("unresolved") + (depth ? " depth" : "") + (budget ? " budget" : ""),
    std::to_string(report.unresolvedPixels) + " pixels left unresolved" + caps +
      "; not reported again until the settings or the input change",
    false);
}

void vtkIGAIsosurfaceMapper::ReportDeadline(const iga::sst::FrameReport& report)
{
  if (report.unresolvedAtDeadline == 0)
  {
    return;
  }
  this->Internal->FrameKey.clear(); // a frame cut short is computed again next time
  char deadline[32];
  std::snprintf(deadline, sizeof deadline, "%g", this->FrameDeadline);
  this->ReportOnce("deadline",
    "the frame stopped at its deadline (FrameDeadline " + std::string(deadline) +
      " s): " + std::to_string(report.unresolvedAtDeadline) +
      " pixels left unresolved, drawn with the hits found by then; not reported again until "
      "the settings or the input change",
    false);
}

void vtkIGAIsosurfaceMapper::ShadeFrame(vtkActor* actor, const Frame& frame)
{
  Internals& in = *this->Internal;
  vtkProperty* property = actor->GetProperty();
  vtkScalarsToColors* lut = this->GetLookupTable();
  // vtkMapper's rule (vtkOpenGLPolyDataMapper's): the table's own range when asked to.
  if (frame.ByScalars && !this->UseLookupTableScalarRange)
  {
    lut->SetRange(this->ScalarRange);
  }
  // A table no render has built yet (a frame computed without a window) maps every value to 0.
  lut->Build();
  const int width = frame.Width, height = frame.Height;
  in.Size[0] = width;
  in.Size[1] = height;
  this->AllocateLayers(frame);
  const iga::sst::GBuffer& gbuffer = in.GBuffer;
  const std::vector<unsigned char> mapped =
    frame.ByScalars ? mappedColours(lut, gbuffer) : std::vector<unsigned char>();
  smpFor(height, this->NumberOfThreads,
    [&](vtkIdType firstRow, vtkIdType endRow)
    {
      for (vtkIdType j = firstRow; j < endRow; ++j)
      {
        for (int i = 0; i < width; ++i)
        {
          const size_t p = size_t(j) * width + i;
          const int count = std::min(gbuffer.hitCount(i, int(j)), in.LayerCount);
          for (int k = 0; k < count; ++k)
          {
            const size_t h = gbuffer.offsets[p] + size_t(k);
            LayerImage& layer = *in.Layers[size_t(k)];
            double base[3];
            baseColour(property, frame.ByScalars ? &mapped[4 * h] : nullptr, base);
            shadeHit(
              gbuffer.hits[h], base, property, frame.Lights, frame.View, &layer.Colour[4 * p]);
            layer.Depth[p] = windowDepth(gbuffer.hits[h]);
          }
        }
      }
    });
  this->LastAntialiasedPixels = 0;
  if (this->Antialiasing)
  {
    this->SmoothSilhouettes(actor, frame);
  }
  if (property->GetEdgeVisibility())
  {
    this->DrawEdges(property);
  }
  in.FrameTime.Modified();
}

void vtkIGAIsosurfaceMapper::ShadeHit(
  const Frame& frame, vtkProperty* property, const iga::sst::Hit& hit, float* rgba)
{
  double base[3];
  baseColour(
    property, frame.ByScalars ? this->GetLookupTable()->MapValue(hit.color) : nullptr, base);
  shadeHit(hit, base, property, frame.Lights, frame.View, rgba);
}

void vtkIGAIsosurfaceMapper::SmoothSilhouettes(vtkActor* actor, const Frame& frame)
{
  Internals& in = *this->Internal;
  LayerImage& image = *in.Layers[0];
  const std::vector<uint8_t> mask = iga::sst::contrastingPixels(
    image.Colour, frame.Width, frame.Height, float(this->AntialiasingThreshold));
  // The samples in what is left of the frame's deadline, without progress (the frame's is done).
  iga::sst::Settings settings = frame.Settings;
  settings.firstHitOnly = true;
  settings.progress = nullptr;
  if (settings.deadlineMs > 0)
  {
    settings.deadlineMs = std::max(settings.deadlineMs - this->LastEngineTime, 1e-6);
  }
  std::array<iga::sst::GBuffer, iga::sst::kRotatedGridSamples> samples;
  try
  {
    const auto report = iga::sst::renderRotatedGridSamples(
      frame.View, settings, mask,
      [&](const iga::sst::View& view, const iga::sst::Settings& s, iga::sst::GBuffer& out)
      { return this->RunEngine(frame, view, s, out); },
      samples);
    this->LastEngineTime += report.msTotal;
    if (report.unresolvedAtDeadline > 0)
    {
      in.FrameKey.clear(); // drawn as it is now, and computed again next time
      return;
    }
  }
  catch (const std::exception& e)
  {
    this->ReportOnce("antialiasing",
      std::string("antialiasing failed: ") + e.what() + "; the frame is drawn without it", false);
    return;
  }
  // A pixel's colour is its samples' mean; where its centre missed, its depth is its nearest
  // sample's.
  for (size_t p = 0; p < mask.size(); ++p)
  {
    if (!mask[p])
      continue;
    float sum[4] = { 0, 0, 0, 0 }, rgba[4];
    float nearest = image.Depth[p];
    for (const iga::sst::GBuffer& sample : samples)
    {
      if (sample.offsets[p] == sample.offsets[p + 1])
        continue;
      const iga::sst::Hit& hit = sample.hits[sample.offsets[p]];
      this->ShadeHit(frame, actor->GetProperty(), hit, rgba);
      for (int c = 0; c < 4; ++c)
        sum[c] += rgba[c] / iga::sst::kRotatedGridSamples;
      nearest = std::min(nearest, windowDepth(hit));
    }
    std::copy(sum, sum + 4, &image.Colour[4 * p]);
    image.Depth[p] = in.GBuffer.offsets[p] < in.GBuffer.offsets[p + 1] ? image.Depth[p] : nearest;
    ++this->LastAntialiasedPixels;
  }
}

void vtkIGAIsosurfaceMapper::AllocateLayers(const Frame& frame)
{
  // One layer for an opaque surface; for a translucent one, as many as a pixel has hits (up to
  // kMaxLayers, the nearest; said once when a pixel has more).
  Internals& in = *this->Internal;
  int most = 1;
  for (size_t p = 0; frame.Translucent && p + 1 < in.GBuffer.offsets.size(); ++p)
  {
    most = std::max(most, int(in.GBuffer.offsets[p + 1] - in.GBuffer.offsets[p]));
  }
  if (most > kMaxLayers)
  {
    this->ReportOnce("layers",
      "the translucent surface has up to " + std::to_string(most) + " layers a pixel; the " +
        std::to_string(kMaxLayers) + " nearest are drawn",
      false);
  }
  in.LayerCount = std::min(most, kMaxLayers);
  for (size_t k = size_t(in.LayerCount); k < in.Layers.size(); ++k) // unused: their memory goes
  {
    in.Layers[k]->Colour = std::vector<float>();
    in.Layers[k]->Depth = std::vector<float>();
  }
  while (in.Layers.size() < size_t(in.LayerCount))
  {
    in.Layers.push_back(std::make_unique<LayerImage>());
  }
  const size_t pixels = size_t(frame.Width) * size_t(frame.Height);
  for (int k = 0; k < in.LayerCount; ++k)
  {
    in.Layers[size_t(k)]->Colour.assign(4 * pixels, 0.0f);
    in.Layers[size_t(k)]->Depth.assign(pixels, 1.0f);
  }
}

void vtkIGAIsosurfaceMapper::DrawEdges(vtkProperty* property)
{
  // In the edge colour, unlit, over the shading (premultiplied colours).
  Internals& in = *this->Internal;
  const std::vector<float> coverage =
    iga::sst::elementEdgeCoverage(in.GBuffer, std::max(1.0f, property->GetLineWidth()));
  double edge[3];
  property->GetEdgeColor(edge);
  for (size_t p = 0; p < coverage.size(); ++p)
  {
    float* rgba = &in.Layers[0]->Colour[4 * p];
    for (int c = 0; c < 3; ++c)
    {
      rgba[c] = (1 - coverage[p]) * rgba[c] + coverage[p] * float(edge[c]) * rgba[3];
    }
  }
}

void vtkIGAIsosurfaceMapper::SelectionIds(
  vtkHardwareSelector* selector, vtkDataObject* input, std::vector<float>& ids)
{
  // The pass's ids instead of colours, in VTK's encoding (0 is "nothing"): prop, composite
  // block, process or cell (= patch) id + 1. Point ids are not drawn: a pixel of the isosurface
  // is no control point.
  Internals& in = *this->Internal;
  const int pass = selector->GetCurrentPass();
  const bool composite = vtkCompositeDataSet::SafeDownCast(input) != nullptr;
  for (const auto* cells : { &in.PatchCell, &in.QuadCell })
  {
    if (!cells->empty())
    {
      selector->UpdateMaximumCellId(*std::max_element(cells->begin(), cells->end()));
    }
  }
  ids.assign(in.Layers[0]->Colour.size(), 0.0f);
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
      vtkIdType cellId;
      unsigned int block;
      this->PatchSource(hit->patch, cellId, block);
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
          selector->RenderCompositeIndex(composite ? block : 1);
          VTK_FALLTHROUGH;
        default: // actor and process passes
          std::copy(selector->GetPropColorValue(), selector->GetPropColorValue() + 3, rgba);
          rgba[3] = 1.0f;
      }
    }
  }
}

void vtkIGAIsosurfaceMapper::DrawFrame(vtkRenderer* renderer, vtkActor* actor, vtkDataObject* input)
{
  // Hardware selection (vtkHardwareSelector, vtkPropPicker) draws ids instead of colours.
  vtkHardwareSelector* selector = renderer->GetSelector();
  std::vector<float> ids;
  if (selector)
  {
    selector->BeginRenderProp();
    this->SelectionIds(selector, input, ids);
  }
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (window)
  {
    this->UploadTextures(window, selector ? &ids : nullptr);
    this->DrawQuad(window, actor, selector != nullptr);
  }
  if (selector)
  {
    selector->EndRenderProp();
  }
}

void vtkIGAIsosurfaceMapper::UploadTextures(vtkOpenGLRenderWindow* window, std::vector<float>* ids)
{
  // When the frame changed, or ids were drawn instead of the first layer's colours.
  Internals& in = *this->Internal;
  if (!ids && in.UploadTime >= in.FrameTime && in.Layers[0]->ColourTexture->GetContext() == window)
  {
    return;
  }
  for (int k = 0; k < in.LayerCount; ++k)
  {
    LayerImage& layer = *in.Layers[size_t(k)];
    layer.ColourTexture->SetContext(window);
    layer.DepthTexture->SetContext(window);
    layer.ColourTexture->Create2DFromRaw(
      in.Size[0], in.Size[1], 4, VTK_FLOAT, ids && k == 0 ? ids->data() : layer.Colour.data());
    layer.DepthTexture->Create2DFromRaw(in.Size[0], in.Size[1], 1, VTK_FLOAT, layer.Depth.data());
    for (vtkTextureObject* texture : { layer.ColourTexture.Get(), layer.DepthTexture.Get() })
    {
      texture->SetMinificationFilter(vtkTextureObject::Nearest);
      texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    }
  }
  in.UploadTime.Modified();
  if (ids)
  {
    in.UploadTime = vtkTimeStamp(); // the colours go back up next time
  }
}

std::vector<vtkOpenGLRenderPass*> vtkIGAIsosurfaceMapper::RenderPasses(
  vtkOpenGLRenderWindow* window, vtkActor* actor)
{
  std::vector<vtkOpenGLRenderPass*> passes;
  vtkInformation* keys = actor->GetPropertyKeys();
  if (keys && keys->Has(vtkOpenGLRenderPass::RenderPasses()))
  {
    for (int k = 0; k < keys->Length(vtkOpenGLRenderPass::RenderPasses()); ++k)
    {
      passes.push_back(
        static_cast<vtkOpenGLRenderPass*>(keys->Get(vtkOpenGLRenderPass::RenderPasses(), k)));
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
  return passes;
}

bool vtkIGAIsosurfaceMapper::UpdateShader(
  vtkOpenGLRenderWindow* window, vtkActor* actor, const std::vector<vtkOpenGLRenderPass*>& passes)
{
  // Render passes (order-independent translucency, dual and classic depth peeling) hook into
  // the shader as into vtkOpenGLPolyDataMapper's, through the DepthPeeling markers, at every
  // peel; their depth tests read gl_FragDepth, set before the PreColor hook, and gl_FragCoord.z
  // would be the quad's: it is replaced by the surface's depth igaDepth.
  Internals& in = *this->Internal;
  vtkMTimeType passTime = 0;
  for (vtkOpenGLRenderPass* pass : passes)
  {
    passTime = std::max(passTime, pass->GetShaderStageMTime());
  }
  if (in.Quad && passes == in.ShaderPasses && passTime <= in.ShaderTime)
  {
    window->GetShaderCache()->ReadyShaderProgram(in.Quad->Program);
    return in.Quad->Program != nullptr;
  }
  std::string vertex = vtkOpenGLRenderUtilities::GetFullScreenQuadVertexShader();
  std::string geometry;
  std::string fragment = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
  vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Decl", vtkIGAIsosurfaceDeclFS);
  vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Impl", vtkIGAIsosurfaceImplFS);
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
  return in.Quad->Program != nullptr;
}

void vtkIGAIsosurfaceMapper::DrawQuad(
  vtkOpenGLRenderWindow* window, vtkActor* actor, bool selecting)
{
  // A full-screen pass with gl_FragDepth.
  Internals& in = *this->Internal;
  const std::vector<vtkOpenGLRenderPass*> passes = this->RenderPasses(window, actor);
  if (!this->UpdateShader(window, actor, passes))
  {
    vtkErrorMacro(<< "the isosurface shader did not compile");
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
  // A pass a layer: blending and depth peeling take each layer as a fragment of its own. A
  // hardware selector sees the first hits only.
  const int layers = selecting ? 1 : in.LayerCount;
  for (int k = 0; k < layers; ++k)
  {
    LayerImage& layer = *in.Layers[size_t(k)];
    layer.ColourTexture->Activate();
    layer.DepthTexture->Activate();
    in.Quad->Program->SetUniformi("colourTexture", layer.ColourTexture->GetTextureUnit());
    in.Quad->Program->SetUniformi("depthTexture", layer.DepthTexture->GetTextureUnit());
    for (vtkOpenGLRenderPass* pass : passes)
    {
      pass->SetShaderParameters(in.Quad->Program, this, actor, in.Quad->VAO);
    }
    in.Quad->Render();
    layer.ColourTexture->Deactivate();
    layer.DepthTexture->Deactivate();
  }
}

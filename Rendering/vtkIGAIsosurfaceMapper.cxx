#include "vtkIGAIsosurfaceMapper.h"

#include "vtkIGABezierHexahedra.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderUtilities.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkPointData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkUnstructuredGrid.h"
#include "vtk_glew.h"

#include "iga/sst/Engine.h"

#include <algorithm>
#include <array>
#include <cmath>

vtkStandardNewMacro(vtkIGAIsosurfaceMapper);

struct vtkIGAIsosurfaceMapper::Internals
{
  // Data, converted when the input changes.
  iga::VolumeSet<double> Set;
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
  vtkTimeStamp UploadTime;
  vtkTimeStamp FrameTime;
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
}

void vtkIGAIsosurfaceMapper::SetInputData(vtkUnstructuredGrid* input)
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

int vtkIGAIsosurfaceMapper::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

double* vtkIGAIsosurfaceMapper::GetBounds()
{
  // The control points bound the patches (convex hull): what ResetCamera needs.
  vtkDataSet* input = this->GetInput();
  if (!input)
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return this->Bounds;
  }
  this->Update();
  input->GetBounds(this->Bounds);
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
}

namespace
{

/// Phong shading of one hit with VTK's property and the renderer's (directional) lights.
void shadeHit(const iga::sst::Hit& hit, const double* base, vtkProperty* property,
  const std::vector<std::pair<vtkLight*, std::array<double, 3>>>& lights, const double* toEye,
  float* rgba)
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
    light.first->GetDiffuseColor(lightColour);
    const double intensity = light.first->GetIntensity();
    const double* L = light.second.data(); // towards the light
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

} // namespace

void vtkIGAIsosurfaceMapper::Render(vtkRenderer* renderer, vtkActor* actor)
{
  Internals& in = *this->Internal;
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::SafeDownCast(this->GetInput());
  if (!input || this->Isovalues.empty())
  {
    return;
  }
  this->Update();

  // Patches, when the data changed.
  if (input->GetMTime() > in.SetTime || !in.SetTime)
  {
    std::string error;
    std::vector<std::string> warnings;
    in.SetValid = vtkIGABezierHexahedra::FromUnstructuredGrid(input, in.Set, error, warnings);
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
    double(property->GetMTime()), double(lut->GetMTime()), double(width), double(height) };
  key.insert(key.end(), worldToClip->GetData(), worldToClip->GetData() + 16);
  key.insert(key.end(), actor->GetMatrix()->GetData(), actor->GetMatrix()->GetData() + 16);
  double eye[3];
  camera->GetPosition(eye);
  key.insert(key.end(), eye, eye + 3);
  vtkLightCollection* lightCollection = renderer->GetLights();
  std::vector<std::pair<vtkLight*, std::array<double, 3>>> lights;
  vtkCollectionSimpleIterator it;
  lightCollection->InitTraversal(it);
  while (vtkLight* light = lightCollection->GetNextLight(it))
  {
    if (light->GetSwitch() && light->GetIntensity() > 0)
    {
      double position[3], focal[3], colour[3];
      light->GetTransformedPosition(position);
      light->GetTransformedFocalPoint(focal);
      light->GetDiffuseColor(colour);
      std::array<double, 3> towards = { position[0] - focal[0], position[1] - focal[1],
        position[2] - focal[2] };
      iga::normalize3(towards.data());
      lights.emplace_back(light, towards);
      key.insert(key.end(), towards.begin(), towards.end());
      key.insert(key.end(), colour, colour + 3);
      key.push_back(light->GetIntensity());
    }
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
    // Patches in world space: the actor's matrix acts linearly on homogeneous control points,
    // exactly, whatever the matrix.
    std::vector<iga::BezierVolume<double>> world = in.Set.patches;
    vtkMatrix4x4* matrix = actor->GetMatrix();
    for (auto& patch : world)
    {
      const auto view = patch.view();
      for (int p = 0; p < view.pointCount(); ++p)
      {
        double* cp = view.point(p);
        double moved[4];
        matrix->MultiplyPoint(cp, moved);
        std::copy(moved, moved + 4, cp);
      }
    }

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
    const auto& names = in.Set.attributeNames;
    auto indexOf = [&](const std::string& name)
    { return int(std::find(names.begin(), names.end(), name) - names.begin()); };
    settings.surfaceAttribute =
      this->SurfaceArrayName.empty() ? 0 : indexOf(this->SurfaceArrayName);
    const bool byScalars = this->ScalarVisibility && this->ArrayName && *this->ArrayName &&
                           indexOf(this->ArrayName) < int(names.size());
    settings.colorAttribute = byScalars ? indexOf(this->ArrayName) : -1;
    if (names.empty() || settings.surfaceAttribute >= int(names.size()))
    {
      vtkErrorMacro(<< "no point array named '" << this->SurfaceArrayName
                    << "' to draw isosurfaces of");
      return;
    }

    iga::sst::GBuffer& gbuffer = in.GBuffer;
    try
    {
      const auto report =
        iga::sst::render(world, view, settings, iga::sst::Method::SharedSubdivisionTree, gbuffer);
      this->LastEngineTime = report.msTotal;
      if (report.unresolvedPixels > 0)
      {
        vtkWarningMacro(<< report.unresolvedPixels << " pixels unresolved at the subdivision cap");
      }
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro(<< e.what());
      return;
    }

    if (byScalars)
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

  // Draw: upload when the frame changed, then a full-screen pass with gl_FragDepth.
  vtkOpenGLRenderWindow* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    return;
  }
  if (in.UploadTime < in.FrameTime || in.ColourTexture->GetContext() != window)
  {
    in.ColourTexture->SetContext(window);
    in.DepthTexture->SetContext(window);
    in.ColourTexture->Create2DFromRaw(in.Size[0], in.Size[1], 4, VTK_FLOAT, in.Colour.data());
    in.DepthTexture->Create2DFromRaw(in.Size[0], in.Size[1], 1, VTK_FLOAT, in.Depth.data());
    for (vtkTextureObject* texture : { in.ColourTexture.Get(), in.DepthTexture.Get() })
    {
      texture->SetMinificationFilter(vtkTextureObject::Nearest);
      texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    }
    in.UploadTime.Modified();
  }
  if (!in.Quad)
  {
    std::string fragment = vtkOpenGLRenderUtilities::GetFullScreenQuadFragmentShaderTemplate();
    vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Decl",
      "uniform sampler2D colourTexture;\n"
      "uniform sampler2D depthTexture;\n");
    vtkShaderProgram::Substitute(fragment, "//VTK::FSQ::Impl",
      "  vec4 colour = texture(colourTexture, texCoord);\n"
      "  if (colour.a <= 0.0) { discard; }\n"
      "  gl_FragDepth = texture(depthTexture, texCoord).r;\n"
      "  gl_FragData[0] = colour;\n");
    in.Quad.reset(new vtkOpenGLQuadHelper(window, nullptr, fragment.c_str(), nullptr));
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(in.Quad->Program);
  }
  if (!in.Quad->Program)
  {
    vtkErrorMacro(<< "the isosurface shader did not compile");
    return;
  }
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglEnableDisable depthTest(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthFunc depthFunc(state);
  state->vtkglEnable(GL_DEPTH_TEST);
  state->vtkglDepthFunc(GL_LEQUAL);
  state->vtkglDepthMask(GL_TRUE);
  in.ColourTexture->Activate();
  in.DepthTexture->Activate();
  in.Quad->Program->SetUniformi("colourTexture", in.ColourTexture->GetTextureUnit());
  in.Quad->Program->SetUniformi("depthTexture", in.DepthTexture->GetTextureUnit());
  in.Quad->Render();
  in.ColourTexture->Deactivate();
  in.DepthTexture->Deactivate();
}

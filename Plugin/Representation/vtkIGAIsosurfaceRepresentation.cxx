#include "vtkIGAIsosurfaceRepresentation.h"

#include "vtkIGAIsosurfaceMapper.h"

#include "vtkCommand.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOutlineSource.h"
#include "vtkPVLODActor.h"
#include "vtkPVRenderView.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkTransform.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <string>

vtkStandardNewMacro(vtkIGAIsosurfaceRepresentation);

vtkIGAIsosurfaceRepresentation::vtkIGAIsosurfaceRepresentation()
{
  this->Actor->SetProperty(this->Property);
  this->Actor->SetMapper(this->Mapper);
  this->Actor->SetLODMapper(this->OutlineMapper);
  this->Mapper->SetScalarVisibility(0);
  this->Mapper->SetScalarModeToUsePointFieldData();
  // ParaView owns the lookup table's range (as vtkGeometryRepresentation's mapper does).
  this->Mapper->SetUseLookupTableScalarRange(1);
  this->OutlineMapper->SetScalarVisibility(0);
  vtkMath::UninitializeBounds(this->DataBounds);
  // The engine's progress as this representation's, which ParaView's progress handler
  // observes (see the class documentation).
  this->SetProgressText("IGA Isosurface");
  this->Mapper->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkIGAIsosurfaceRepresentation::OnMapperProgress);
}

vtkIGAIsosurfaceRepresentation::~vtkIGAIsosurfaceRepresentation() = default;

void vtkIGAIsosurfaceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Cells in this piece: "
     << (this->Cache ? this->Cache->GetNumberOfElements(vtkDataObject::CELL) : 0) << "\n";
}

int vtkIGAIsosurfaceRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkIGAIsosurfaceRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A rank without data (or without cells) still takes part in every view pass with an empty
  // piece, so that the collective delivery and compositing steps match on all ranks.
  this->Cache = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkMath::UninitializeBounds(this->DataBounds);
  vtkDataObject* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                           ? vtkDataObject::GetData(inputVector[0], 0)
                           : nullptr;
  // The control points bound the patches (convex hull property).
  if (auto* grid = vtkUnstructuredGrid::SafeDownCast(input))
  {
    this->Cache->ShallowCopy(grid);
    if (grid->GetNumberOfCells() > 0)
    {
      grid->GetBounds(this->DataBounds);
    }
  }
  else if (auto* composite = vtkCompositeDataSet::SafeDownCast(input))
  {
    // The mapper draws composites itself (and picks their blocks).
    this->Cache.TakeReference(composite->NewInstance());
    this->Cache->ShallowCopy(composite);
    if (composite->GetNumberOfCells() > 0)
    {
      composite->GetBounds(this->DataBounds);
    }
  }
  else if (input)
  {
    vtkErrorMacro(<< "IGA representations need an unstructured grid of Bézier cells, not a "
                  << input->GetClassName());
  }
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

int vtkIGAIsosurfaceRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    // Each rank keeps its own piece; the view reduces the bounds over ranks for the camera
    // and clipping range, and IceT composites the ranks' colour and depth.
    vtkPVRenderView::SetPiece(inInfo, this, this->Cache);
    vtkPVRenderView::SetGeometryBounds(inInfo, this, this->DataBounds);
    vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, true);
    if (this->Property->GetOpacity() < 1.0)
    {
      // Translucent surfaces blend across ranks: IceT must composite the ranks in visibility
      // order, sorted by the pieces' bounds (the data stays where it is).
      outInfo->Set(vtkPVRenderView::NEED_ORDERED_COMPOSITING(), 1);
      vtkPVRenderView::SetOrderedCompositingConfiguration(
        inInfo, this, vtkPVRenderView::USE_BOUNDS_FOR_REDISTRIBUTION, this->DataBounds);
    }
  }
  else if (request_type == vtkPVView::REQUEST_UPDATE_LOD())
  {
    vtkNew<vtkPolyData> outline;
    if (vtkMath::AreBoundsInitialized(this->DataBounds))
    {
      this->Outline->SetBounds(this->DataBounds);
      this->Outline->Update();
      outline->ShallowCopy(this->Outline->GetOutput());
    }
    vtkPVRenderView::SetPieceLOD(inInfo, this, outline);
    vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    // An empty piece draws nothing; the mapper would report it as bad input.
    vtkDataObject* piece = vtkPVView::GetDeliveredPiece(inInfo, this);
    const bool empty = !piece || piece->GetNumberOfElements(vtkDataObject::CELL) == 0;
    this->Mapper->SetInputDataObject(empty ? nullptr : piece);
    this->OutlineMapper->SetInputDataObject(vtkPVView::GetDeliveredPieceLOD(inInfo, this));
    this->Actor->SetEnableLOD(inInfo->Has(vtkPVRenderView::USE_LOD()) ? 1 : 0);
  }
  return 1;
}

bool vtkIGAIsosurfaceRepresentation::AddToView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->AddActor(this->Actor);
    return this->Superclass::AddToView(view);
  }
  return false;
}

bool vtkIGAIsosurfaceRepresentation::RemoveFromView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->RemoveActor(this->Actor);
    return this->Superclass::RemoveFromView(view);
  }
  return false;
}

void vtkIGAIsosurfaceRepresentation::SetVisibility(bool val)
{
  this->Superclass::SetVisibility(val);
  this->Actor->SetVisibility(val ? 1 : 0);
}

void vtkIGAIsosurfaceRepresentation::SetNumberOfIsovalues(int count)
{
  this->Mapper->SetNumberOfIsovalues(count);
}

void vtkIGAIsosurfaceRepresentation::SetIsovalue(int index, double value)
{
  this->Mapper->SetIsovalue(index, value);
}

void vtkIGAIsosurfaceRepresentation::SetSurfaceArray(
  int, int, int, int fieldAssociation, const char* name)
{
  if (name && *name && fieldAssociation != vtkDataObject::FIELD_ASSOCIATION_POINTS)
  {
    vtkErrorMacro(<< "the surface array '" << name << "' must be a point array");
    return;
  }
  this->Mapper->SetSurfaceArrayName(name);
}

void vtkIGAIsosurfaceRepresentation::SetNumberOfThreads(int threads)
{
  this->Mapper->SetNumberOfThreads(threads);
}

void vtkIGAIsosurfaceRepresentation::SetBackend(int backend)
{
  this->Mapper->SetBackend(backend);
}

void vtkIGAIsosurfaceRepresentation::SetMethod(int method)
{
  this->Mapper->SetMethod(method);
}

void vtkIGAIsosurfaceRepresentation::SetRootFinder(int finder)
{
  this->Mapper->SetRootFinder(finder);
}

void vtkIGAIsosurfaceRepresentation::SetFrameCoherency(int coherent)
{
  this->Mapper->SetFrameCoherency(coherent != 0);
}

void vtkIGAIsosurfaceRepresentation::SetAntialiasing(int antialias)
{
  this->Mapper->SetAntialiasing(antialias != 0);
}

void vtkIGAIsosurfaceRepresentation::SetAntialiasingThreshold(double threshold)
{
  this->Mapper->SetAntialiasingThreshold(threshold);
}

int vtkIGAIsosurfaceRepresentation::GetLastAntialiasedPixels()
{
  return int(this->Mapper->GetLastAntialiasedPixels());
}

int vtkIGAIsosurfaceRepresentation::GetLastRayCompositionPatches()
{
  return int(this->Mapper->GetLastRayCompositionPatches());
}

int vtkIGAIsosurfaceRepresentation::GetLastSeededRays()
{
  return int(this->Mapper->GetLastSeededRays());
}

int vtkIGAIsosurfaceRepresentation::GetLastSstPatches()
{
  return int(this->Mapper->GetLastSstPatches());
}

void vtkIGAIsosurfaceRepresentation::SetMaximumSubdivisionDepth(int depth)
{
  this->Mapper->SetMaximumSubdivisionDepth(depth);
}

void vtkIGAIsosurfaceRepresentation::SetMemoryBudget(int megabytes)
{
  this->Mapper->SetMemoryBudgetMB(megabytes);
}

void vtkIGAIsosurfaceRepresentation::SetFrameDeadline(double seconds)
{
  this->Mapper->SetFrameDeadline(seconds);
}

void vtkIGAIsosurfaceRepresentation::OnMapperProgress(vtkObject*, unsigned long, void* data)
{
  this->UpdateProgress(*static_cast<double*>(data));
}

void vtkIGAIsosurfaceRepresentation::SetInputArrayToProcess(
  int idx, int port, int connection, int fieldAssociation, const char* name)
{
  this->Superclass::SetInputArrayToProcess(idx, port, connection, fieldAssociation, name);
  if (idx != 0)
  {
    return;
  }
  // The mapper samples point attributes at the hits; cell colouring falls back to the
  // solid colour.
  const bool byPoints =
    name && *name && fieldAssociation == vtkDataObject::FIELD_ASSOCIATION_POINTS;
  if (name && *name && !byPoints)
  {
    vtkWarningMacro(<< "IGA Isosurface colours by point arrays only; '" << name
                    << "' is drawn in the solid colour");
  }
  this->Mapper->SetScalarVisibility(byPoints ? 1 : 0);
  this->Mapper->SelectColorArray(byPoints ? name : nullptr);
}

void vtkIGAIsosurfaceRepresentation::SetCsgExpression(const char* expression)
{
  this->Mapper->SetCsgExpression(expression);
}

void vtkIGAIsosurfaceRepresentation::SetNumberOfSlices(int count)
{
  this->Slices.resize(size_t(std::max(count, 0)), { 1, 0, 0, 0 });
  this->UpdateCsg();
}

void vtkIGAIsosurfaceRepresentation::SetSlice(int index, double a, double b, double c, double d)
{
  if (index < 0 || size_t(index) >= this->Slices.size())
  {
    vtkErrorMacro(<< "slice " << index << " of " << this->Slices.size());
    return;
  }
  this->Slices[size_t(index)] = { a, b, c, d };
  this->UpdateCsg();
}

void vtkIGAIsosurfaceRepresentation::SetPlaneUse(int use)
{
  if (use < PLANE_OFF || use > PLANE_CLIP)
  {
    vtkErrorMacro(<< "plane use " << use << " is none of off (0), slice (1) and clip (2)");
    return;
  }
  this->PlaneUse = use;
  this->UpdateCsg();
}

void vtkIGAIsosurfaceRepresentation::SetPlaneOrigin(double x, double y, double z)
{
  this->PlaneOrigin[0] = x;
  this->PlaneOrigin[1] = y;
  this->PlaneOrigin[2] = z;
  this->UpdateCsg();
}

void vtkIGAIsosurfaceRepresentation::SetPlaneNormal(double x, double y, double z)
{
  this->PlaneNormal[0] = x;
  this->PlaneNormal[1] = y;
  this->PlaneNormal[2] = z;
  this->UpdateCsg();
}

std::array<double, 4> vtkIGAIsosurfaceRepresentation::WidgetPlane() const
{
  const double* n = this->PlaneNormal;
  return { n[0], n[1], n[2], -vtkMath::Dot(n, this->PlaneOrigin) };
}

void vtkIGAIsosurfaceRepresentation::UpdateCsg()
{
  // A zero normal (while the widget's fields are typed in) is no plane: the widget is ignored.
  const bool plane = this->PlaneUse != PLANE_OFF && vtkMath::Norm(this->PlaneNormal) > 0;
  const bool clip = plane && this->PlaneUse == PLANE_CLIP;
  auto slices = this->Slices;
  if (plane && !clip)
  {
    slices.push_back(this->WidgetPlane());
  }
  this->Mapper->SetNumberOfSlices(int(slices.size()));
  for (size_t k = 0; k < slices.size(); ++k)
  {
    this->Mapper->SetSlice(int(k), slices[k][0], slices[k][1], slices[k][2], slices[k][3]);
  }
  this->Mapper->SetNumberOfCappedClips(clip ? 1 : 0);
  if (clip)
  {
    const auto cut = this->WidgetPlane();
    this->Mapper->SetCappedClip(0, cut[0], cut[1], cut[2], cut[3]);
  }
}

void vtkIGAIsosurfaceRepresentation::SetRepresentation(const char* name)
{
  const std::string type = name ? name : "";
  if (type != "IGA Isosurface" && type != "IGA Surface" && type != "IGA Surface With Edges" &&
      type != "IGA CSG")
  {
    vtkErrorMacro(<< "unknown representation '" << type
                  << "' (IGA Isosurface, IGA Surface, IGA Surface With Edges, IGA CSG)");
    return;
  }
  this->Mapper->SetDrawMode(type == "IGA Isosurface" ? vtkIGAIsosurfaceMapper::DRAW_ISOSURFACES
                            : type == "IGA CSG"      ? vtkIGAIsosurfaceMapper::DRAW_CSG
                                                     : vtkIGAIsosurfaceMapper::DRAW_SURFACES);
  this->Property->SetEdgeVisibility(type == "IGA Surface With Edges");
  this->SetProgressText(type.c_str());
  this->Modified();
}

void vtkIGAIsosurfaceRepresentation::SetEdgeColor(double r, double g, double b)
{
  this->Property->SetEdgeColor(r, g, b);
}

void vtkIGAIsosurfaceRepresentation::SetLineWidth(double width)
{
  this->Property->SetLineWidth(float(width));
}

void vtkIGAIsosurfaceRepresentation::SetLookupTable(vtkScalarsToColors* lut)
{
  this->Mapper->SetLookupTable(lut);
}

void vtkIGAIsosurfaceRepresentation::SetOpacity(double value)
{
  this->Property->SetOpacity(value);
}

void vtkIGAIsosurfaceRepresentation::SetAmbient(double value)
{
  this->Property->SetAmbient(value);
}

void vtkIGAIsosurfaceRepresentation::SetDiffuse(double value)
{
  this->Property->SetDiffuse(value);
}

void vtkIGAIsosurfaceRepresentation::SetSpecular(double value)
{
  this->Property->SetSpecular(value);
}

void vtkIGAIsosurfaceRepresentation::SetSpecularPower(double value)
{
  this->Property->SetSpecularPower(value);
}

void vtkIGAIsosurfaceRepresentation::SetAmbientColor(double r, double g, double b)
{
  this->Property->SetAmbientColor(r, g, b);
}

void vtkIGAIsosurfaceRepresentation::SetDiffuseColor(double r, double g, double b)
{
  this->Property->SetDiffuseColor(r, g, b);
}

void vtkIGAIsosurfaceRepresentation::SetSpecularColor(double r, double g, double b)
{
  this->Property->SetSpecularColor(r, g, b);
}

void vtkIGAIsosurfaceRepresentation::SetOrientation(double x, double y, double z)
{
  this->Actor->SetOrientation(x, y, z);
}

void vtkIGAIsosurfaceRepresentation::SetOrigin(double x, double y, double z)
{
  this->Actor->SetOrigin(x, y, z);
}

void vtkIGAIsosurfaceRepresentation::SetPosition(double x, double y, double z)
{
  this->Actor->SetPosition(x, y, z);
}

void vtkIGAIsosurfaceRepresentation::SetScale(double x, double y, double z)
{
  this->Actor->SetScale(x, y, z);
}

void vtkIGAIsosurfaceRepresentation::SetUserTransform(const double matrix[16])
{
  vtkNew<vtkTransform> transform;
  transform->SetMatrix(matrix);
  this->Actor->SetUserTransform(transform);
}

void vtkIGAIsosurfaceRepresentation::SetPickable(int value)
{
  this->Actor->SetPickable(value);
}

// The shared-subdivision-tree loop over device-wide primitives (Thrust): every stage is a
// parallel map, scan, sort or compaction over global node and tuple arrays, as the paper lays
// it out for the GPU. The per-element steps are Tree.h and PixelProblem.h, shared with the CPU
// driver. nvcc compiles this for CUDA (CudaEngine.cu); the tests also compile it with g++ for
// Thrust's sequential host system, which checks the driver's logic on machines without a GPU.
#pragma once

#include "DeviceRuntime.h"
#include "FramePlan.h"
#include "ParallelFor.h"
#include "iga/Validation.h"

#include <thrust/copy.h>
#include <thrust/count.h>
#include <thrust/execution_policy.h>
#include <thrust/fill.h>
#include <thrust/for_each.h>
#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <thrust/reduce.h>
#include <thrust/scan.h>
#include <thrust/sort.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

namespace iga
{
namespace sst
{
namespace device
{

template<class T>
T* raw(Array<T>& v)
{
  return v.data();
}

/// Sizes an array for this frame. Shrinking keeps the allocation, so steady-state frames reuse
/// the memory of earlier ones instead of allocating.
template<class T>
T* sized(Array<T>& v, size_t n)
{
  v.resize(n);
  return raw(v);
}

/// Calls fn(k) for k in [0, n) on the device.
template<class Fn>
void forEach(size_t n, Fn fn)
{
  if (n > 0)
  {
    thrust::for_each_n(exec(), thrust::counting_iterator<size_t>(0), n, fn);
  }
}

/// Copies device memory to host memory (the host waits for the work before it).
template<class T>
void download(const T* first, size_t count, T* host)
{
  if (count > 0)
  {
    copyToHost(host, first, count * sizeof(T));
  }
}

template<class T>
T readBack(const T* where)
{
  T value;
  download(where, 1, &value);
  return value;
}

/// Exclusive scan of counts in place with one extra slot at the end; returns the total, which
/// the 32-bit indices of pairs and tuples must reach (checkIndexable). Counts are 64-bit
/// where the total could pass 2^32, so that the check sees it unwrapped.
template<class Count>
size_t scanCounts(Array<Count>& counts, size_t n)
{
  Count* c = raw(counts);
  thrust::exclusive_scan(exec(), c, c + n + 1, c);
  const size_t total = size_t(readBack(c + n));
  checkIndexable(total);
  return total;
}

/// Threads for a host copy of `bytes`: one per MiB at most, since starting a thread costs about
/// as much as copying a few hundred KiB.
inline int copyThreads(size_t bytes, int threads)
{
  return std::max(1, std::min(threads, int(bytes >> 20)));
}

/// Host arrays of doubles read as one sequence: the coefficients of the input patches or of
/// the control nets, gathered into the staging area a chunk at a time.
class HostSequence
{
public:
  void append(const double* values, size_t count)
  {
    this->Parts.push_back(values);
    this->Starts.push_back(this->Starts.back() + count);
  }

  size_t size() const { return this->Starts.back(); }

  /// Copies values [first, last) of the sequence to `to`.
  void copy(size_t first, size_t last, double* to) const
  {
    size_t part = size_t(std::upper_bound(this->Starts.begin(), this->Starts.end(), first) -
                         this->Starts.begin()) -
                  1;
    for (size_t at = first; at < last; ++part)
    {
      const size_t end = std::min(last, this->Starts[part + 1]);
      std::copy(this->Parts[part] + (at - this->Starts[part]),
        this->Parts[part] + (end - this->Starts[part]), to + (at - first));
      at = end;
    }
  }

private:
  std::vector<const double*> Parts;
  std::vector<size_t> Starts{ 0 }; ///< of each part, then the total
};

/// What the driver knows of an input patch: its shape and where its data lie on the device.
struct PatchShape
{
  int degree[3];
  int channels;     ///< of the world patch
  int screenValues; ///< control points times kScreenChannels (= kShadeChannels)
  size_t world;     ///< offset of its world coefficients
  size_t screen;    ///< offset of its screen patch in the initial pool and of its shading patch
};

static_assert(kScreenChannels == kShadeChannels, "screen and shading patches share offsets");

inline bool sameShapes(const std::vector<PatchShape>& a, const std::vector<PatchShape>& b)
{
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
    [](const PatchShape& x, const PatchShape& y)
    {
      return std::equal(x.degree, x.degree + 3, y.degree) && x.channels == y.channels &&
             x.screenValues == y.screenValues && x.world == y.world && x.screen == y.screen;
    });
}

/// A NURBS volume on the device: its net and its extraction operators, as offsets.
struct VolumeTable
{
  int degree[3];
  int netSize[3];
  size_t net;           ///< offset of its control net
  size_t matrices[3];   ///< offsets of its per-direction element matrices
  size_t firstBasis[3]; ///< offsets of its per-direction first control point indices
};

/// A Bézier element of a NURBS volume.
struct ElementRef
{
  int volume;
  int element[3];
};

IGA_HD inline VolumeView<const double> viewOf(
  const Node& node, const double* pool, const PatchShape* shapes)
{
  return VolumeView<const double>(pool + node.coeff, shapes[node.patch].degree, kScreenChannels);
}

/// Orders (pixel, node) tuples by pixel, then nearest node depth, then node.
struct TupleOrder
{
  const Node* nodes;
  IGA_HD bool operator()(const Tuple& a, const Tuple& b) const
  {
    if (a.pixel != b.pixel)
    {
      return a.pixel < b.pixel;
    }
    const double za = nodes[a.node].info.box.lo[2], zb = nodes[b.node].info.box.lo[2];
    return za < zb || (za == zb && a.node < b.node);
  }
};

struct HitPixelOrder
{
  IGA_HD bool operator()(const RawHit& a, const RawHit& b) const { return a.pixel < b.pixel; }
};

/// Writes the start offsets of pixels [first, first + pixelCount] (one past the last: the end)
/// into offsets[first ...], for records sorted by pixel, all of them in that range: per pixel, a
/// binary search for its first record. (Filling the gaps between records, one thread a record,
/// left a sparse frame's last thread two million pixels to write: 50 ms at 1080p.)
template<class Record>
void pixelOffsets(
  const Record* records, size_t count, size_t first, size_t pixelCount, uint32_t* offsets)
{
  forEach(pixelCount + 1,
    [=] IGA_HD(size_t k)
    {
      const size_t p = first + k;
      size_t lo = 0, hi = count;
      while (lo < hi)
      {
        const size_t mid = (lo + hi) / 2;
        if (records[mid].pixel < p)
        {
          lo = mid + 1;
        }
        else
        {
          hi = mid;
        }
      }
      offsets[p] = uint32_t(lo);
    });
}

/// What the device's check of the world patches found.
struct PatchSummary
{
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  unsigned invalid = 0; ///< patches with a non-finite value or a non-positive weight

  double range() const { return hi > lo ? hi - lo : 1.0; }
};

struct CombineSummaries
{
  IGA_HD PatchSummary operator()(const PatchSummary& a, const PatchSummary& b) const
  {
    PatchSummary c;
    c.lo = a.lo < b.lo ? a.lo : b.lo;
    c.hi = a.hi > b.hi ? a.hi : b.hi;
    c.invalid = a.invalid + b.invalid;
    return c;
  }
};

enum SplitState : uint8_t
{
  Keep = 0,
  Split = 1,
  AtDepthCap = 2,
  OverBudget = 3
};

/// The device engine. Its arrays persist from frame to frame (a pool that only grows), so a
/// steady stream of frames allocates nothing. Every member is public because CUDA's extended
/// lambdas may not live in private member functions.
struct Driver
{
  void render(const std::vector<BezierVolume<double>>& patches, const View& view,
    const Settings& settings, GBuffer& out, FrameReport& report)
  {
    this->draw(
      [&] { this->uploadPatches(patches, settings, report); }, view, settings, out, report);
  }

  void renderNurbs(const NurbsVolumes& volumes, const View& view, const Settings& settings,
    GBuffer& out, FrameReport& report)
  {
    this->draw([&] { this->uploadNurbs(volumes, settings, report); }, view, settings, out, report);
  }

  /// A frame: `upload` puts the world patches on the device (or finds them there), then the
  /// frame proper.
  template<class Upload>
  void draw(
    Upload upload, const View& view, const Settings& settings, GBuffer& out, FrameReport& report)
  {
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point t)
    { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
    const Clock::time_point start = Clock::now();
    report.uploadedBytes = 0;
    checkSettings(settings); // before the upload, which reads the transfer chunk
    upload();
    report.msInput = ms(start);
    this->prepareFrame(view, settings, report);
    this->Report = &report;
    this->Settings_ = &settings;
    this->Peak = 0;
    this->PeakBudgeted = 0;
    unsigned long long* unresolvedTuples = sized(this->UnresolvedTuples, 2);
    thrust::fill(exec(), unresolvedTuples, unresolvedTuples + 2, 0ull);
    sized(this->Totals, 6);
    report.msSetup = ms(start);

    this->Stages.begin();
    report.bands = drawInBands(this->rowBandsOfFrame(settings), this->Frame,
      [&]
      {
        this->sweepAndGroup();
        this->Stages.end(report.msSweepAndGroup);
        this->sharedSubdivisionTrees();
      });
    this->Stages.finish();
    const Clock::time_point stage = Clock::now();
    this->fillGBuffer(view, settings, out);
    report.msGBuffer = ms(stage);
    report.unresolvedPixels =
      thrust::count(exec(), this->Unresolved.begin(), this->Unresolved.end(), 1);
    unsigned long long tallies[2];
    download(unresolvedTuples, 2, tallies);
    report.unresolvedAtDepthCap = size_t(tallies[0]);
    report.unresolvedAtBudget = size_t(tallies[1]);
    report.peakBytes = this->Peak;
    report.peakBudgetedBytes = this->PeakBudgeted;
    report.msTotal = ms(start);
  }

  /// Checks and copies the world patches to the device, unless the settings' data version
  /// says the copy already there is current.
  void uploadPatches(
    const std::vector<BezierVolume<double>>& patches, const Settings& settings, FrameReport& report)
  {
    const bool current = !this->FromNurbs && settings.dataVersion != 0 &&
                         settings.dataVersion == this->DataVersion &&
                         patches.size() == this->Shapes.size() &&
                         settings.surfaceAttribute == this->SurfaceAttribute &&
                         settings.colorAttribute == this->ColorAttribute;
    if (current)
    {
      return;
    }
    // Until the copy below is complete the device holds neither these patches nor the elements
    // of NURBS volumes it may have held: the copy overwrites their shapes and coefficients.
    this->DataVersion = 0;
    this->ExtractionVersion = 0;
    this->FromNurbs = false;
    // Shapes are checked here, control point values on the device; checkPatches names the
    // first problem when there is one.
    std::vector<PatchShape> shapes(patches.size());
    size_t world = 0, screen = 0;
    for (size_t p = 0; p < patches.size(); ++p)
    {
      const auto v = patches[p].view();
      if (!usableShape(v.degree, v.channels, settings))
      {
        throwFirstProblem(patches, settings);
      }
      for (int d = 0; d < 3; ++d)
      {
        shapes[p].degree[d] = v.degree[d];
      }
      shapes[p].channels = v.channels;
      shapes[p].screenValues = v.pointCount() * kScreenChannels;
      shapes[p].world = world;
      shapes[p].screen = screen;
      world += size_t(v.valueCount());
      screen += size_t(shapes[p].screenValues);
    }
    HostSequence coefficients;
    for (const BezierVolume<double>& patch : patches)
    {
      const auto v = patch.view();
      coefficients.append(v.coeffs, size_t(v.valueCount()));
    }
    this->setShapes(shapes, report);
    this->uploadStaged(coefficients, this->World, settings);
    report.uploadedBytes += world * sizeof(double);
    const PatchSummary summary = this->summarizePatches(settings.surfaceAttribute);
    if (summary.invalid > 0)
    {
      throwFirstProblem(patches, settings);
    }
    this->AttributeRange = summary.range();
    this->SurfaceAttribute = settings.surfaceAttribute;
    this->ColorAttribute = settings.colorAttribute;
    this->DataVersion = settings.dataVersion;
    ++this->Uploads;
  }

  /// Sends the patch shapes, unless the device holds the same (a deforming set keeps them).
  void setShapes(const std::vector<PatchShape>& shapes, FrameReport& report)
  {
    if (!sameShapes(shapes, this->HostShapes))
    {
      this->HostShapes.clear(); // until the copy below is complete
      this->Shapes = shapes;
      this->HostShapes = shapes;
      report.uploadedBytes += shapes.size() * sizeof(PatchShape);
    }
    this->ScreenValues = 0;
    for (const PatchShape& shape : shapes)
    {
      this->ScreenValues += size_t(shape.screenValues);
    }
  }

  /// Copies NURBS volumes to the device and extracts their Bézier elements there: the
  /// extraction operators when the extraction version changes, the control nets when the data
  /// version does (a deforming volume sends only its net).
  void uploadNurbs(const NurbsVolumes& volumes, const Settings& settings, FrameReport& report)
  {
    const bool extractionsCurrent = this->FromNurbs && volumes.extractionVersion != 0 &&
                                    volumes.extractionVersion == this->ExtractionVersion &&
                                    volumes.extractions.size() == this->Volumes.size() &&
                                    volumes.channels == this->Channels;
    if (!extractionsCurrent)
    {
      this->ExtractionVersion = 0; // until the copy below is complete
      this->DataVersion = 0;
      std::vector<VolumeTable> tables(volumes.extractions.size());
      std::vector<ElementRef> elements;
      std::vector<PatchShape> shapes;
      std::vector<double> matrices;
      std::vector<int> firstBasis;
      size_t net = 0, world = 0, screen = 0;
      for (size_t v = 0; v < tables.size(); ++v)
      {
        const BezierExtraction<double, 3>& extraction = *volumes.extractions[v];
        VolumeTable& table = tables[v];
        table.net = net;
        size_t points = 1;
        for (int d = 0; d < 3; ++d)
        {
          const ExtractionOperator1D<double>& op = extraction.direction(d);
          table.degree[d] = op.degree;
          table.netSize[d] = extraction.netSize(d);
          table.matrices[d] = matrices.size();
          table.firstBasis[d] = firstBasis.size();
          matrices.insert(matrices.end(), op.matrices.begin(), op.matrices.end());
          firstBasis.insert(firstBasis.end(), op.firstBasis.begin(), op.firstBasis.end());
          points *= size_t(table.netSize[d]);
        }
        net += points * size_t(volumes.channels);
        const int order = (table.degree[0] + 1) * (table.degree[1] + 1) * (table.degree[2] + 1);
        for (int e = 0; e < extraction.elementCount(); ++e)
        {
          ElementRef ref;
          ref.volume = int(v);
          extraction.elementIndex(e, ref.element);
          elements.push_back(ref);
          PatchShape shape;
          for (int d = 0; d < 3; ++d)
          {
            shape.degree[d] = table.degree[d];
          }
          shape.channels = volumes.channels;
          shape.screenValues = order * kScreenChannels;
          shape.world = world;
          shape.screen = screen;
          world += size_t(order) * volumes.channels;
          screen += size_t(shape.screenValues);
          shapes.push_back(shape);
        }
      }
      this->setShapes(shapes, report);
      this->Volumes = tables;
      this->Elements = elements;
      this->Matrices = matrices;
      this->FirstBasis = firstBasis;
      this->NetValues = net;
      this->WorldValues = world;
      report.uploadedBytes += tables.size() * sizeof(VolumeTable) +
                              elements.size() * sizeof(ElementRef) +
                              matrices.size() * sizeof(double) + firstBasis.size() * sizeof(int);
      this->Channels = volumes.channels;
      this->ExtractionVersion = volumes.extractionVersion;
      this->FromNurbs = true;
    }
    const bool netsCurrent = extractionsCurrent && settings.dataVersion != 0 &&
                             settings.dataVersion == this->DataVersion &&
                             settings.surfaceAttribute == this->SurfaceAttribute &&
                             settings.colorAttribute == this->ColorAttribute;
    if (netsCurrent)
    {
      return;
    }
    this->DataVersion = 0;
    checkAttributes(volumes.channels, settings, "volume 0");
    HostSequence nets;
    for (const std::vector<double>* net : volumes.nets)
    {
      nets.append(net->data(), net->size());
    }
    this->uploadStaged(nets, this->Nets, settings);
    report.uploadedBytes += this->NetValues * sizeof(double);

    // Extraction, one element per thread; a scratch block of twice its size each.
    const size_t elementCount = this->Elements.size();
    const ElementRef* elements = raw(this->Elements);
    const VolumeTable* tables = raw(this->Volumes);
    const PatchShape* shapes = raw(this->Shapes);
    const double* matrices = raw(this->Matrices);
    const int* firstBasis = raw(this->FirstBasis);
    const double* net = raw(this->Nets);
    double* world = sized(this->World, this->WorldValues);
    double* scratch = sized(this->Scratch, 2 * this->WorldValues);
    const int channels = volumes.channels;
    forEach(elementCount,
      [=] IGA_HD(size_t e)
      {
        const ElementRef& ref = elements[e];
        const VolumeTable& table = tables[ref.volume];
        const double* operators[3];
        int first[3];
        for (int d = 0; d < 3; ++d)
        {
          const int order = table.degree[d] + 1;
          operators[d] = matrices + table.matrices[d] + size_t(ref.element[d]) * order * order;
          first[d] = firstBasis[table.firstBasis[d] + ref.element[d]];
        }
        extractElement<double, 3>(net + table.net, table.netSize, channels, table.degree, operators,
          first, world + shapes[e].world, scratch + 2 * shapes[e].world);
      });
    // Elements of checked nets are valid: extraction takes convex combinations.
    this->AttributeRange = this->summarizePatches(settings.surfaceAttribute).range();
    this->SurfaceAttribute = settings.surfaceAttribute;
    this->ColorAttribute = settings.colorAttribute;
    this->DataVersion = settings.dataVersion;
    ++this->Uploads;
  }

  /// Over the world patches on the device: how many have an invalid control point, and the
  /// surface attribute's range over the others, as checkPatches computes it.
  PatchSummary summarizePatches(int surfaceAttribute)
  {
    const PatchShape* shapes = raw(this->Shapes);
    const double* world = raw(this->World);
    const int attribute = kFirstAttributeChannel + surfaceAttribute;
    return thrust::transform_reduce(
      exec(), thrust::counting_iterator<size_t>(0),
      thrust::counting_iterator<size_t>(this->Shapes.size()),
      [=] IGA_HD(size_t p)
      {
        const VolumeView<const double> patch(
          world + shapes[p].world, shapes[p].degree, shapes[p].channels);
        PatchSummary summary;
        if (firstInvalidPoint(patch) >= 0)
        {
          summary.invalid = 1;
        }
        else
        {
          rationalRange(patch, attribute, kWeightChannel, summary.lo, summary.hi);
        }
        return summary;
      },
      PatchSummary(), CombineSummaries());
  }

  /// Throws checkPatches' message for the first bad patch.
  [[noreturn]] static void throwFirstProblem(
    const std::vector<BezierVolume<double>>& patches, const Settings& settings)
  {
    checkPatches(patches, settings);
    // Not reached: the device tests the same conditions as the host.
    throw std::invalid_argument("a patch failed the device's check of its control points");
  }

  /// The frame's preparation on the device: screen and shading patches of every patch, and the
  /// subdivision-tree roots, in the CPU driver's order. The rare roots straddling the eye plane
  /// are split on the host (addRoot) and their parts sent up.
  void prepareFrame(const View& view, const Settings& settings, FrameReport& report)
  {
    FramePlan plan = planView(view, settings, this->AttributeRange, report);
    report.threads = 0;
    this->Isovalues = settings.isovalues;
    report.uploadedBytes += settings.isovalues.size() * sizeof(double);
    this->Frame = plan.frame;
    this->Frame.isovalues = raw(this->Isovalues);
    this->PixelCount = size_t(settings.width) * settings.height;
    this->Unresolved.resize(this->PixelCount);
    thrust::fill(exec(), this->Unresolved.begin(), this->Unresolved.end(), uint8_t(0));
    this->BestDepth.resize(this->PixelCount);
    thrust::fill(exec(), this->BestDepth.begin(), this->BestDepth.end(),
      std::numeric_limits<double>::infinity());
    this->HitCount = 0;

    const size_t patchCount = this->Shapes.size();
    const PatchShape* shapes = raw(this->Shapes);
    const double* world = raw(this->World);
    double* screen = sized(this->InitialPool, this->ScreenValues);
    double* shading = sized(this->ShadingPool, this->ScreenValues);
    const Matrix4<double> windowFromWorld = plan.windowFromWorld;
    const int surface = kFirstAttributeChannel + settings.surfaceAttribute;
    const int colour =
      settings.colorAttribute >= 0 ? kFirstAttributeChannel + settings.colorAttribute : -1;
    // Shading patches do not depend on the view: made again only for new data.
    const bool shade = this->ShadedUpload != this->Uploads;
    this->ShadedUpload = this->Uploads;
    forEach(patchCount,
      [=] IGA_HD(size_t p)
      {
        const PatchShape& shape = shapes[p];
        const VolumeView<const double> patch(world + shape.world, shape.degree, shape.channels);
        makeScreenPatch<double>(patch, windowFromWorld, surface, screen + shape.screen);
        if (shade)
        {
          makeShadingPatch(patch, surface, colour, shading + shape.screen);
        }
      });

    // Roots: per (patch, isovalue), dropped (0), in front of the eye (1) or straddling it (2).
    const size_t isoCount = settings.isovalues.size();
    const size_t rootCount = patchCount * isoCount;
    Node* roots = sized(this->Roots, rootCount);
    uint8_t* state = sized(this->RootStates, rootCount);
    const FrameConstants frame = this->Frame;
    forEach(rootCount,
      [=] IGA_HD(size_t r)
      {
        Node root = rootNode(int(r / isoCount), int(r % isoCount));
        const PatchShape& shape = shapes[root.patch];
        const VolumeView<const double> view(screen + shape.screen, shape.degree, kScreenChannels);
        root.info = analyzeNode(view, frame.isovalues[root.iso], frame.clip);
        root.coeff = shape.screen;
        roots[r] = root;
        state[r] = !worthKeeping(root.info, frame)                 ? 0
                   : root.info.status == ProjectionStatus::InFront ? 1
                                                                   : 2;
      });
    uint32_t* straddling = sized(this->ToSplit, rootCount);
    const size_t straddlingCount = thrust::copy_if(exec(), thrust::counting_iterator<uint32_t>(0),
                                     thrust::counting_iterator<uint32_t>(uint32_t(rootCount)),
                                     state, straddling, [] IGA_HD(uint8_t s) { return s == 2; }) -
                                   straddling;
    // Host side of the straddling roots: their parts, and how many each gives.
    std::vector<uint32_t> straddlers(straddlingCount), partCounts(straddlingCount);
    download(straddling, straddlingCount, straddlers.data());
    FramePlan parts = plan;
    for (size_t k = 0; k < straddlingCount; ++k)
    {
      const int p = int(straddlers[k] / isoCount), iso = int(straddlers[k] % isoCount);
      const PatchShape& shape = this->HostShapes[p];
      std::vector<double> worldValues(
        size_t(shape.screenValues / kScreenChannels) * shape.channels);
      download(world + shape.world, worldValues.size(), worldValues.data());
      const VolumeView<const double> patch(worldValues.data(), shape.degree, shape.channels);
      std::vector<double> coefficients(size_t(shape.screenValues));
      makeScreenPatch<double>(patch, plan.windowFromWorld, surface, coefficients.data());
      const size_t before = parts.initialNodes.size();
      addRoot(parts, shape.degree, rootNode(p, iso), coefficients.data(), settings, report);
      partCounts[k] = uint32_t(parts.initialNodes.size() - before);
    }
    for (Node& node : parts.initialNodes)
    {
      node.coeff += this->ScreenValues; // their coefficients follow the screen patches
    }
    uint64_t* counts = sized(this->Counts, rootCount + 1);
    forEach(rootCount, [=] IGA_HD(size_t r) { counts[r] = state[r] == 1 ? 1 : 0; });
    partCounts.push_back(0); // the scan below reads one past the last
    this->Index = partCounts;
    const uint32_t* partCount = raw(this->Index);
    forEach(straddlingCount, [=] IGA_HD(size_t k) { counts[straddling[k]] = partCount[k]; });
    const size_t total = scanCounts(this->Counts, rootCount);
    Node* initial = sized(this->InitialNodes, total);
    forEach(rootCount,
      [=] IGA_HD(size_t r)
      {
        if (state[r] == 1)
        {
          initial[counts[r]] = roots[r];
        }
      });
    this->NextNodes = parts.initialNodes;
    const Node* partNodes = raw(this->NextNodes);
    this->Offsets.resize(straddlingCount + 1);
    thrust::exclusive_scan(
      exec(), partCount, partCount + straddlingCount + 1, this->Offsets.begin(), uint64_t(0));
    const uint64_t* partStart = raw(this->Offsets);
    forEach(straddlingCount,
      [=] IGA_HD(size_t k)
      {
        for (uint32_t n = 0; n < partCount[k]; ++n)
        {
          initial[counts[straddling[k]] + n] = partNodes[partStart[k] + n];
        }
      });
    this->InitialPool.resize(this->ScreenValues + parts.initialPool.size());
    if (!parts.initialPool.empty())
    {
      copyToDevice(raw(this->InitialPool) + this->ScreenValues, parts.initialPool.data(),
        parts.initialPool.size() * sizeof(double));
    }
    report.uploadedBytes += straddlingCount * sizeof(uint32_t) +
                            parts.initialNodes.size() * sizeof(Node) +
                            parts.initialPool.size() * sizeof(double);
  }

  template<class T>
  static size_t bytesOf(const Array<T>& v)
  {
    return v.size() * sizeof(T);
  }

  /// The band's work items and the loop's arrays, what the memory budget caps, at their sizes
  /// in use (each array keeps its largest allocation between frames: the device's pool).
  size_t budgetedBytes() const
  {
    return bytesOf(this->Items) + bytesOf(this->ItemNodes) + bytesOf(this->Nodes) +
           bytesOf(this->Pool) + bytesOf(this->NextNodes) + bytesOf(this->NextPool) +
           bytesOf(this->Children) + bytesOf(this->ChildPool) + bytesOf(this->Tuples) +
           bytesOf(this->Next) + bytesOf(this->Outcomes) + bytesOf(this->Solution) +
           bytesOf(this->HitIndex) + bytesOf(this->Counts) + bytesOf(this->Taken) +
           bytesOf(this->ToSplit) + bytesOf(this->SplitFlags) + bytesOf(this->SplitIndex) +
           bytesOf(this->ChildValues) + bytesOf(this->SplitCost) + bytesOf(this->FailedTuples) +
           bytesOf(this->NodeBytes) + bytesOf(this->Deferred) + bytesOf(this->KeepFlags) +
           bytesOf(this->Used) + bytesOf(this->FirstTuple) + bytesOf(this->Index) +
           bytesOf(this->Offsets);
  }

  /// The copies of the input, the per-pixel arrays and the hits: what the budget does not cap.
  size_t fixedBytes() const
  {
    return bytesOf(this->World) + bytesOf(this->Roots) + bytesOf(this->InitialNodes) +
           bytesOf(this->InitialPool) + bytesOf(this->ShadingPool) + bytesOf(this->ItemOffsets) +
           bytesOf(this->Cursor) + bytesOf(this->Ends) + bytesOf(this->BestDepth) +
           bytesOf(this->Unresolved) + bytesOf(this->PixelSolves) + bytesOf(this->Hits);
  }

  /// Marks the iteration's scratch arrays empty, out of the working set (they keep their
  /// allocations for the next iteration).
  void endIteration()
  {
    auto markEmpty = [](auto&... arrays) { (arrays.resize(0), ...); };
    markEmpty(this->NextNodes, this->Children, this->NextPool, this->ChildPool, this->Solution,
      this->Counts, this->ChildValues, this->SplitCost, this->NodeBytes, this->Offsets,
      this->FailedTuples, this->HitIndex, this->ToSplit, this->SplitIndex, this->Index,
      this->FirstTuple, this->Outcomes, this->SplitFlags, this->Deferred, this->KeepFlags,
      this->Used, this->Next);
  }

  void trackMemory()
  {
    const size_t budgeted = this->budgetedBytes();
    this->PeakBudgeted = std::max(this->PeakBudgeted, budgeted);
    this->Peak = std::max(this->Peak, budgeted + this->fixedBytes());
  }

  // ---- sweep and group ---------------------------------------------------------------------

  /// The bands of rows the frame is drawn in (rowBands), from the initial nodes' boxes.
  std::vector<int> rowBandsOfFrame(const Settings& settings)
  {
    const Node* nodes = raw(this->InitialNodes);
    const FrameConstants frame = this->Frame;
    const size_t rows = size_t(frame.height) + 1;
    unsigned long long* differences = sized(this->RowPairs, rows);
    thrust::fill(exec(), differences, differences + rows, 0ull);
    forEach(this->InitialNodes.size(),
      [=] IGA_HD(size_t n)
      {
        addRowPairs(nodes[n].info.box, frame,
          [=](int row, uint64_t value) { addAtomically(differences + row, value); });
      });
    std::vector<unsigned long long> read(rows);
    download(differences, rows, read.data());
    return rowBands(std::vector<uint64_t>(read.begin(), read.end()).data(), settings);
  }

  /// Per pixel of the pass, the initial nodes whose boxes cover it, sorted by nearest depth.
  void sweepAndGroup()
  {
    const size_t nodeCount = this->InitialNodes.size();
    const Node* nodes = raw(this->InitialNodes);
    const FrameConstants frame = this->Frame;
    uint64_t* counts = sized(this->Counts, nodeCount + 1);
    forEach(
      nodeCount, [=] IGA_HD(size_t n) { counts[n] = coveredPixelCount(nodes[n].info.box, frame); });
    const size_t total = scanCounts(this->Counts, nodeCount);
    Tuple* items = sized(this->Items, total);
    // One thread per (pixel, node) pair.
    forEach(total,
      [=] IGA_HD(size_t k)
      {
        const uint32_t n = ownerOf(counts, nodeCount, k);
        items[k] = { uint32_t(coveredPixel(nodes[n].info.box, frame, uint32_t(k - counts[n]))), n };
      });
    thrust::sort(exec(), items, items + total, TupleOrder{ nodes });
    pixelOffsets(items, total, passFirstPixel(this->Frame), passPixelCount(this->Frame),
      sized(this->ItemOffsets, this->PixelCount + 1));
    uint32_t* itemNodes = sized(this->ItemNodes, total);
    forEach(total, [=] IGA_HD(size_t k) { itemNodes[k] = items[k].node; });
    this->trackMemory();
  }

  // ---- shared subdivision trees ------------------------------------------------------------

  void sharedSubdivisionTrees()
  {
    const size_t first = passFirstPixel(this->Frame), count = passPixelCount(this->Frame);
    const size_t pixels = this->PixelCount;
    const uint32_t* offsets = raw(this->ItemOffsets);
    thrust::copy(
      exec(), offsets + first, offsets + first + count, sized(this->Cursor, pixels) + first);
    sized(this->Ends, pixels);
    uint32_t* certified = sized(this->PixelSolves, pixels) + first;
    thrust::fill(exec(), certified, certified + count, uint32_t(0));
    for (;;)
    {
      const Node* initial = raw(this->InitialNodes);
      const uint32_t* items = raw(this->ItemNodes);
      const uint32_t* cursor = raw(this->Cursor);
      const double* best = raw(this->BestDepth);
      uint32_t* ends = raw(this->Ends);
      const bool firstHit = this->Frame.firstHitOnly;
      forEach(count,
        [=] IGA_HD(size_t k)
        {
          const size_t p = first + k;
          ends[p] = groupEnd(initial, items, cursor[p], offsets[p + 1], best[p], firstHit);
        });
      const size_t total = thrust::transform_reduce(
        exec(), thrust::counting_iterator<size_t>(first),
        thrust::counting_iterator<size_t>(first + count),
        [=] IGA_HD(size_t p) { return size_t(ends[p] - cursor[p]); }, size_t(0),
        thrust::plus<size_t>());
      this->Stages.end(this->Report->msSweepAndGroup);
      if (total == 0)
      {
        break;
      }
      this->solveRound();
      this->Cursor.swap(this->Ends);
      sized(this->Ends, pixels);
    }
    this->Report->newtonSolves +=
      thrust::reduce(exec(), certified, certified + count, size_t(0), thrust::plus<size_t>());
  }

  /// Gathers the nodes flagged in `take` (with their coefficients) into Nodes and Pool, in
  /// order, followed by the flagged nodes of a second source; Index holds the new index of each.
  /// Returns the node count. `alsoRead`, when given, is a device value read back in the same
  /// wait as the count, into `alsoReadValue`.
  size_t gatherNodes(const Node* first, const double* firstPool, const uint8_t* firstTake,
    size_t firstCount, const Node* second, const double* secondPool, const uint8_t* secondTake,
    size_t secondCount, bool asRound, const uint64_t* alsoRead = nullptr,
    size_t* alsoReadValue = nullptr)
  {
    const size_t count = firstCount + secondCount;
    const PatchShape* shapes = raw(this->Shapes);
    uint32_t* index = sized(this->Index, count + 1);
    uint64_t* offsets = sized(this->Offsets, count + 1);
    forEach(count,
      [=] IGA_HD(size_t n)
      {
        const bool fromFirst = n < firstCount;
        const bool take = fromFirst ? firstTake[n] : secondTake[n - firstCount];
        const Node& node = fromFirst ? first[n] : second[n - firstCount];
        index[n] = take ? 1 : 0;
        offsets[n] = take ? uint64_t(shapes[node.patch].screenValues) : 0;
      });
    thrust::exclusive_scan(exec(), index, index + count + 1, index);
    thrust::exclusive_scan(exec(), offsets, offsets + count + 1, offsets);
    uint64_t* totals = raw(this->Totals);
    forEach(1,
      [=] IGA_HD(size_t)
      {
        totals[0] = index[count];
        totals[1] = offsets[count];
        totals[2] = alsoRead ? *alsoRead : 0;
      });
    uint64_t read[3];
    download(totals, 3, read);
    const size_t kept = size_t(read[0]), values = size_t(read[1]);
    if (alsoReadValue)
    {
      *alsoReadValue = size_t(read[2]);
    }
    Node* nodes = sized(this->NextNodes, kept);
    double* pool = sized(this->NextPool, values);
    forEach(count,
      [=] IGA_HD(size_t n)
      {
        const bool fromFirst = n < firstCount;
        if (!(fromFirst ? firstTake[n] : secondTake[n - firstCount]))
        {
          return;
        }
        Node node = fromFirst ? first[n] : second[n - firstCount];
        const double* source = (fromFirst ? firstPool : secondPool) + node.coeff;
        const int valueCount = shapes[node.patch].screenValues;
        for (int v = 0; v < valueCount; ++v)
        {
          pool[offsets[n] + v] = source[v];
        }
        node.coeff = offsets[n];
        if (asRound)
        {
          node.initial = uint32_t(n);
          node.implicit = true;
        }
        else if (fromFirst && !node.implicit)
        {
          // Explicit children are analysed once they are known to receive pixels.
          const auto view = viewOf(node, pool, shapes);
          analyzeNodeSolver(view, node.info);
          analyzeNodeCentre(view, node.info);
        }
        nodes[index[n]] = node;
      });
    this->Nodes.swap(this->NextNodes);
    this->Pool.swap(this->NextPool);
    return kept;
  }

  /// The SST loop over one round of SAG groups: overlap, solution, subdivision and compaction
  /// until no tuple and no implicit node is left. The host waits for the device four times an
  /// iteration, each time for sizes it must allocate: the overlap's candidates and tuples, the
  /// subdivision's children (with the solution's hits), and the compaction's nodes and tuples.
  void solveRound()
  {
    FrameReport& report = *this->Report;
    const Settings& settings = *this->Settings_;
    const FrameConstants frame = this->Frame;
    const PatchShape* shapes = raw(this->Shapes);
    const bool firstHit = frame.firstHitOnly;
    uint64_t* totals = raw(this->Totals);

    // This round's initial nodes, all implicit.
    {
      const size_t initialCount = this->InitialNodes.size();
      uint8_t* present = sized(this->Present, initialCount);
      thrust::fill(exec(), present, present + initialCount, uint8_t(0));
      const uint32_t* items = raw(this->ItemNodes);
      const uint32_t* cursor = raw(this->Cursor);
      const uint32_t* ends = raw(this->Ends);
      const size_t first = passFirstPixel(this->Frame);
      forEach(passPixelCount(this->Frame),
        [=] IGA_HD(size_t pass)
        {
          const size_t p = first + pass;
          for (uint32_t k = cursor[p]; k < ends[p]; ++k)
          {
            present[items[k]] = 1;
          }
        });
      this->NodeCount = this->gatherNodes(raw(this->InitialNodes), raw(this->InitialPool), present,
        initialCount, nullptr, nullptr, nullptr, 0, true);
    }
    size_t tupleCount = 0;
    while (this->NodeCount > 0)
    {
      ++report.iterations;
      report.maxPatches = std::max(report.maxPatches, this->NodeCount);
      const size_t nodeCount = this->NodeCount;
      Node* nodes = raw(this->Nodes);
      const double* pool = raw(this->Pool);
      const uint32_t* items = raw(this->ItemNodes);
      const uint32_t* cursor = raw(this->Cursor);
      const uint32_t* ends = raw(this->Ends);

      // Overlap stage: implicit nodes that are ready become tuples of the pixels whose centres
      // their boxes cover (members of the round, not behind a nearer hit), as many as the
      // memory budget takes; the others wait.
      {
        // Candidates: the covered pixels of the ready nodes, one thread each; those the round
        // takes become tuples, in node and row order. Each implicit node's bytes are summed
        // too: the budget keeps room to carry every one over unsplit.
        const double* best = raw(this->BestDepth);
        uint64_t* counts = sized(this->Counts, nodeCount + 1);
        uint64_t* implicitBytes = sized(this->NodeBytes, nodeCount + 1);
        forEach(nodeCount,
          [=] IGA_HD(size_t n)
          {
            counts[n] = nodes[n].implicit && readyForTuples(nodes[n], frame)
                          ? coveredPixelCount(nodes[n].info.box, frame)
                          : 0;
            implicitBytes[n] =
              nodes[n].implicit ? nodeBytes(1, shapes[nodes[n].patch].screenValues) : 0;
          });
        thrust::exclusive_scan(exec(), implicitBytes, implicitBytes + nodeCount + 1, implicitBytes);
        const size_t candidates = scanCounts(this->Counts, nodeCount);
        uint32_t* taken = sized(this->Taken, candidates + 1);
        forEach(candidates,
          [=] IGA_HD(size_t k)
          {
            const uint32_t n = ownerOf(counts, nodeCount, k);
            const size_t p = coveredPixel(nodes[n].info.box, frame, uint32_t(k - counts[n]));
            taken[k] = roundTakesPixel(nodes[n], best[p], items, cursor[p], ends[p], frame) ? 1 : 0;
          });
        thrust::exclusive_scan(exec(), taken, taken + candidates + 1, taken);
        const uint64_t itemCount = this->ItemNodes.size();
        const uint64_t held = loopBytes(itemCount, nodeCount, this->Pool.size(), tupleCount);
        const uint64_t budget = settings.memoryBudgetBytes;
        const bool noTuples = tupleCount == 0;
        forEach(1,
          [=] IGA_HD(size_t)
          {
            const size_t admitted =
              admittedNodes(nodeCount, budget, held + implicitBytes[nodeCount], itemCount, noTuples,
                [=](size_t n) { return taken[counts[n + 1]]; });
            totals[0] = admitted;
            totals[1] = taken[counts[admitted]];
          });
        uint64_t read[2];
        download(totals, 2, read);
        const size_t admitted = size_t(read[0]), added = size_t(read[1]);
        checkIndexable(tupleCount + added);
        this->Tuples.resize(tupleCount + added);
        Tuple* tuples = raw(this->Tuples) + tupleCount;
        forEach(candidates,
          [=] IGA_HD(size_t k)
          {
            if (taken[k + 1] != taken[k] && taken[k] < added)
            {
              const uint32_t n = ownerOf(counts, nodeCount, k);
              tuples[taken[k]] = {
                uint32_t(coveredPixel(nodes[n].info.box, frame, uint32_t(k - counts[n]))), n
              };
            }
          });
        forEach(admitted,
          [=] IGA_HD(size_t n)
          {
            Node& node = nodes[n];
            if (node.implicit && readyForTuples(node, frame))
            {
              node.implicit = false;
              analyzeNodeCentre(viewOf(node, pool, shapes), node.info);
            }
          });
        tupleCount += added;
        this->Taken.resize(0); // scratch: out of the working set
      }
      report.maxTuples = std::max(report.maxTuples, tupleCount);
      this->Stages.end(report.msOverlap);

      // Solution stage: each pixel's tuples in order of nearest depth by one thread, so that in
      // first-hit mode a hit drops the tuples behind it at once; the thread of a pixel's first
      // tuple takes its run. (A thread per pixel of the image cost more than the solutions in
      // sparse frames: the kernel's register use lets few of those mostly idle threads run at
      // once.) The hits are appended once the subdivision stage has read their count back.
      Tuple* tuples = raw(this->Tuples);
      uint8_t* outcome = sized(this->Outcomes, tupleCount);
      double* solution = sized(this->Solution, 4 * tupleCount);
      thrust::sort(exec(), tuples, tuples + tupleCount, TupleOrder{ nodes });
      uint32_t* hitIndex = sized(this->HitIndex, tupleCount + 1);
      {
        double* bestDepth = raw(this->BestDepth);
        uint32_t* certified = raw(this->PixelSolves);
        forEach(tupleCount,
          [=] IGA_HD(size_t first)
          {
            const uint32_t pixel = tuples[first].pixel;
            if (first > 0 && tuples[first - 1].pixel == pixel)
            {
              return;
            }
            size_t end = first + 1;
            while (end < tupleCount && tuples[end].pixel == pixel)
            {
              ++end;
            }
            bestDepth[pixel] = solvePixelTuples(
              tuples, uint32_t(first), uint32_t(end), pixel, nodes,
              [=](const Node& node) { return viewOf(node, pool, shapes); }, bestDepth[pixel], frame,
              outcome, solution, certified[pixel]);
            for (size_t t = first; t < end; ++t)
            {
              hitIndex[t] = outcome[t] == Solved ? 1 : 0;
            }
          });
      }
      thrust::exclusive_scan(exec(), hitIndex, hitIndex + tupleCount + 1, hitIndex);
      this->Stages.end(report.msSolution);

      // Subdivision stage: split the nodes some pixel failed on, and the implicit ones whose
      // boxes still cover pixels.
      const double* best = raw(this->BestDepth);
      uint8_t* split = sized(this->SplitFlags, nodeCount);
      thrust::fill(exec(), split, split + nodeCount, uint8_t(Keep));
      unsigned long long* failed = sized(this->FailedTuples, nodeCount); // per node
      thrust::fill(exec(), failed, failed + nodeCount, 0ull);
      forEach(tupleCount,
        [=] IGA_HD(size_t t)
        {
          if (outcome[t] == Failed && firstHit &&
              nodes[tuples[t].node].info.box.lo[2] > best[tuples[t].pixel])
          {
            outcome[t] = Dropped; // a nearer hit was found this iteration
          }
          if (outcome[t] == Failed)
          {
            split[tuples[t].node] = Split;
            addAtomically(&failed[tuples[t].node], 1);
          }
        });
      // Per node in order: whether it is to be split, and the running totals of split nodes, of
      // their children's coefficients and of what splitting adds (splitBytes); the bytes of the
      // implicit nodes that may be carried over unsplit (those waiting for the overlap stage,
      // and those to split).
      uint32_t* splitIndex = sized(this->SplitIndex, nodeCount + 1);
      uint64_t* childValues = sized(this->ChildValues, nodeCount + 1);
      uint64_t* splitCost = sized(this->SplitCost, nodeCount + 1);
      uint64_t* carriedBytes = sized(this->NodeBytes, nodeCount + 1);
      forEach(nodeCount,
        [=] IGA_HD(size_t n)
        {
          const bool waiting = nodes[n].implicit && readyForTuples(nodes[n], frame);
          if (nodes[n].implicit && !waiting)
          {
            split[n] = coveredPixelCount(nodes[n].info.box, frame) > 0 ? Split : Keep;
          }
          if (split[n] == Split && nodes[n].level >= frame.maxSubdivisionDepth)
          {
            split[n] = AtDepthCap; // its pixels stay unresolved
          }
          const bool splits = split[n] == Split;
          const int values = shapes[nodes[n].patch].screenValues;
          splitIndex[n] = splits ? 1 : 0;
          childValues[n] = splits ? uint64_t(8) * values : 0;
          splitCost[n] = splits ? splitBytes(values, failed[n]) : 0;
          carriedBytes[n] = nodes[n].implicit && (waiting || splits) ? nodeBytes(1, values) : 0;
        });
      thrust::exclusive_scan(exec(), splitIndex, splitIndex + nodeCount + 1, splitIndex);
      thrust::exclusive_scan(exec(), childValues, childValues + nodeCount + 1, childValues);
      thrust::exclusive_scan(exec(), splitCost, splitCost + nodeCount + 1, splitCost);
      thrust::exclusive_scan(exec(), carriedBytes, carriedBytes + nodeCount + 1, carriedBytes);
      // Memory cap: split as many nodes as the budget allows, in order (the nodes before the
      // first whose children would pass it); implicit nodes beyond it become tuples in the next
      // iteration instead, explicit ones leave their pixels unresolved. The copies of implicit
      // nodes carried over are charged first, as if every implicit node were refused.
      const uint64_t held =
        loopBytes(this->ItemNodes.size(), nodeCount, this->Pool.size(), tupleCount);
      const uint64_t budget = settings.memoryBudgetBytes;
      forEach(1,
        [=] IGA_HD(size_t)
        {
          const uint64_t charged = held + carriedBytes[nodeCount];
          const size_t allowed = prefixWithin(nodeCount, charged < budget ? budget - charged : 0,
            [=](size_t n) { return splitCost[n + 1]; });
          totals[0] = splitIndex[allowed]; // nodes split
          totals[1] = childValues[allowed];
          totals[2] = hitIndex[tupleCount];
          totals[3] = allowed;
          totals[4] = charged; // for the compaction's cap
        });
      uint32_t* toSplit = sized(this->ToSplit, nodeCount);
      uint8_t* deferred = sized(this->Deferred, nodeCount);
      forEach(nodeCount,
        [=] IGA_HD(size_t n)
        {
          deferred[n] = nodes[n].implicit && readyForTuples(nodes[n], frame) ? 1 : 0; // waiting
          if (split[n] != Split)
          {
            return;
          }
          if (n < totals[3])
          {
            toSplit[splitIndex[n]] = uint32_t(n);
          }
          else if (nodes[n].implicit)
          {
            nodes[n].overBudget = true; // ready for tuples next time
            deferred[n] = 1;
            split[n] = Keep;
          }
          else
          {
            split[n] = OverBudget;
          }
        });
      uint64_t read[3];
      download(totals, 3, read);
      const size_t allowed = size_t(read[0]), newHits = size_t(read[2]);

      checkIndexable(this->HitCount + newHits, "hits");
      this->Hits.resize(this->HitCount + newHits);
      RawHit* hits = raw(this->Hits) + this->HitCount;
      forEach(tupleCount,
        [=] IGA_HD(size_t t)
        {
          if (outcome[t] == Solved)
          {
            hits[hitIndex[t]] = rawHitOf(
              tuples[t].pixel, nodes[tuples[t].node], &solution[4 * t], solution[4 * t + 3]);
          }
        });
      this->HitCount += newHits;

      checkIndexable(8 * allowed + nodeCount, "nodes"); // gatherNodes indexes them
      double* childPool = sized(this->ChildPool, size_t(read[1]));
      Node* children = sized(this->Children, 8 * allowed);
      uint8_t* keep = sized(this->KeepFlags, 8 * allowed);
      uint8_t* used = sized(this->Used, 8 * allowed); // by the compaction stage
      // The first tuple that moves to each child: those after the compaction's cap do not.
      unsigned int* firstTuple = sized(this->FirstTuple, 8 * allowed);
      // One thread per child (a parent's eight children in one thread left most of the GPU
      // idle).
      forEach(8 * allowed,
        [=] IGA_HD(size_t k)
        {
          const uint32_t n = toSplit[k / 8];
          const Node& parent = nodes[n];
          const int c = int(k % 8);
          Node child = childOf(parent, c);
          child.coeff = childValues[n] + size_t(c) * shapes[parent.patch].screenValues;
          midpointChild<double, 3>(viewOf(parent, pool, shapes), c, childPool + child.coeff);
          const auto view = viewOf(child, childPool, shapes);
          child.info = analyzeNodeBounds(view, frame.isovalues[child.iso], frame.clip);
          keep[k] = worthKeeping(child.info, frame) ? 1 : 0;
          firstTuple[k] = ~0u;
          if (child.implicit && keep[k])
          {
            analyzeNodeSolver(view, child.info);
          }
          children[k] = child;
        });
      report.subdividedPatches += allowed;
      this->trackMemory();
      this->Stages.end(report.msSubdivision);

      // Compaction: failed tuples move to the kept children covering their pixel; solved and
      // dropped tuples and unsplit explicit nodes leave. A child is used when it receives a
      // tuple.
      uint64_t* newCounts = sized(this->Counts, tupleCount + 1);
      uint8_t* unresolved = raw(this->Unresolved);
      unsigned long long* unresolvedTuples = raw(this->UnresolvedTuples);
      forEach(tupleCount,
        [=] IGA_HD(size_t t)
        {
          uint32_t count = 0;
          const uint8_t state = split[tuples[t].node];
          if (outcome[t] == Failed && state == Split)
          {
            const size_t first = 8 * size_t(splitIndex[tuples[t].node]);
            for (size_t c = first; c < first + 8; ++c)
            {
              if (keep[c] &&
                  mayHitPixel(children[c], tuples[t].pixel, best[tuples[t].pixel], frame))
              {
                ++count;
                lowerAtomically(&firstTuple[c], unsigned(t));
              }
            }
          }
          else if (outcome[t] == Failed && state >= AtDepthCap)
          {
            unresolved[tuples[t].pixel] = 1;
            addAtomically(&unresolvedTuples[state == AtDepthCap ? 0 : 1], 1);
          }
          newCounts[t] = count;
        });
      thrust::exclusive_scan(exec(), newCounts, newCounts + tupleCount + 1, newCounts);
      // Memory cap on the tuples handed on: the tuples whose next ones pass it give them up.
      const uint64_t itemCount = this->ItemNodes.size(), childCount = 8 * allowed;
      const uint64_t childValueCount = read[1];
      forEach(1,
        [=] IGA_HD(size_t)
        {
          const uint64_t charged = totals[4], carried = carriedBytes[nodeCount];
          const size_t handedOn = prefixWithin(tupleCount,
            nextTupleRoom(budget, charged + childBytes(childCount, childValueCount), itemCount,
              nodeBytes(childCount, childValueCount) + carried),
            [=](size_t t) { return newCounts[t + 1]; });
          totals[4] = handedOn;
          totals[5] = newCounts[handedOn];
        });
      // The next nodes: implicit children that were kept, explicit children that received
      // pixels, and deferred implicit nodes; stored contiguously.
      forEach(8 * allowed, [=] IGA_HD(size_t c)
        { used[c] = keep[c] && (children[c].implicit || firstTuple[c] < totals[4]) ? 1 : 0; });
      size_t nextCount = 0;
      this->NodeCount = this->gatherNodes(children, childPool, used, 8 * allowed, nodes, pool,
        deferred, nodeCount, false, totals + 5, &nextCount);
      checkIndexable(nextCount);
      const uint32_t* newIndex = raw(this->Index);
      Tuple* next = sized(this->Next, nextCount);
      this->trackMemory(); // the iteration's peak: the old and the new nodes and tuples
      forEach(tupleCount,
        [=] IGA_HD(size_t t)
        {
          size_t write = newCounts[t];
          if (newCounts[t + 1] == write)
          {
            return;
          }
          if (t >= totals[4]) // given up at the cap
          {
            unresolved[tuples[t].pixel] = 1;
            addAtomically(&unresolvedTuples[1], 1);
            return;
          }
          const size_t first = 8 * size_t(splitIndex[tuples[t].node]);
          for (size_t c = first; c < first + 8; ++c)
          {
            if (keep[c] && mayHitPixel(children[c], tuples[t].pixel, best[tuples[t].pixel], frame))
            {
              next[write++] = { tuples[t].pixel, newIndex[c] };
            }
          }
        });
      this->Tuples.swap(this->Next);
      tupleCount = nextCount;
      this->endIteration();
      this->Stages.end(report.msCompaction);
      if (settings.progress)
      {
        settings.progress(report.iterations, tupleCount);
      }
    }
    this->Tuples.resize(0);
  }

  // ---- G-buffer ----------------------------------------------------------------------------

  void fillGBuffer(const View& view, const Settings& settings, GBuffer& out)
  {
    const size_t pixels = this->PixelCount;
    const size_t hitCount = this->HitCount;
    RawHit* raws = raw(this->Hits);
    thrust::stable_sort(exec(), raws, raws + hitCount, HitPixelOrder());
    uint32_t* offsets = sized(this->PixelStart, pixels + 1);
    pixelOffsets(raws, hitCount, 0, pixels, offsets);
    ShadingView viewer{};
    for (int d = 0; d < 3; ++d)
    {
      viewer.eye[d] = view.eye[d];
      viewer.forward[d] = view.forward[d];
    }
    viewer.parallel = view.parallel;
    viewer.hasColor = settings.colorAttribute >= 0;
    const PatchShape* shapes = raw(this->Shapes);
    const double* shadingPool = raw(this->ShadingPool);
    Hit* shaded = sized(this->Shaded, hitCount);
    forEach(hitCount,
      [=] IGA_HD(size_t h)
      {
        const PatchShape& shape = shapes[raws[h].patch];
        const VolumeView<const double> shading(
          shadingPool + shape.screen, shape.degree, kShadeChannels);
        shaded[h] = shadeHit(shading, raws[h], viewer);
      });
    uint32_t* kept = sized(this->KeptOffsets, pixels + 1);
    const double footprint = view.pixelFootprint;
    const bool firstHit = settings.firstHitOnly;
    forEach(pixels,
      [=] IGA_HD(size_t p)
      {
        kept[p] = uint32_t(mergePixelHits(shaded + offsets[p], int(offsets[p + 1] - offsets[p]),
          footprint, viewer.parallel, firstHit));
      });
    const size_t total = scanCounts(this->KeptOffsets, pixels); // at most the hit count
    Hit* compact = sized(this->Compact, total);
    forEach(pixels,
      [=] IGA_HD(size_t p)
      {
        for (uint32_t k = kept[p]; k < kept[p + 1]; ++k)
        {
          compact[k] = shaded[offsets[p] + (k - kept[p])];
        }
      });
    out.width = settings.width;
    out.height = settings.height;
    const size_t offsetBytes = this->downloadOffsets(kept, settings, out.offsets);
    out.hits.resize(total);
    this->downloadStaged(compact, total, out.hits.data(), settings);
    this->Report->downloadedBytes = offsetBytes + total * sizeof(Hit);
  }

  /// Brings the per-pixel offsets of the kept hits (`kept`, pixels + 1 entries) to the host.
  /// A frame covering less than half the image sends only its covered pixels and their offsets
  /// (8 bytes a covered pixel instead of 4 a pixel: a sparse 1080p frame sends kilobytes, not
  /// 8 MB), and the host expands them on its threads. Returns the bytes sent.
  size_t downloadOffsets(
    const uint32_t* kept, const Settings& settings, std::vector<uint32_t>& offsets)
  {
    const size_t pixels = this->PixelCount;
    uint32_t* covered = sized(this->CoveredPixels, pixels);
    const size_t coveredCount = thrust::copy_if(exec(), thrust::counting_iterator<uint32_t>(0),
                                  thrust::counting_iterator<uint32_t>(uint32_t(pixels)), covered,
                                  [=] IGA_HD(uint32_t p) { return kept[p + 1] > kept[p]; }) -
                                covered;
    if (2 * coveredCount >= pixels)
    {
      offsets.resize(pixels + 1);
      this->downloadStaged(kept, pixels + 1, offsets.data(), settings);
      return (pixels + 1) * sizeof(uint32_t);
    }
    uint32_t* starts = sized(this->CoveredStarts, coveredCount + 1);
    forEach(coveredCount + 1,
      [=] IGA_HD(size_t k) { starts[k] = kept[k < coveredCount ? covered[k] : pixels]; });
    std::vector<uint32_t> hostCovered(coveredCount), hostStarts(coveredCount + 1);
    this->downloadStaged(covered, coveredCount, hostCovered.data(), settings);
    this->downloadStaged(starts, coveredCount + 1, hostStarts.data(), settings);
    offsets.resize(pixels + 1);
    offsetsFromRuns(hostCovered, hostStarts, 0, pixels, threadCount(settings), offsets);
    return (2 * coveredCount + 1) * sizeof(uint32_t);
  }

  // ---- transfers ---------------------------------------------------------------------------

  /// Runs step(first, count, staged, threads) over [0, n) a chunk at a time, `staged` the
  /// page-locked staging area holding one chunk of T and `threads` the host threads for its
  /// part of the copy. Transfers larger than Settings::transferChunkBytes go in several chunks,
  /// so that the page-locked memory kept between frames stays bounded.
  template<class T, class Step>
  void inChunks(size_t n, const Settings& settings, Step step)
  {
    const size_t chunk = std::min(n, std::max<size_t>(1, settings.transferChunkBytes / sizeof(T)));
    this->Staging.resize((chunk * sizeof(T) + sizeof(double) - 1) / sizeof(double));
    T* staged = reinterpret_cast<T*>(this->Staging.data());
    const int threads = copyThreads(chunk * sizeof(T), threadCount(settings));
    for (size_t first = 0; first < n; first += chunk)
    {
      step(first, std::min(chunk, n - first), staged, threads);
    }
  }

  /// Copies a host sequence to a device array through the staging area: each chunk is
  /// gathered on several host threads into page-locked memory, which the bus reads at full
  /// speed.
  void uploadStaged(const HostSequence& from, Array<double>& to, const Settings& settings)
  {
    to.resize(from.size());
    this->inChunks<double>(from.size(), settings,
      [&](size_t first, size_t count, double* staged, int threads)
      {
        parallelFor(count, threads,
          [&](size_t begin, size_t end) { from.copy(first + begin, first + end, staged + begin); });
        copyToDevice(raw(to) + first, staged, count * sizeof(double));
      });
  }

  /// Copies n device values to host memory through the staging area.
  template<class T>
  void downloadStaged(const T* from, size_t n, T* to, const Settings& settings)
  {
    this->inChunks<T>(n, settings,
      [&](size_t first, size_t count, T* staged, int threads)
      {
        download(from + first, count, staged);
        parallelFor(count, threads,
          [&](size_t begin, size_t end)
          { std::copy(staged + begin, staged + end, to + first + begin); });
      });
  }

  FrameReport* Report = nullptr;
  const Settings* Settings_ = nullptr;
  FrameConstants Frame{};
  size_t PixelCount = 0;
  size_t NodeCount = 0;
  size_t HitCount = 0;
  size_t Peak = 0, PeakBudgeted = 0;
  uint64_t DataVersion = 0;       ///< of the world patches or nets on the device (0: none)
  uint64_t ExtractionVersion = 0; ///< of the extractions on the device (0: none)
  uint64_t Uploads = 0;           ///< data changes so far (uploads or extractions)
  uint64_t ShadedUpload = 0;      ///< the data change the shading patches were made for
  int Channels = 0;
  bool FromNurbs = false; ///< the world patches were extracted from NURBS volumes
  size_t NetValues = 0, WorldValues = 0;
  std::vector<PatchShape> HostShapes;
  Array<VolumeTable> Volumes;
  Array<ElementRef> Elements;
  Array<double> Matrices, Nets, Scratch;
  Array<int> FirstBasis;
  int SurfaceAttribute = -1, ColorAttribute = -1;
  double AttributeRange = 1;
  size_t ScreenValues = 0;
  Array<PatchShape> Shapes;
  Array<double> World; ///< the input patches' coefficients
  Array<Node> Roots;
  Array<uint8_t> RootStates;
  Array<double> Isovalues;
  Array<Node> InitialNodes;
  Array<double> InitialPool;
  Array<double> ShadingPool;
  Array<Tuple> Items;          ///< SAG: (pixel, initial node) sorted by pixel and depth
  Array<uint32_t> ItemNodes;   ///< their nodes
  Array<uint32_t> ItemOffsets; ///< per pixel
  Array<uint32_t> Cursor, Ends;
  Array<double> BestDepth;
  Array<uint8_t> Unresolved;
  Array<Node> Nodes, NextNodes, Children;
  Array<double> Pool, NextPool, ChildPool;
  Array<Tuple> Tuples, Next;
  Array<uint64_t> Counts; ///< per owner, then scanned into where its items start
  Array<uint32_t> Index, PixelStart, ToSplit, Taken, HitIndex, SplitIndex, KeptOffsets;
  Array<uint32_t> CoveredPixels, CoveredStarts; ///< G-buffer of a sparse frame, sent back
  Array<uint64_t> ChildValues, SplitCost;
  Array<unsigned long long> FailedTuples; ///< per node, counted with atomics
  Array<uint64_t> NodeBytes; ///< per node, then scanned: implicit nodes the budget keeps room for
  Array<uint64_t> Totals;    ///< scan totals read back together
  Array<unsigned long long> RowPairs;         ///< the sweep's pairs per row, as differences
  Array<unsigned long long> UnresolvedTuples; ///< at the depth cap, over the memory budget
  StageTimer Stages;
  Array<uint64_t> Offsets;
  Array<uint32_t> PixelSolves;
  Array<uint8_t> Present, Outcomes, SplitFlags, Deferred, KeepFlags, Used;
  Array<unsigned int> FirstTuple;
  Array<double> Solution;
  Array<RawHit> Hits;
  Array<Hit> Shaded, Compact;
  PinnedArray<double> Staging; ///< uploads and downloads pass through it, a chunk at a time
};

} // namespace device
} // namespace sst
} // namespace iga

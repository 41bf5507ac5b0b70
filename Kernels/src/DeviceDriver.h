// The device driver of the shared-subdivision-tree engine: the input kept on the device
// (patches, or NURBS nets extracted there), the frame's preparation on the device, the shared
// SST loop (sst/Loop.h) over Thrust's primitives (sst/ThrustExec.h), and the transfers of the
// G-buffer. nvcc compiles this for CUDA (CudaEngine.cu); the tests also compile it with g++ for
// Thrust's sequential host system, which checks the driver on machines without a GPU.
#pragma once

#include "FramePlan.h"
#include "ParallelFor.h"
#include "iga/Validation.h"
#include "sst/Loop.h"
#include "sst/ThrustExec.h"

#include <thrust/iterator/counting_iterator.h>
#include <thrust/reduce.h>

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
IGA_DEVICE_SYSTEM_BEGIN

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

/// What the device's check of the world patches found.
struct PatchSummary
{
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  unsigned invalid = 0; ///< patches that firstInvalidPoint or weightsTooSkewed refuses

  AttributeRange range() const { return { lo, hi }; }
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

/// Root r of a frame's roots: the volumes' (patch, isovalue) pairs first, then one per surface.
IGA_HD inline Node rootAt(size_t r, size_t volumes, size_t isoCount)
{
  const size_t volumeRoots = volumes * isoCount;
  return r < volumeRoots ? rootNode(int(r / isoCount), int(r % isoCount))
                         : rootNode(int(volumes + r - volumeRoots), -1);
}

/// The device engine. Its arrays persist from frame to frame (a pool that only grows), so a
/// steady stream of frames allocates nothing. Every member is public because CUDA's extended
/// lambdas may not live in private member functions.
struct Driver
{
  void render(const Scene& scene, const View& view, const Settings& settings, GBuffer& out,
    FrameReport& report)
  {
    this->draw([&] { this->uploadPatches(scene, settings, report); }, view, settings, out, report);
  }

  void renderNurbs(const NurbsVolumes& volumes, const View& view, const Settings& settings,
    GBuffer& out, FrameReport& report)
  {
    this->draw([&] { this->uploadNurbs(volumes, settings, report); }, view, settings, out, report);
  }

  /// A frame: `upload` puts the world patches on the device (or finds them there), then the
  /// frame's preparation, the shared loop and the G-buffer's download.
  template<class Upload>
  void draw(
    Upload upload, const View& view, const Settings& settings, GBuffer& out, FrameReport& report)
  {
    using Clock = std::chrono::steady_clock;
    auto ms = [](Clock::time_point t)
    { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); };
    const Clock::time_point start = Clock::now();
    report.uploadedBytes = 0;
    checkSettings(settings, false); // before the upload, which reads the transfer chunk
    upload();
    report.msInput = ms(start);
    this->prepareFrame(view, settings, report);
    LoopState<ThrustExec>& s = this->Loop;
    setFrame(s, report, settings, view);
    s.shapes = raw(this->Shapes);
    s.initialNodes = raw(this->InitialNodes);
    s.initialCount = this->InitialNodes.size();
    s.initialPool = raw(this->InitialPool);
    s.initialValues = this->InitialPool.size();
    s.shadingPool = raw(this->ShadingPool);
    s.shadingValues = this->ShadingPool.size();
    s.driverBytes = bytesOf(this->World) + bytesOf(this->Roots);
    report.msSetup = ms(start);
    drawFrame(s, settings, [&] { drawPass(s); });
    const Clock::time_point stage = Clock::now();
    this->deliver(settings, out);
    report.msGBuffer += ms(stage);
    report.msTotal = ms(start);
  }

  /// Checks and copies the world patches to the device, unless the settings' data version
  /// says the copy already there is current.
  void uploadPatches(const Scene& scene, const Settings& settings, FrameReport& report)
  {
    const bool current =
      !this->FromNurbs && settings.dataVersion != 0 && settings.dataVersion == this->DataVersion &&
      scene.size() == this->Shapes.size() && settings.surfaceAttribute == this->SurfaceAttribute &&
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
    std::vector<PatchShape> shapes(scene.size());
    size_t world = 0, screen = 0;
    HostSequence coefficients;
    for (size_t p = 0; p < scene.size(); ++p)
    {
      const auto v = scene[p];
      if (!usableShape(v.degree, v.channels, settings))
      {
        throwFirstProblem(scene, settings);
      }
      coefficients.append(v.coeffs, size_t(v.valueCount()));
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
    this->setShapes(shapes, report);
    this->uploadStaged(coefficients, this->World, settings);
    report.uploadedBytes += world * sizeof(double);
    const PatchSummary summary = this->summarizePatches(settings.surfaceAttribute);
    if (summary.invalid > 0)
    {
      throwFirstProblem(scene, settings);
    }
    this->Attribute = summary.range();
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
    this->Loop.exec.forEach(elementCount,
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
    this->Attribute = this->summarizePatches(settings.surfaceAttribute).range();
    this->SurfaceAttribute = settings.surfaceAttribute;
    this->ColorAttribute = settings.colorAttribute;
    this->DataVersion = settings.dataVersion;
    ++this->Uploads;
  }

  /// Over the world patches on the device: how many have an invalid control point or too
  /// widely ranging weights, and the surface attribute's range over the other volumes, as
  /// checkPatches computes it.
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
        if (firstInvalidPoint(patch) >= 0 || weightsTooSkewed(patch))
        {
          summary.invalid = 1;
        }
        else if (!isSurface(patch))
        {
          rationalRange(patch, attribute, kWeightChannel, summary.lo, summary.hi);
        }
        return summary;
      },
      PatchSummary(), CombineSummaries());
  }

  /// Throws checkPatches' message for the first bad patch.
  [[noreturn]] static void throwFirstProblem(const Scene& scene, const Settings& settings)
  {
    checkPatches(scene, settings);
    // Not reached: the device tests the same conditions as the host.
    throw std::invalid_argument("a patch failed the device's check of its control points");
  }

  /// The frame's preparation on the device: screen and shading patches of every patch, and the
  /// subdivision-tree roots, in the CPU driver's order. The rare roots straddling the eye plane
  /// are split on the host (addRoot) and their parts sent up.
  void prepareFrame(const View& view, const Settings& settings, FrameReport& report)
  {
    const size_t volumeCount = size_t(std::count_if(this->HostShapes.begin(),
      this->HostShapes.end(), [](const PatchShape& shape) { return shape.degree[2] != 0; }));
    FramePlan plan = planView(view, settings, this->Attribute, volumeCount > 0, report);
    report.threads = 0;
    this->Isovalues = settings.isovalues;
    report.uploadedBytes += settings.isovalues.size() * sizeof(double);
    FrameConstants& frame = this->Loop.frame;
    frame = plan.frame;
    frame.isovalues = raw(this->Isovalues);
    const ThrustExec exec;

    const size_t patchCount = this->Shapes.size();
    const PatchShape* shapes = raw(this->Shapes);
    const double* world = raw(this->World);
    double* screen = sized(this->InitialPool, this->ScreenValues);
    double* shading = sized(this->ShadingPool, this->ScreenValues);
    const glm::dmat4 windowFromWorld = plan.windowFromWorld;
    const int surface = kFirstAttributeChannel + settings.surfaceAttribute;
    const int colour =
      settings.colorAttribute >= 0 ? kFirstAttributeChannel + settings.colorAttribute : -1;
    // Shading patches do not depend on the view: made again only for new data.
    const bool shade = this->ShadedUpload != this->Uploads;
    this->ShadedUpload = this->Uploads;
    exec.forEach(patchCount,
      [=] IGA_HD(size_t p)
      {
        const PatchShape& shape = shapes[p];
        const VolumeView<const double> patch(world + shape.world, shape.degree, shape.channels);
        const int attribute = isSurface(patch) ? kWeightChannel : surface;
        makeScreenPatch<double>(patch, windowFromWorld, attribute, screen + shape.screen);
        if (shade)
        {
          makeShadingPatch(patch, attribute, colour, shading + shape.screen);
        }
      });

    // Roots: per (volume, isovalue) and per surface, dropped (0), in front of the eye (1) or
    // straddling it (2).
    const size_t isoCount = settings.isovalues.size();
    const size_t rootCount = volumeCount * isoCount + (patchCount - volumeCount);
    Node* roots = sized(this->Roots, rootCount);
    uint8_t* state = sized(this->RootStates, rootCount);
    exec.forEach(rootCount,
      [=] IGA_HD(size_t r)
      {
        Node root = rootAt(r, volumeCount, isoCount);
        const PatchShape& shape = shapes[root.patch];
        const VolumeView<const double> view(screen + shape.screen, shape.degree, kScreenChannels);
        analyzeNodeBounds(view, isovalueOf(root, frame), frame.clip, root.info);
        root.coeff = shape.screen;
        roots[r] = root;
        state[r] = !worthKeeping(root.info, frame)                 ? 0
                   : root.info.status == ProjectionStatus::InFront ? 1
                                                                   : 2;
      });
    report.constantAttributeRoots += exec.sum(
      rootCount, [=] IGA_HD(size_t r) { return size_t(roots[r].info.constantAttribute ? 1 : 0); });
    uint32_t* straddling = sized(this->Straddling, rootCount);
    const size_t straddlingCount = exec.select(
      rootCount, [=] IGA_HD(size_t r) { return state[r] == 2; }, [] IGA_HD(size_t r) { return r; },
      straddling);
    // Host side of the straddling roots: their parts, and how many each gives.
    std::vector<uint32_t> straddlers(straddlingCount), partCounts(straddlingCount);
    exec.read(straddling, straddlingCount, straddlers.data());
    FramePlan parts = plan;
    for (size_t k = 0; k < straddlingCount; ++k)
    {
      const Node root = rootAt(straddlers[k], volumeCount, isoCount);
      const PatchShape& shape = this->HostShapes[root.patch];
      std::vector<double> worldValues(
        size_t(shape.screenValues / kScreenChannels) * shape.channels);
      exec.read(world + shape.world, worldValues.size(), worldValues.data());
      const VolumeView<const double> patch(worldValues.data(), shape.degree, shape.channels);
      std::vector<double> coefficients(size_t(shape.screenValues));
      makeScreenPatch<double>(patch, plan.windowFromWorld,
        isSurface(patch) ? kWeightChannel : surface, coefficients.data());
      const size_t before = parts.initialNodes.size();
      addRoot(parts, shape.degree, root, coefficients.data(), settings, report);
      partCounts[k] = uint32_t(parts.initialNodes.size() - before);
    }
    for (Node& node : parts.initialNodes)
    {
      node.coeff += this->ScreenValues; // their coefficients follow the screen patches
    }
    uint64_t* counts = sized(this->RootCounts, rootCount + 1);
    exec.forEach(rootCount, [=] IGA_HD(size_t r) { counts[r] = state[r] == 1 ? 1 : 0; });
    partCounts.push_back(0); // the scan below reads one past the last
    this->PartCounts = partCounts;
    const uint32_t* partCount = raw(this->PartCounts);
    exec.forEach(straddlingCount, [=] IGA_HD(size_t k) { counts[straddling[k]] = partCount[k]; });
    const size_t total = scanCounts(exec, this->RootCounts, rootCount);
    Node* initial = sized(this->InitialNodes, total);
    exec.forEach(rootCount,
      [=] IGA_HD(size_t r)
      {
        if (state[r] == 1)
        {
          initial[counts[r]] = roots[r];
        }
      });
    this->PartNodes = parts.initialNodes;
    const Node* partNodes = raw(this->PartNodes);
    uint64_t* partStart = sized(this->PartStarts, straddlingCount + 1);
    exec.forEach(straddlingCount + 1, [=] IGA_HD(size_t k) { partStart[k] = partCount[k]; });
    exec.scan(partStart, straddlingCount);
    exec.forEach(straddlingCount,
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

  // ---- G-buffer ----------------------------------------------------------------------------

  /// The G-buffer stage's kept hits (on the device, run by run) into the G-buffer.
  void deliver(const Settings& settings, GBuffer& out)
  {
    LoopState<ThrustExec>& s = this->Loop;
    out.width = settings.width;
    out.height = settings.height;
    const size_t offsetBytes = this->downloadOffsets(settings, out.offsets);
    Hit* compact = sized(this->Compact, s.KeptCount);
    compactHits(s, compact);
    out.hits.resize(s.KeptCount);
    this->downloadStaged(compact, s.KeptCount, out.hits.data(), settings);
    s.report->downloadedBytes = offsetBytes + s.KeptCount * sizeof(Hit);
  }

  /// Brings the per-pixel offsets of the kept hits to the host.
  /// A frame covering less than half the image sends only its covered pixels and their offsets
  /// (8 bytes a covered pixel instead of 4 a pixel: a sparse 1080p frame sends kilobytes, not
  /// 8 MB), and the host expands them on its threads. Returns the bytes sent.
  size_t downloadOffsets(const Settings& settings, std::vector<uint32_t>& offsets)
  {
    LoopState<ThrustExec>& s = this->Loop;
    const size_t pixels = s.pixelCount, covered = s.RunCount;
    offsets.resize(pixels + 1);
    if (2 * covered >= pixels)
    {
      uint32_t* dense = sized(this->PixelStarts, pixels + 1);
      s.exec.offsetsFromRuns(raw(s.RunPixels), raw(s.KeptStarts), covered, 0, pixels, dense);
      this->downloadStaged(dense, pixels + 1, offsets.data(), settings);
      return (pixels + 1) * sizeof(uint32_t);
    }
    std::vector<uint32_t> runPixels(covered), keptStarts(covered + 1);
    this->downloadStaged(raw(s.RunPixels), covered, runPixels.data(), settings);
    this->downloadStaged(raw(s.KeptStarts), covered + 1, keptStarts.data(), settings);
    offsetsFromRuns(runPixels.data(), keptStarts.data(), covered, 0, pixels, threadCount(settings),
      offsets.data());
    return (2 * covered + 1) * sizeof(uint32_t);
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

  LoopState<ThrustExec> Loop;
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
  AttributeRange Attribute;
  size_t ScreenValues = 0;
  Array<PatchShape> Shapes;
  Array<double> World; ///< the input patches' coefficients
  Array<Node> Roots;
  Array<uint8_t> RootStates;
  Array<double> Isovalues;
  Array<Node> InitialNodes;
  Array<double> InitialPool;
  Array<double> ShadingPool;
  // Scratch of the frame's preparation.
  Array<uint32_t> Straddling, PartCounts;
  Array<uint64_t> RootCounts, PartStarts;
  Array<Node> PartNodes;
  Array<uint32_t> PixelStarts; ///< the offsets of a dense G-buffer, sent back
  Array<Hit> Compact;          ///< the kept hits, sent back
  PinnedArray<double> Staging; ///< uploads and downloads pass through it, a chunk at a time
};

IGA_DEVICE_SYSTEM_END
} // namespace device
} // namespace sst
} // namespace iga

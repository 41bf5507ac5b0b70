#include "vtkIGAMFEMReader.h"

#include "IGAFileHead.h"
#include "IGAReadError.h"
#include "IGATextLines.h"

#include "vtkIGANurbsData.h"
#include "vtkObjectFactory.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

vtkStandardNewMacro(vtkIGAMFEMReader);

namespace
{
// MFEM's reference hexahedron and quadrilateral (fem/geom.cpp): the vertices of each edge and,
// for the hexahedron, of each face, in MFEM's order.
constexpr int kHexEdges[12][2] = { { 0, 1 }, { 1, 2 }, { 3, 2 }, { 0, 3 }, { 4, 5 }, { 5, 6 },
  { 7, 6 }, { 4, 7 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
constexpr int kHexFaces[6][4] = { { 3, 2, 1, 0 }, { 0, 1, 5, 4 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 },
  { 3, 0, 4, 7 }, { 4, 5, 6, 7 } };
constexpr int kQuadEdges[4][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 } };
constexpr long kMaxCount = 100000000;

std::string trimmed(const std::string& text)
{
  const size_t first = text.find_first_not_of(" \t");
  const size_t last = text.find_last_not_of(" \t");
  return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

/// The next line, which must be the section keyword `word`.
void expectWord(IGATextLines& lines, const char* word)
{
  const IGATextLine& line = lines.take(word);
  if (trimmed(line.text) != word)
    throw IGAReadError(line.number, "'" + trimmed(line.text) + "' where '" + word + "' should be");
}

int readCount(IGATextLines& lines, const char* what, long most = kMaxCount)
{
  return lines.integers(what, 1, 0, most)[0];
}

/// `count` numbers, over as many lines as they take (MFEM reads them as a stream).
std::vector<double> readValues(IGATextLines& lines, const char* what, size_t count)
{
  std::vector<double> values;
  values.reserve(count);
  while (values.size() < count)
  {
    const long number = lines.peek(what).number;
    const auto line = lines.numbers(what);
    if (values.size() + line.size() > count)
      throw IGAReadError(number,
        std::string(what) + ": more values than the " + std::to_string(count) + " expected");
    values.insert(values.end(), line.begin(), line.end());
  }
  return values;
}

/// "Key: value" (FiniteElementSpace's lines); the value.
std::string readKey(IGATextLines& lines, const std::string& key)
{
  const IGATextLine& line = lines.take(key.c_str());
  const std::string text = trimmed(line.text);
  if (text.compare(0, key.size() + 1, key + ":") != 0)
    throw IGAReadError(line.number, "'" + text + "' where '" + key + ": ...' should be");
  return trimmed(text.substr(key.size() + 1));
}

int keyInteger(IGATextLines& lines, const std::string& key, int lo, int hi)
{
  const long number = lines.peek(key.c_str()).number;
  const std::string value = readKey(lines, key);
  char* end = nullptr;
  const long parsed = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || parsed < lo || parsed > hi)
    throw IGAReadError(number, key + ": '" + value + "' is not an integer in " +
                                 std::to_string(lo) + ".." + std::to_string(hi));
  return int(parsed);
}

/// A finite element space's header (mesh nodes or a GridFunction): its collection, VDim and
/// Ordering (0: by nodes, every x then every y...; 1: by VDim, x y z per control point).
struct SpaceHeader
{
  std::string collection;
  int vdim = 0, ordering = 0;
};

SpaceHeader readSpaceHeader(IGATextLines& lines)
{
  expectWord(lines, "FiniteElementSpace");
  SpaceHeader header;
  const long number = lines.peek("FiniteElementCollection").number;
  header.collection = readKey(lines, "FiniteElementCollection");
  if (header.collection.compare(0, 5, "NURBS") != 0)
    throw IGAReadError(
      number, "FiniteElementCollection " + header.collection + " is not a NURBS collection");
  header.vdim = keyInteger(lines, "VDim", 1, 3);
  header.ordering = keyInteger(lines, "Ordering", 0, 1);
  return header;
}

/// Values of a space of `points` control points, `vdim` each, control point by control point.
std::vector<double> readSpaceValues(
  IGATextLines& lines, const SpaceHeader& header, size_t points, const char* what)
{
  auto values = readValues(lines, what, points * size_t(header.vdim));
  if (header.ordering == 1)
    return values;
  std::vector<double> byPoint(values.size());
  for (size_t p = 0; p < points; ++p)
    for (int c = 0; c < header.vdim; ++c)
      byPoint[p * header.vdim + c] = values[size_t(c) * points + p];
  return byPoint;
}

struct KnotVector
{
  int degree = 0, count = 0;
  std::vector<double> knots;

  /// The same spline space run backwards (t -> first + last - t).
  KnotVector reversed() const
  {
    KnotVector out = *this;
    const double sum = this->knots.front() + this->knots.back();
    for (size_t k = 0; k < this->knots.size(); ++k)
      out.knots[k] = sum - this->knots[this->knots.size() - 1 - k];
    return out;
  }
};

/// "degree count knots..." (MFEM calls the degree the order).
KnotVector readKnotVector(IGATextLines& lines, const std::string& what)
{
  const long number = lines.peek(what.c_str()).number;
  const auto values = lines.numbers(what.c_str());
  KnotVector kv;
  if (values.size() < 2 || values[0] != std::floor(values[0]) ||
      values[1] != std::floor(values[1]) || values[0] < 1 || values[0] > iga::kMaxDegree ||
      values[1] < 1 || values[1] > kMaxCount)
    throw IGAReadError(number,
      what + ": '" + lines.peek(what.c_str()).text + "' does not begin with a degree in 1.." +
        std::to_string(iga::kMaxDegree) + " and a number of control points");
  kv.degree = int(values[0]);
  kv.count = int(values[1]);
  kv.knots.assign(values.begin() + 2, values.end());
  try
  {
    iga::validateKnotVector(kv.knots, kv.degree, kv.count);
  }
  catch (const std::invalid_argument& e)
  {
    throw IGAReadError(number, what + ": " + e.what());
  }
  return kv;
}

std::vector<KnotVector> readKnotVectors(IGATextLines& lines, long expected = -1)
{
  expectWord(lines, "knotvectors");
  const long number = lines.peek("the number of knot vectors").number;
  const int count = readCount(lines, "the number of knot vectors");
  if (expected >= 0 && count != expected)
    throw IGAReadError(number, "a patch of dimension " + std::to_string(expected) + " has " +
                                 std::to_string(count) + " knot vectors");
  std::vector<KnotVector> kvs;
  for (int k = 0; k < count; ++k)
    kvs.push_back(readKnotVector(lines, "knot vector " + std::to_string(k)));
  return kvs;
}

/// The coarse mesh whose elements are the patches.
struct Topology
{
  int dimension = 0;
  std::vector<std::vector<int>> patches; ///< each patch's corner vertices, MFEM's order
  int vertices = 0;
  /// Per edge (its vertices, smaller first): its knot vector.
  std::map<std::pair<int, int>, int> edgeKnots;
  /// The edges in the file's order, which is MFEM's numbering of them.
  std::vector<std::pair<int, int>> edges;
};

std::pair<int, int> edgeKey(int a, int b)
{
  return { std::min(a, b), std::max(a, b) };
}

Topology readTopology(IGATextLines& lines)
{
  Topology topology;
  expectWord(lines, "dimension");
  const long dimensionLine = lines.peek("the dimension").number;
  topology.dimension = lines.integers("the dimension", 1, 1, 3)[0];
  if (topology.dimension == 1)
    throw IGAReadError(dimensionLine, "dimension 1: NURBS curves are not drawn (volumes and "
                                      "surfaces are)");
  const int corners = topology.dimension == 3 ? 8 : 4;
  const int geometry = topology.dimension == 3 ? 5 : 3; // MFEM's CUBE, SQUARE
  expectWord(lines, "elements");
  const int elements = readCount(lines, "the number of elements");
  for (int e = 0; e < elements; ++e)
  {
    const long number = lines.peek("an element").number;
    const auto values =
      lines.integers("element (attribute, geometry, vertices)", 2 + corners, 0, kMaxCount);
    if (values[1] != geometry)
      throw IGAReadError(number, "element " + std::to_string(e) + " has geometry " +
                                   std::to_string(values[1]) + ", a mesh of dimension " +
                                   std::to_string(topology.dimension) + " needs " +
                                   std::to_string(geometry));
    topology.patches.emplace_back(values.begin() + 2, values.end());
  }
  expectWord(lines, "boundary");
  const int boundary = readCount(lines, "the number of boundary elements");
  for (int b = 0; b < boundary; ++b)
    lines.integers("boundary element", -1, 0, kMaxCount);
  expectWord(lines, "edges");
  const int edges = readCount(lines, "the number of edges");
  std::vector<std::array<int, 3>> listed;
  for (int e = 0; e < edges; ++e)
  {
    const auto values = lines.integers("edge (knot vector, vertices)", 3, 0, kMaxCount);
    listed.push_back({ values[0], values[1], values[2] });
  }
  expectWord(lines, "vertices");
  const long verticesLine = lines.peek("the number of vertices").number;
  topology.vertices = readCount(lines, "the number of vertices");
  for (const auto& edge : listed)
  {
    if (edge[1] >= topology.vertices || edge[2] >= topology.vertices)
      throw IGAReadError(verticesLine, "an edge names vertex " +
                                         std::to_string(std::max(edge[1], edge[2])) + " of " +
                                         std::to_string(topology.vertices));
    if (!topology.edgeKnots.emplace(edgeKey(edge[1], edge[2]), edge[0]).second)
      throw IGAReadError(verticesLine,
        "edge " + std::to_string(edge[1]) + "-" + std::to_string(edge[2]) + " is listed twice");
    topology.edges.push_back(edgeKey(edge[1], edge[2]));
  }
  for (size_t p = 0; p < topology.patches.size(); ++p)
    for (int v : topology.patches[p])
      if (v >= topology.vertices)
        throw IGAReadError(verticesLine, "element " + std::to_string(p) + " names vertex " +
                                           std::to_string(v) + " of " +
                                           std::to_string(topology.vertices));
  return topology;
}

/// MFEM's numbering of the control points of a patch-topology mesh (NURBSExtension): the
/// vertices, then the interiors of the edges (in the file's order), of the faces (3D, in the
/// order the patches meet them) and of the patches; a shared edge's points run from its smaller
/// vertex, a shared face's as the first patch meeting it runs them.
class ControlPointNumbering
{
public:
  ControlPointNumbering(const Topology& topology, const std::vector<KnotVector>& knotVectors)
    : Topo(topology)
    , Knots(knotVectors)
  {
    const bool volume = topology.dimension == 3;
    const int edgeCount = volume ? 12 : 4;
    this->Total = size_t(topology.vertices);
    for (const auto& edge : topology.edges)
    {
      const int kv = topology.edgeKnots.at(edge);
      if (size_t(kv) >= knotVectors.size())
        throw IGAReadError(0, "edge " + std::to_string(edge.first) + "-" +
                                std::to_string(edge.second) + " names knot vector " +
                                std::to_string(kv) + " of " + std::to_string(knotVectors.size()));
      this->Edges[edge] = int(this->EdgeCounts.size());
      this->EdgeCounts.push_back(knotVectors[size_t(kv)].count - 2);
    }
    for (size_t p = 0; p < topology.patches.size(); ++p)
    {
      const auto& v = topology.patches[p];
      PatchLinks links;
      for (int e = 0; e < edgeCount; ++e)
      {
        const int a = v[volume ? kHexEdges[e][0] : kQuadEdges[e][0]];
        const int b = v[volume ? kHexEdges[e][1] : kQuadEdges[e][1]];
        links.edges[e] = this->EdgeIndex(int(p), a, b);
        links.edgeForward[e] = a < b;
      }
      for (int f = 0; volume && f < 6; ++f)
      {
        std::array<int, 4> corners;
        for (int c = 0; c < 4; ++c)
          corners[c] = v[kHexFaces[f][c]];
        links.faces[f] = this->FaceIndex(corners, links.faceOrientation[f]);
      }
      this->Links.push_back(links);
      this->CheckParallelEdges(int(p));
    }
    // Offsets: edges, faces, then the patches' interiors, in numbering order.
    for (const auto& edge : this->EdgeCounts)
    {
      this->EdgeOffsets.push_back(this->Total);
      this->Total += size_t(edge);
    }
    for (const auto& face : this->FaceSizes)
    {
      this->FaceOffsets.push_back(this->Total);
      this->Total += size_t(face[0]) * size_t(face[1]);
    }
    for (size_t p = 0; p < topology.patches.size(); ++p)
    {
      this->PatchOffsets.push_back(this->Total);
      const auto n = this->InteriorSize(int(p));
      this->Total += size_t(n[0]) * size_t(n[1]) * size_t(volume ? n[2] : 1);
    }
  }

  /// Control points in all (the weights' and nodes' count).
  size_t total() const { return this->Total; }

  /// Patch p's knot vector along each direction (from its corner 0 towards 1, 3 and 4) and its
  /// control points' numbers, first direction fastest.
  void patch(int p, KnotVector* kv, std::vector<size_t>& numbers) const
  {
    const bool volume = this->Topo.dimension == 3;
    const auto& v = this->Topo.patches[size_t(p)];
    const int towards[3] = { 1, 3, 4 };
    for (int d = 0; d < this->Topo.dimension; ++d)
    {
      // A knot vector runs from its edge's smaller vertex (MFEM 4.9 on; earlier versions read
      // the same files alike where the knot vectors are symmetric, as MFEM's own are).
      const KnotVector& listed =
        this->Knots[size_t(this->Topo.edgeKnots.at(edgeKey(v[0], v[towards[d]])))];
      kv[d] = v[0] < v[towards[d]] ? listed : listed.reversed();
    }
    const auto n = this->InteriorSize(p);
    numbers.clear();
    const int depth = volume ? n[2] + 2 : 1;
    for (int k = 0; k < depth; ++k)
      for (int j = 0; j < n[1] + 2; ++j)
        for (int i = 0; i < n[0] + 2; ++i)
          numbers.push_back(volume ? this->At(p, i, j, k) : this->At(p, i, j));
  }

private:
  struct PatchLinks
  {
    int edges[12], faces[6];
    bool edgeForward[12];
    int faceOrientation[6];
  };

  int EdgeIndex(int patch, int a, int b) const
  {
    const auto found = this->Edges.find(edgeKey(a, b));
    if (found == this->Edges.end())
      throw IGAReadError(0, "element " + std::to_string(patch) + ": its edge " + std::to_string(a) +
                              "-" + std::to_string(b) + " is not in the edges section");
    return found->second;
  }

  /// The face's number; its orientation for this patch (MFEM's GetQuadOrientation against the
  /// corners the first patch meeting it gave).
  int FaceIndex(const std::array<int, 4>& corners, int& orientation)
  {
    std::array<int, 4> key = corners;
    std::sort(key.begin(), key.end());
    const auto found = this->Faces.find(key);
    if (found == this->Faces.end())
    {
      const int index = int(this->FaceBases.size());
      this->Faces[key] = index;
      this->FaceBases.push_back(corners);
      this->FaceSizes.push_back(
        { this->EdgeCountOf(corners[0], corners[1]), this->EdgeCountOf(corners[1], corners[2]) });
      orientation = 0;
      return index;
    }
    const auto& base = this->FaceBases[size_t(found->second)];
    const int at = int(std::find(corners.begin(), corners.end(), base[0]) - corners.begin());
    orientation = corners[size_t((at + 1) % 4)] == base[1] ? 2 * at : 2 * at + 1;
    return found->second;
  }

  int EdgeCountOf(int a, int b) const
  {
    return this->EdgeCounts[size_t(this->Edges.at(edgeKey(a, b)))];
  }

  /// Interior control points of patch p along each direction.
  std::array<int, 3> InteriorSize(int p) const
  {
    const PatchLinks& links = this->Links[size_t(p)];
    const bool volume = this->Topo.dimension == 3;
    return { this->EdgeCounts[size_t(links.edges[0])],
      this->EdgeCounts[size_t(links.edges[volume ? 3 : 1])],
      volume ? this->EdgeCounts[size_t(links.edges[8])] : 0 };
  }

  /// A patch's parallel edges must have as many control points (MFEM's CheckPatches).
  void CheckParallelEdges(int p) const
  {
    static const int kHexParallel[3][4] = { { 0, 2, 4, 6 }, { 1, 3, 5, 7 }, { 8, 9, 10, 11 } };
    static const int kQuadParallel[2][4] = { { 0, 2, 0, 2 }, { 1, 3, 1, 3 } };
    const bool volume = this->Topo.dimension == 3;
    const PatchLinks& links = this->Links[size_t(p)];
    for (int d = 0; d < this->Topo.dimension; ++d)
    {
      const int* edges = volume ? kHexParallel[d] : kQuadParallel[d];
      const int count = this->EdgeCounts[size_t(links.edges[edges[0]])];
      for (int e = 1; e < 4; ++e)
      {
        const int other = this->EdgeCounts[size_t(links.edges[edges[e]])];
        if (other != count)
          throw IGAReadError(0, "element " + std::to_string(p) + ": its edges along direction " +
                                  std::to_string(d) + " have " + std::to_string(count + 2) +
                                  " and " + std::to_string(other + 2) + " control points");
      }
    }
  }

  static int Along(int n, int count, bool forward) { return forward ? n : count - 1 - n; }

  /// MFEM's Or2D: point (n1, n2) of a face as this patch runs it, in the face's own numbering.
  static int OnFace(int n1, int n2, int count1, int count2, int orientation)
  {
    switch (orientation)
    {
      case 0:
        return n1 + n2 * count1;
      case 1:
        return n2 + n1 * count2;
      case 2:
        return n2 + (count1 - 1 - n1) * count2;
      case 3:
        return (count1 - 1 - n1) + n2 * count1;
      case 4:
        return (count1 - 1 - n1) + (count2 - 1 - n2) * count1;
      case 5:
        return (count2 - 1 - n2) + (count1 - 1 - n1) * count2;
      case 6:
        return (count2 - 1 - n2) + n1 * count2;
      default:
        return n1 + (count2 - 1 - n2) * count1;
    }
  }

  size_t Edge(const PatchLinks& links, int e, int n, int count) const
  {
    return this->EdgeOffsets[size_t(links.edges[e])] +
           size_t(Along(n, count, links.edgeForward[e]));
  }
  size_t Face(const PatchLinks& links, int f, int n1, int n2, int count1, int count2) const
  {
    return this->FaceOffsets[size_t(links.faces[f])] +
           size_t(OnFace(n1, n2, count1, count2, links.faceOrientation[f]));
  }

  /// Quadrilateral patch p's control point (i, j) (MFEM's NURBSPatchMap, 2D).
  size_t At(int p, int i, int j) const
  {
    const auto& v = this->Topo.patches[size_t(p)];
    const PatchLinks& l = this->Links[size_t(p)];
    const auto n = this->InteriorSize(p);
    const int I = n[0], J = n[1], i1 = i - 1, j1 = j - 1;
    if (j1 < 0)
      return i1 < 0 ? size_t(v[0]) : i1 >= I ? size_t(v[1]) : this->Edge(l, 0, i1, I);
    if (j1 >= J)
      return i1 < 0 ? size_t(v[3]) : i1 >= I ? size_t(v[2]) : this->Edge(l, 2, I - 1 - i1, I);
    if (i1 < 0)
      return this->Edge(l, 3, J - 1 - j1, J);
    if (i1 >= I)
      return this->Edge(l, 1, j1, J);
    return this->PatchOffsets[size_t(p)] + size_t(i1 + j1 * I);
  }

  /// Hexahedral patch p's control point (i, j, k) (MFEM's NURBSPatchMap, 3D).
  size_t At(int p, int i, int j, int k) const
  {
    const auto& v = this->Topo.patches[size_t(p)];
    const PatchLinks& l = this->Links[size_t(p)];
    const auto n = this->InteriorSize(p);
    const int I = n[0], J = n[1], K = n[2], i1 = i - 1, j1 = j - 1, k1 = k - 1;
    if (k1 < 0 || k1 >= K)
    {
      // The bottom (face 0, edges 0-3) or the top (face 5, edges 4-7).
      const bool top = k1 >= K;
      const int e = top ? 4 : 0, c = top ? 4 : 0;
      if (j1 < 0)
        return i1 < 0 ? size_t(v[c]) : i1 >= I ? size_t(v[c + 1]) : this->Edge(l, e, i1, I);
      if (j1 >= J)
        return i1 < 0 ? size_t(v[c + 3]) : i1 >= I ? size_t(v[c + 2]) : this->Edge(l, e + 2, i1, I);
      if (i1 < 0)
        return this->Edge(l, e + 3, j1, J);
      if (i1 >= I)
        return this->Edge(l, e + 1, j1, J);
      return top ? this->Face(l, 5, i1, j1, I, J) : this->Face(l, 0, i1, J - 1 - j1, I, J);
    }
    if (j1 < 0)
      return i1 < 0    ? this->Edge(l, 8, k1, K)
             : i1 >= I ? this->Edge(l, 9, k1, K)
                       : this->Face(l, 1, i1, k1, I, K);
    if (j1 >= J)
      return i1 < 0    ? this->Edge(l, 11, k1, K)
             : i1 >= I ? this->Edge(l, 10, k1, K)
                       : this->Face(l, 3, I - 1 - i1, k1, I, K);
    if (i1 < 0)
      return this->Face(l, 4, J - 1 - j1, k1, J, K);
    if (i1 >= I)
      return this->Face(l, 2, j1, k1, J, K);
    return this->PatchOffsets[size_t(p)] + size_t(i1 + I * (j1 + J * k1));
  }

  const Topology& Topo;
  const std::vector<KnotVector>& Knots;
  std::map<std::pair<int, int>, int> Edges;
  std::vector<int> EdgeCounts;
  std::map<std::array<int, 4>, int> Faces;
  std::vector<std::array<int, 4>> FaceBases;
  std::vector<std::array<int, 2>> FaceSizes;
  std::vector<PatchLinks> Links;
  std::vector<size_t> EdgeOffsets, FaceOffsets, PatchOffsets;
  size_t Total = 0;
};

/// A patch of the set from its knot vectors, Euclidean control points (`spaceDim` values each)
/// and weights, first direction fastest.
template<int Dim>
iga::BSplinePatch<double, Dim> makePatch(const KnotVector* kv, const std::vector<double>& points,
  int spaceDim, const std::vector<double>& weights)
{
  iga::BSplinePatch<double, Dim> patch;
  for (int d = 0; d < Dim; ++d)
  {
    patch.degree[d] = kv[d].degree;
    patch.knots[d] = kv[d].knots;
    patch.netSize[d] = kv[d].count;
  }
  std::vector<double> euclidean(3 * weights.size(), 0.0);
  for (size_t p = 0; p < weights.size(); ++p)
    for (int c = 0; c < spaceDim; ++c)
      euclidean[3 * p + c] = points[p * spaceDim + c];
  iga::setGeometryNet(patch, euclidean, weights);
  return patch;
}

void checkWeights(const std::vector<double>& weights, long line)
{
  for (size_t w = 0; w < weights.size(); ++w)
    if (!(weights[w] > 0))
      throw IGAReadError(line, "weight " + std::to_string(w) + " is " + std::to_string(weights[w]) +
                                 ", weights must be positive");
}

/// The form that lists the patch topology and the control points as a finite element space's
/// nodes. Returns the numbering's per-patch control points (for GridFunctions) and the nodes'
/// space.
void readTopologyForm(IGATextLines& lines, const Topology& topology, iga::NurbsSet<double>& set,
  std::vector<std::vector<size_t>>& patchPoints, SpaceHeader& space, size_t& total)
{
  const auto knotVectors = readKnotVectors(lines);
  const ControlPointNumbering numbering(topology, knotVectors);
  total = numbering.total();
  // "weights", or MFEM's keywords for all weights 1.
  const IGATextLine& keyword = lines.take("weights");
  const std::string weightsKind = trimmed(keyword.text);
  if (weightsKind != "weights" && weightsKind != "unitweights" && weightsKind != "autoweights")
    throw IGAReadError(keyword.number, "'" + weightsKind + "' where 'weights' should be");
  const long weightsLine = weightsKind == "weights" ? lines.peek("the weights").number : 0;
  const auto weights = weightsKind == "weights" ? readValues(lines, "weights", total)
                                                : std::vector<double>(total, 1.0);
  checkWeights(weights, weightsLine);
  const long spaceLine = lines.peek("FiniteElementSpace").number;
  space = readSpaceHeader(lines);
  if (space.vdim < topology.dimension)
    throw IGAReadError(spaceLine, "the nodes have " + std::to_string(space.vdim) +
                                    " components, fewer than the mesh's dimension " +
                                    std::to_string(topology.dimension));
  const auto nodes = readSpaceValues(lines, space, total, "nodes");
  for (size_t p = 0; p < topology.patches.size(); ++p)
  {
    KnotVector kv[3];
    std::vector<size_t> numbers;
    numbering.patch(int(p), kv, numbers);
    std::vector<double> points, patchWeights;
    for (size_t n : numbers)
    {
      patchWeights.push_back(weights[n]);
      points.insert(points.end(), nodes.begin() + long(n * space.vdim),
        nodes.begin() + long((n + 1) * space.vdim));
    }
    const size_t expected =
      size_t(kv[0].count) * size_t(kv[1].count) * size_t(topology.dimension == 3 ? kv[2].count : 1);
    if (numbers.size() != expected)
      throw IGAReadError(0, "patch " + std::to_string(p) + ": its edges give " +
                              std::to_string(numbers.size()) +
                              " control points, its knot vectors " + std::to_string(expected));
    if (topology.dimension == 3)
      set.volumes.push_back(makePatch<3>(kv, points, space.vdim, patchWeights));
    else
      set.surfaces.push_back(makePatch<2>(kv, points, space.vdim, patchWeights));
    patchPoints.push_back(std::move(numbers));
  }
}

/// The form that lists every patch's knot vectors and control points.
void readPatchesForm(IGATextLines& lines, const Topology& topology, iga::NurbsSet<double>& set)
{
  expectWord(lines, "patches");
  for (size_t p = 0; p < topology.patches.size(); ++p)
  {
    const auto kv = readKnotVectors(lines, topology.dimension);
    expectWord(lines, "dimension");
    const int spaceDim = lines.integers("the patch's space dimension", 1, 1, 3)[0];
    const IGATextLine& form = lines.take("controlpoints");
    const std::string kind = trimmed(form.text);
    if (kind != "controlpoints" && kind != "controlpoints_homogeneous" &&
        kind != "controlpoints_cartesian")
      throw IGAReadError(form.number, "'" + kind + "' where 'controlpoints' should be");
    size_t count = 1;
    for (const auto& direction : kv)
      count *= size_t(direction.count);
    std::vector<double> points, weights;
    const long first = lines.peek("a control point").number;
    const auto values = readValues(lines, "control points", count * size_t(spaceDim + 1));
    for (size_t c = 0; c < count; ++c)
    {
      const double w = values[c * (spaceDim + 1) + size_t(spaceDim)];
      weights.push_back(w);
      for (int d = 0; d < spaceDim; ++d)
      {
        const double value = values[c * (spaceDim + 1) + size_t(d)];
        points.push_back(kind == "controlpoints_cartesian" || !(w > 0) ? value : value / w);
      }
    }
    checkWeights(weights, first);
    if (topology.dimension == 3)
      set.volumes.push_back(makePatch<3>(kv.data(), points, spaceDim, weights));
    else
      set.surfaces.push_back(makePatch<2>(kv.data(), points, spaceDim, weights));
  }
}

/// The attribute name of GridFunction file `name`: its name without folder and extension.
std::string fieldName(const std::string& name)
{
  return vtksys::SystemTools::GetFilenameWithoutLastExtension(name);
}

/// A GridFunction file's values, control point by control point, on the mesh's space.
std::vector<double> readGridFunction(
  const std::string& file, const SpaceHeader& mesh, size_t total, int& components)
{
  std::ifstream in;
  const std::string problem = igaOpenRegularFile(file, in);
  if (!problem.empty())
    throw IGAReadError(0, problem);
  std::stringstream text;
  text << in.rdbuf();
  try
  {
    IGATextLines lines(text.str(), '#');
    const long number = lines.peek("FiniteElementSpace").number;
    const SpaceHeader header = readSpaceHeader(lines);
    if (header.collection != mesh.collection)
      throw IGAReadError(number, "its space is " + header.collection + ", the mesh's " +
                                   mesh.collection +
                                   ": a field is read on the mesh's control "
                                   "points only");
    components = header.vdim;
    auto values = readSpaceValues(lines, header, total, "values");
    if (!lines.atEnd())
      throw IGAReadError(lines.peek("").number,
        "more values than the mesh's " + std::to_string(total) + " control points take");
    return values;
  }
  catch (const IGAReadError& e)
  {
    throw IGAReadError(0, "GridFunction " + file + ":" + e.what());
  }
}

/// Adds the fields of the GridFunction files to every patch.
void addGridFunctions(const std::vector<std::string>& files, const SpaceHeader& mesh, size_t total,
  const std::vector<std::vector<size_t>>& patchPoints, iga::NurbsSet<double>& set)
{
  for (const std::string& file : files)
  {
    int components = 0;
    const auto values = readGridFunction(file, mesh, total, components);
    const std::string name = fieldName(file);
    for (int c = 0; c < components; ++c)
      set.attributeNames.push_back(components == 1 ? name : name + "_" + std::to_string(c));
    for (size_t p = 0; p < patchPoints.size(); ++p)
    {
      std::vector<double> patchValues;
      for (size_t n : patchPoints[p])
        patchValues.insert(patchValues.end(), values.begin() + long(n * components),
          values.begin() + long((n + 1) * components));
      if (p < set.volumes.size())
        iga::appendAttributes(set.volumes[p], patchValues, components);
      else
        iga::appendAttributes(set.surfaces[p - set.volumes.size()], patchValues, components);
    }
  }
}
} // namespace

void vtkIGAMFEMReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (const auto& name : this->GridFunctionFileNames)
    os << indent << "GridFunctionFileName: " << name << "\n";
}

void vtkIGAMFEMReader::AddGridFunctionFileName(const char* name)
{
  this->GridFunctionFileNames.emplace_back(name ? name : "");
  this->Modified();
}

void vtkIGAMFEMReader::RemoveAllGridFunctionFileNames()
{
  if (!this->GridFunctionFileNames.empty())
  {
    this->GridFunctionFileNames.clear();
    this->Modified();
  }
}

int vtkIGAMFEMReader::GetNumberOfGridFunctionFileNames() const
{
  return int(this->GridFunctionFileNames.size());
}

const char* vtkIGAMFEMReader::GetGridFunctionFileName(int index) const
{
  return index >= 0 && size_t(index) < this->GridFunctionFileNames.size()
           ? this->GridFunctionFileNames[size_t(index)].c_str()
           : nullptr;
}

std::string vtkIGAMFEMReader::InputStamp() const
{
  std::string stamp;
  for (const auto& name : this->GridFunctionFileNames)
    stamp += name + " " + std::to_string(vtksys::SystemTools::ModifiedTime(name.c_str())) + "\n";
  return stamp;
}

bool vtkIGAMFEMReader::IsOwnFormat(const std::string& head) const
{
  return head.compare(0, 20, "MFEM NURBS mesh v1.0") == 0;
}

std::string vtkIGAMFEMReader::ReadNurbs(const std::string& text, vtkIGANurbsData* data)
{
  iga::NurbsSet<double> set;
  set.attributeNames = iga::geometryAttributeNames();
  try
  {
    IGATextLines lines(text, '#');
    const IGATextLine& title = lines.take("the title");
    if (trimmed(title.text) != "MFEM NURBS mesh v1.0")
      throw IGAReadError(title.number,
        "'" + trimmed(title.text) + "' is not an MFEM NURBS mesh (\"MFEM NURBS mesh v1.0\")");
    const Topology topology = readTopology(lines);
    if (topology.patches.empty())
      throw IGAReadError(0, "the mesh has no elements (patches)");
    const bool patchesForm = trimmed(lines.peek("knotvectors or patches").text) == "patches";
    if (patchesForm)
    {
      if (!this->GridFunctionFileNames.empty())
        throw IGAReadError(0, "GridFunctions are read on meshes that list knot vectors and "
                              "weights, not on the \"patches\" form");
      readPatchesForm(lines, topology, set);
    }
    else
    {
      std::vector<std::vector<size_t>> patchPoints;
      SpaceHeader space;
      size_t total = 0;
      readTopologyForm(lines, topology, set, patchPoints, space, total);
      addGridFunctions(this->GridFunctionFileNames, space, total, patchPoints, set);
    }
  }
  catch (const IGAReadError& e)
  {
    return e.what();
  }
  return data->SetPatches(set);
}

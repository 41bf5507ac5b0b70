// The boundary faces of volume sets: a face is the volume on its side exactly, faces shared by
// two patches and faces collapsed onto an axis are not on the boundary, counted on datasets
// whose faces are known by construction.
#include "BoundaryChecks.h"

#include "iga/Boundary.h"
#include "iga/Datasets.h"
#include "iga/DegenerateZoo.h"
#include "iga/Orientation.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <random>

namespace
{

/// Number of boundary faces of each kind (direction, side) over all patches.
int countFaces(const std::vector<iga::PatchFace>& faces, int direction, int side)
{
  return int(std::count_if(faces.begin(), faces.end(),
    [&](const iga::PatchFace& f) { return f.direction == direction && f.side == side; }));
}

TEST(Boundary, FaceIsTheVolumeOnItsSide)
{
  // A deformed tube patch: rational (weights sqrt(2)/2), three attributes.
  const auto tube = iga::makeTube<double>(0.25, 0.7);
  const auto& volume = tube.patches[3];
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int direction = 0; direction < 3; ++direction)
  {
    for (int side = 0; side < 2; ++side)
    {
      const auto face = iga::faceSurface(volume, direction, side);
      int s, t;
      iga::faceDirections(direction, s, t);
      EXPECT_EQ(face.degree(0), volume.degree(s));
      EXPECT_EQ(face.degree(1), volume.degree(t));
      for (int sample = 0; sample < 20; ++sample)
      {
        const double st[2] = { unit(random), unit(random) };
        double u[3];
        u[direction] = side;
        u[s] = st[0];
        u[t] = st[1];
        std::vector<double> onFace(size_t(face.channels())), inVolume(size_t(face.channels()));
        iga::evaluateHomogeneous<double, 2>(face.view(), st, onFace.data(), nullptr);
        iga::evaluateHomogeneous<double, 3>(volume.view(), u, inVolume.data(), nullptr);
        for (size_t c = 0; c < onFace.size(); ++c)
          EXPECT_NEAR(onFace[c], inVolume[c], 1e-14) << direction << side << " channel " << c;
      }
    }
  }
}

/// Euclidean point and, with `du`, the partial derivatives of a rational patch's geometry.
template<int Dim>
glm::dvec3 pointOf(const iga::PatchView<const double, Dim>& patch, const double* u, glm::dvec3* du)
{
  std::vector<double> values(size_t(patch.channels)), derivatives(size_t(Dim * patch.channels));
  iga::evaluateHomogeneous<double, Dim>(patch, u, values.data(), derivatives.data());
  glm::dvec3 x;
  for (int c = 0; c < 3; ++c)
  {
    glm::dvec3 gradient(0);
    x[c] = iga::rationalValue<double, Dim>(
      values.data(), derivatives.data(), patch.channels, c, iga::kWeightChannel, &gradient[0]);
    for (int d = 0; du && d < Dim; ++d)
      du[d][c] = gradient[d];
  }
  return x;
}

TEST(Boundary, OutwardFacesPointOutOfRightAndLeftHandedVolumes)
{
  const auto tube = iga::makeTube<double>(0.25, 0.7);
  auto mirrored = tube.patches[3];
  iga::reverseDirection(mirrored.view(), 1);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.05, 0.95);
  const iga::BezierVolume<double>* volumes[2] = { &tube.patches[3], &mirrored };
  for (const auto* volume : volumes)
  {
    const bool leftHanded = iga::signedVolume(volume->view()) < 0;
    EXPECT_EQ(leftHanded, (volume == &mirrored) != (iga::signedVolume(tube.patches[3].view()) < 0));
    for (int direction = 0; direction < 3; ++direction)
      for (int side = 0; side < 2; ++side)
      {
        const iga::PatchFace face{ 0, direction, side };
        const auto surface = iga::outwardFaceSurface(*volume, face, leftHanded);
        const bool reversed = iga::faceNormalPointsInward(face, leftHanded);
        for (int sample = 0; sample < 10; ++sample)
        {
          const double st[2] = { unit(random), unit(random) };
          glm::dvec3 dx[2];
          const glm::dvec3 x = pointOf<2>(surface.view(), st, dx);
          double u[3];
          iga::faceParameterInVolume(face, reversed, st[0], st[1], u);
          EXPECT_LT(glm::length(pointOf<3>(volume->view(), u, nullptr) - x), 1e-12);
          u[direction] = side ? 0.9 : 0.1; // a point inside the volume near the face
          const glm::dvec3 inward = pointOf<3>(volume->view(), u, nullptr) - x;
          EXPECT_LT(glm::dot(glm::cross(dx[0], dx[1]), inward), 0)
            << "face " << direction << side << (leftHanded ? " left-handed" : "");
        }
      }
  }
}

TEST(Boundary, OnePatchHasSixFaces)
{
  EXPECT_EQ(iga::boundaryFaces(iga::makeMarsdenSphere<double>(3).patches).size(), 6u);
}

TEST(Boundary, SharedFacesOfTheTubeAreDropped)
{
  // 4 quadrants (angle) x 1 wall (radius) x 2 segments (height): the faces across the angle
  // and the middle ones across the height are shared; inner, outer, bottom and top remain.
  for (double time : { 0.0, 0.5, 1.0 }) // deformed: shared points move together
  {
    const auto tube = iga::makeTube<double>(0.25, time);
    ASSERT_EQ(tube.patches.size(), 8u);
    const auto faces = iga::boundaryFaces(tube.patches);
    EXPECT_EQ(faces.size(), 24u) << time;
    EXPECT_EQ(countFaces(faces, 0, 0) + countFaces(faces, 0, 1), 0) << "across the angle";
    EXPECT_EQ(countFaces(faces, 1, 0), 8) << "inner wall";
    EXPECT_EQ(countFaces(faces, 1, 1), 8) << "outer wall";
    EXPECT_EQ(countFaces(faces, 2, 0) + countFaces(faces, 2, 1), 8) << "bottom and top";
  }
}

/// The tube at rest: inner and outer cylinders (radii 0.25 and 1, height 2) and two annuli; the
/// faces close up.
TEST(Boundary, TubeBoundaryIsClosedWithTheAnalyticArea)
{
  const double pi = 3.141592653589793;
  const auto tube = iga::makeTube<double>(0.25, 0.0);
  const auto faces = iga::boundaryFaces(tube.patches);
  EXPECT_EQ(igatest::openBoundaryEdges(tube.patches, faces), 0u);
  EXPECT_NEAR(igatest::boundaryArea(tube.patches, faces),
    2 * pi * 0.25 * 2 + 2 * pi * 1 * 2 + 2 * pi * (1 - 0.25 * 0.25), 1e-6);
  // One face fewer leaves a hole of four open edges.
  EXPECT_EQ(igatest::openBoundaryEdges(tube.patches, { faces.begin() + 1, faces.end() }), 4u);
  const auto cylinder = iga::makeTube<double>(0.0, 0.7);
  EXPECT_EQ(igatest::openBoundaryEdges(cylinder.patches, iga::boundaryFaces(cylinder.patches)), 0u);
}

TEST(Boundary, FacesCollapsedOntoTheAxisAreDropped)
{
  const auto faces = iga::boundaryFaces(iga::makeTube<double>(0.0, 0.0).patches);
  EXPECT_EQ(faces.size(), 16u);
  EXPECT_EQ(countFaces(faces, 1, 0), 0) << "the inner face is the axis";
}

TEST(Boundary, SharedFacesAreFoundWhateverTheOrientation)
{
  // Two patches of the tube, one with its directions reversed (inverted, then re-oriented):
  // their common face is still found.
  auto tube = iga::makeTube<double>(0.25, 0.0);
  const auto regular = iga::boundaryFaces(tube.patches).size();
  ASSERT_EQ(regular, 24u);
  for (int direction = 0; direction < 3; ++direction)
  {
    auto reversed = tube;
    iga::reverseDirection(reversed.patches[2].view(), direction);
    EXPECT_EQ(iga::boundaryFaces(reversed.patches).size(), regular) << direction;
  }
  // The same face with its weights scaled is the same rational surface.
  for (auto& value : tube.patches[5].coeffs())
    value *= 3;
  EXPECT_EQ(iga::boundaryFaces(tube.patches).size(), regular);
}

TEST(Boundary, BladeWallAndCapsRemain)
{
  const auto layout = iga::bladeLayout(2000);
  const auto blade = iga::makeBlade<double>(layout, 0.5);
  const auto faces = iga::boundaryFaces(blade.patches);
  // Around (periodic: every face across it shared), through the wall (inside and outside
  // surfaces), along the span (root and tip caps).
  EXPECT_EQ(
    long(faces.size()), 2 * layout.around * layout.along + 2 * layout.around * layout.through);
  EXPECT_EQ(igatest::openBoundaryEdges(blade.patches, faces), 0u);
}

TEST(Boundary, ApartPatchesKeepAllFaces)
{
  const auto zoo = iga::makeDegenerateZoo<double>();
  // The point-collapsed patch has no face with area; a collapsed edge leaves its faces their
  // area; the others keep their six.
  const auto faces = iga::boundaryFaces(zoo.patches);
  EXPECT_EQ(std::count_if(faces.begin(), faces.end(), [](auto f) { return f.patch == 2; }), 0);
  for (int patch : { 0, 1, 3, 4, 5, 6, 7 })
    EXPECT_EQ(
      std::count_if(faces.begin(), faces.end(), [&](auto f) { return f.patch == patch; }), 6)
      << patch;
}

} // namespace

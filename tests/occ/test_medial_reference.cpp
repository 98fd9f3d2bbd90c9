// The medial axis of every reference and real CAD face: the properties every
// medial axis has, and the known answers of the reference shapes.
#include <gtest/gtest.h>

#include <cmath>

#include "medial/medial_axis.hpp"
#include "medial_checks.hpp"
#include "occ/occ_reader.hpp"
#include "test_support.hpp"

namespace mm {
namespace {

using test::of_kind;

TEST(MedialReference, EveryReferenceAndRealFaceHasAValidAxis) {
  for (const char* folder : {"/geometry", "/realcad/faces"}) {
    for (const std::string& path : test::brep_files(test::shared_dir() + folder)) {
      SCOPED_TRACE(path);
      const FaceModel face = read_face_models(path, {}).front();
      const MedialAxis axis = compute_medial_axis(face);
      EXPECT_TRUE(test::medial_axis_is_valid(face, axis, 1e-6));
      // Every convex corner has its flare, and only convex corners have one.
      int convex = 0;
      for (const Corner& c : face.corners) convex += c.angle < kPi;
      EXPECT_EQ(static_cast<int>(of_kind(axis, MedialVertexKind::Flare).size()), convex);
    }
  }
}

TEST(MedialReference, PlateWithHoleHasFourJunctionsOnItsDiagonals) {
  const MedialAxis axis = compute_medial_axis(test::reference_face("plate_with_hole"));
  const auto junctions = of_kind(axis, MedialVertexKind::Junction);
  ASSERT_EQ(junctions.size(), 4u);
  // Equidistant from two sides of the 4 x 4 plate and the hole of radius 1:
  // 2 - x = x * sqrt(2) - 1, so x = 3 / (1 + sqrt 2).
  const double x = 3.0 / (1.0 + std::sqrt(2.0));
  for (const MedialVertex* v : junctions) {
    EXPECT_NEAR(std::abs(v->p.x), x, 1e-9);
    EXPECT_NEAR(std::abs(v->p.y), x, 1e-9);
    EXPECT_NEAR(v->r, 2 - x, 1e-9);
  }
}

TEST(MedialReference, HalfDiscAxisIsAParabola) {
  const MedialAxis axis = compute_medial_axis(test::reference_face("half_disk"));
  ASSERT_EQ(axis.edges.size(), 1u);
  EXPECT_EQ(of_kind(axis, MedialVertexKind::Flare).size(), 2u);
  // Equidistant from the diameter (y = 0) and the arc of radius 1: y = (1 - x^2) / 2.
  for (const MedialPoint& p : axis.edges[0].points) EXPECT_NEAR(p.p.y, 0.5 * (1 - p.p.x * p.p.x), 1e-9);
}

TEST(MedialReference, RegularPolygonsMeetAtTheirCentres) {
  for (const auto& [name, sides] : {std::pair<const char*, int>{"triangle", 3}, {"pentagon", 5}, {"hexagon", 6}}) {
    SCOPED_TRACE(name);
    const FaceModel face = test::reference_face(name);
    Vec2 centroid;
    for (const Corner& c : face.corners) centroid = centroid + c.position / sides;
    const MedialAxis axis = compute_medial_axis(face);
    const auto junctions = of_kind(axis, MedialVertexKind::Junction);
    ASSERT_EQ(junctions.size(), 1u);
    EXPECT_NEAR(distance(junctions[0]->p, centroid), 0.0, 1e-9);
    EXPECT_EQ(static_cast<int>(junctions[0]->touches.size()), sides);
    EXPECT_EQ(axis.edges.size(), static_cast<std::size_t>(sides));
  }
}

TEST(MedialReference, RoundEndsAndEllipse) {
  const MedialAxis stadium = compute_medial_axis(test::reference_face("stadium"));
  ASSERT_EQ(of_kind(stadium, MedialVertexKind::FiniteContact).size(), 2u);
  for (const MedialVertex* v : of_kind(stadium, MedialVertexKind::FiniteContact)) {
    EXPECT_NEAR(std::abs(v->p.x), 1.5, 1e-9);
    EXPECT_NEAR(v->contact_angle, kPi, 1e-9);
  }
  const MedialAxis circle = compute_medial_axis(test::reference_face("circle"));
  ASSERT_EQ(circle.vertices.size(), 1u);
  EXPECT_EQ(circle.vertices[0].kind, MedialVertexKind::FiniteContact);
  EXPECT_NEAR(circle.vertices[0].r, 1.0, 1e-12);
  const MedialAxis ellipse = compute_medial_axis(test::reference_face("ellipse"));
  ASSERT_EQ(of_kind(ellipse, MedialVertexKind::CurvatureContact).size(), 2u);
  for (const MedialVertex* v : of_kind(ellipse, MedialVertexKind::CurvatureContact)) {
    EXPECT_NEAR(std::abs(v->p.x), 1.5, 1e-9);
    EXPECT_NEAR(v->r, 0.5, 1e-9);
  }
  const MedialAxis annulus = compute_medial_axis(test::reference_face("annulus"));
  ASSERT_EQ(annulus.edges.size(), 1u);
  EXPECT_EQ(annulus.edges[0].from, -1);
}

TEST(MedialReference, RealFacesFindTheirArcCentres) {
  // The plate of 8 round holes and rounded corners: its slot ends and round
  // corners are finite contacts; the bracket's face has round outer corners too.
  const FaceModel cover =
      read_face_models(test::shared_dir() + "/realcad/faces/trimesh_featuretype_50.brep", {}).front();
  const MedialAxis axis = compute_medial_axis(cover);
  EXPECT_EQ(of_kind(axis, MedialVertexKind::FiniteContact).size(), 2u);
  EXPECT_EQ(of_kind(axis, MedialVertexKind::CurvatureContact).size(), 2u);
}

}  // namespace
}  // namespace mm

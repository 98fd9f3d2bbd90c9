// The medial axis of hand-built faces with known answers, and its properties
// on a thousand random faces with arcs and holes.
#include <gtest/gtest.h>

#include <cmath>

#include "face_builders.hpp"
#include "medial/medial_axis.hpp"
#include "medial_checks.hpp"
#include "svg/svg_writer.hpp"

namespace mm {
namespace {

using test::full_circle;
using test::line;
using test::polygon;

using test::arc;
using test::face;
using test::of_kind;

TEST(MedialAxis, Rectangle4x1) {
  const FaceModel f = face({polygon({{0, 0}, {4, 0}, {4, 1}, {0, 1}})});
  const MedialAxis axis = compute_medial_axis(f);
  const auto junctions = of_kind(axis, MedialVertexKind::Junction);
  ASSERT_EQ(junctions.size(), 2u);
  const double x0 = std::min(junctions[0]->p.x, junctions[1]->p.x), x1 = std::max(junctions[0]->p.x, junctions[1]->p.x);
  EXPECT_NEAR(x0, 0.5, 1e-12);
  EXPECT_NEAR(x1, 3.5, 1e-12);
  EXPECT_NEAR(junctions[0]->p.y, 0.5, 1e-12);
  EXPECT_NEAR(junctions[0]->r, 0.5, 1e-12);
  EXPECT_EQ(of_kind(axis, MedialVertexKind::Flare).size(), 4u);
  EXPECT_EQ(axis.edges.size(), 5u);
  EXPECT_TRUE(test::medial_axis_is_valid(f, axis, 1e-9));
}

TEST(MedialAxis, SquareHasOneJunctionAtItsCentre) {
  const FaceModel f = face({polygon({{0, 0}, {2, 0}, {2, 2}, {0, 2}})});
  const MedialAxis axis = compute_medial_axis(f);
  const auto junctions = of_kind(axis, MedialVertexKind::Junction);
  ASSERT_EQ(junctions.size(), 1u);
  EXPECT_NEAR(distance(junctions[0]->p, {1, 1}), 0.0, 1e-12);
  EXPECT_EQ(junctions[0]->touches.size(), 4u);
  EXPECT_EQ(junctions[0]->edges.size(), 4u);
  EXPECT_TRUE(test::medial_axis_is_valid(f, axis, 1e-9));
}

TEST(MedialAxis, CircleIsOneFiniteContactVertex) {
  const FaceModel f = face({{full_circle({0.3, -0.2}, 1.0, 1)}});
  const MedialAxis axis = compute_medial_axis(f);
  ASSERT_EQ(axis.vertices.size(), 1u);
  EXPECT_TRUE(axis.edges.empty());
  const MedialVertex& v = axis.vertices[0];
  EXPECT_EQ(v.kind, MedialVertexKind::FiniteContact);
  EXPECT_NEAR(distance(v.p, {0.3, -0.2}), 0.0, 1e-15);
  EXPECT_NEAR(v.r, 1.0, 1e-15);
  EXPECT_NEAR(v.contact_angle, 2 * kPi, 1e-12);
}

TEST(MedialAxis, StadiumEndsAtItsArcCentres) {
  // A 3 x 1 slot with round ends.
  const FaceModel f = face({{line({-1.5, -0.5}, {1.5, -0.5}), arc({1.5, -0.5}, {1.5, 0.5}, 0.5),
                             line({1.5, 0.5}, {-1.5, 0.5}), arc({-1.5, 0.5}, {-1.5, -0.5}, 0.5)}});
  const MedialAxis axis = compute_medial_axis(f);
  const auto ends = of_kind(axis, MedialVertexKind::FiniteContact);
  ASSERT_EQ(ends.size(), 2u);
  EXPECT_EQ(axis.vertices.size(), 2u);
  for (const MedialVertex* v : ends) {
    EXPECT_NEAR(std::abs(v->p.x), 1.5, 1e-12);
    EXPECT_NEAR(v->p.y, 0.0, 1e-12);
    EXPECT_NEAR(v->r, 0.5, 1e-12);
    EXPECT_NEAR(v->contact_angle, kPi, 1e-9);
  }
  ASSERT_EQ(axis.edges.size(), 1u);
  for (const MedialPoint& p : axis.edges[0].points) {
    EXPECT_NEAR(p.p.y, 0.0, 1e-12);
    EXPECT_NEAR(medial_angle(p), kPi, 1e-9);
  }
  EXPECT_TRUE(test::medial_axis_is_valid(f, axis, 1e-9));
}

TEST(MedialAxis, EllipseSegmentEndsAtCurvatureContacts) {
  const FaceModel f = face({{BoundaryEdge{EllipseCurve{{0, 0}, {1, 0}, 2.0, 1.0, 1}, 0.0, 2 * kPi, 0, {}, {}}}});
  const MedialAxis axis = compute_medial_axis(f);
  const auto ends = of_kind(axis, MedialVertexKind::CurvatureContact);
  ASSERT_EQ(ends.size(), 2u);
  EXPECT_EQ(axis.vertices.size(), 2u);
  ASSERT_EQ(axis.edges.size(), 1u);
  // Centres of curvature at the ends of the major axis: x = +-(a^2 - b^2)/a, radius b^2/a.
  for (const MedialVertex* v : ends) {
    EXPECT_NEAR(std::abs(v->p.x), 1.5, 1e-9);
    EXPECT_NEAR(v->p.y, 0.0, 1e-9);
    EXPECT_NEAR(v->r, 0.5, 1e-9);
  }
  for (const MedialPoint& p : axis.edges[0].points) EXPECT_NEAR(p.p.y, 0.0, 1e-9);
  EXPECT_TRUE(test::medial_axis_is_valid(f, axis, 1e-9));
}

TEST(MedialAxis, AnnulusIsAClosedLoop) {
  const FaceModel f = face({{full_circle({0, 0}, 2.0, 1)}, {full_circle({0, 0}, 1.0, -1)}});
  const MedialAxis axis = compute_medial_axis(f);
  EXPECT_TRUE(axis.vertices.empty());
  ASSERT_EQ(axis.edges.size(), 1u);
  EXPECT_EQ(axis.edges[0].from, -1);
  EXPECT_EQ(axis.edges[0].to, -1);
  for (const MedialPoint& p : axis.edges[0].points) {
    EXPECT_NEAR(norm(p.p), 1.5, 1e-12);
    EXPECT_NEAR(p.r, 0.5, 1e-12);
  }
  EXPECT_TRUE(test::medial_axis_is_valid(f, axis, 1e-9));
}

TEST(MedialAxis, LShapeHasAParabolaAtItsReflexCorner) {
  const FaceModel f = face({polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}})});
  const MedialAxis axis = compute_medial_axis(f);
  EXPECT_EQ(of_kind(axis, MedialVertexKind::Flare).size(), 5u);
  // Points whose disc touches the reflex corner (1, 1) lie on the parabola with
  // that focus and the far wall as directrix: equally far from both.
  int on_parabola = 0;
  for (const MedialEdge& e : axis.edges) {
    for (const MedialPoint& p : e.points) {
      for (const BoundaryPlace* t : {&p.left, &p.right}) {
        if (t->corner < 0 || distance(t->point, {1, 1}) > 1e-12) continue;
        ++on_parabola;
        EXPECT_NEAR(distance(p.p, {1, 1}), std::min(p.p.x, p.p.y), 1e-12);
      }
    }
  }
  EXPECT_GT(on_parabola, 5);
  // The junction between the parabola and the walls' bisector: (2 - sqrt 2) on the diagonal.
  bool found = false;
  for (const MedialVertex* v : of_kind(axis, MedialVertexKind::Junction)) {
    found |= distance(v->p, {2 - std::sqrt(2.0), 2 - std::sqrt(2.0)}) < 1e-12;
  }
  EXPECT_TRUE(found);
  EXPECT_TRUE(test::medial_axis_is_valid(f, axis, 1e-9));
}

TEST(MedialAxis, TinyEdgeBesideLongOnes) {
  // A 100 x 40 plate with a 0.05 notch step in one side.
  const FaceModel f = face({polygon({{0, 0}, {100, 0}, {100, 40}, {50.05, 40}, {50.05, 39.95}, {0, 39.95}})});
  const MedialAxis axis = compute_medial_axis(f);
  EXPECT_TRUE(test::medial_axis_is_valid(f, axis, 1e-9));
  EXPECT_EQ(of_kind(axis, MedialVertexKind::Flare).size(), 5u);  // the step's convex corner too
}

using test::random_face;

// The medial axis of every random face (a thousand star-shaped ones, then
// three hundred notched ones) is one connected graph with a cycle per hole and every point within 1e-6 of the diagonal
// of the exact axis; each failing face is drawn to random_face_N.svg.
TEST(MedialAxis, PropertiesHoldOnAThousandRandomFaces) {
  std::mt19937 rng(20261121);
  int checked = 0, rejected = 0;
  std::vector<std::string> failures;
  while (checked < 1300) {
    FaceModel f;
    try {
      f = checked < 1000 ? random_face(rng, checked) : test::random_notched_face(rng, checked);
    } catch (const InputError&) {
      ++rejected;  // an inward arc crossed a hole or a side: not a valid face
      continue;
    }
    const MedialAxis axis = compute_medial_axis(f);
    const auto valid = test::medial_axis_is_valid(f, axis, 1e-6);
    if (!valid) {
      SvgCanvas canvas(bounding_box(f), 800);
      draw_face(canvas, f);
      draw_medial_axis(canvas, f, axis);
      canvas.save("random_face_" + std::to_string(checked) + ".svg");
      failures.push_back(valid.message());
    }
    ++checked;
  }
  EXPECT_TRUE(failures.empty()) << ::testing::PrintToString(failures);
  EXPECT_LT(rejected, 200);
}

// The census's random face 1378 (tests/core/mesh_census.cpp): its first axis,
// from coarse chords, has a cycle too many (its points pass the first
// accuracy test, so no finer chords were tried, and the final check stopped
// it with a point 0.0019 off its radius); finer chords are now tried for a
// wrong topology as for an inexact point, and they get it right.
TEST(MedialAxis, WrongTopologyFromCoarseChordsIsBuiltAgainFiner) {
  const std::vector<std::pair<int, FaceModel>> faces = test::census_faces({1378});
  ASSERT_EQ(faces.size(), 1u);
  const FaceModel& face = faces.front().second;
  ASSERT_EQ(face.name, "random face 1378");
  const MedialAxis axis = compute_medial_axis(face);
  EXPECT_TRUE(test::medial_axis_is_valid(face, axis, 1e-6));
}

}  // namespace
}  // namespace mm

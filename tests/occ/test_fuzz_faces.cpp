// Faces the random-face fuzz program (tests/fuzz) found failing, kept as
// regression faces: each must now get a valid mesh. strip_7_63 and
// strip_7_313: thin strips whose slot puts a k = +1 at the flare of a convex
// corner beside a k = -1 (fixed onto the corner); bspline_8_117: a ring
// whose branch into a bump ends at a curvature contact with k = -1 (fixed
// onto the touching point); elliptic_9_99: a lens with 12 degree tips (its
// extra convex corners on the arc, not the chord). bspline_1_37 and
// elliptic_2_1614: rings whose pentagon block has a corner on a mapped
// neighbour's side (a +1 and a -1 on one medial circle), so that no counts
// satisfy both templates: interval assignment must relax, not fail.
// bspline_2_1947 and bspline_5_357: B-spline outlines with a round hole
// where blocks' few intervals on the hole folded elements that smoothing
// with fixed boundary nodes could not unfold.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "mesh_checks.hpp"
#include "occ/occ_reader.hpp"
#include "pipeline/pipeline.hpp"

namespace mm {
namespace {

TEST(FuzzFaces, EachGetsAValidMesh) {
  for (const char* name : {"strip_7_63", "strip_7_313", "bspline_8_117", "elliptic_9_99", "bspline_1_37",
                           "elliptic_2_1614", "bspline_2_1947", "bspline_5_357"}) {
    std::ifstream in(std::string(MEDIALMESH_SOURCE_DIR) + "/tests/data/fuzz/" + name + ".brep");
    std::stringstream text;
    text << in.rdbuf();
    const FaceModel face = face_model_from_brep_string(text.str(), name);
    PipelineOptions options;
    options.meshing.size = 0.05 * face.size;
    MeshedFace m;
    try {
      m = mesh_face(face, options);
    } catch (const SelfCheckError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    EXPECT_TRUE(test::mesh_validity_problems(face, m.blocks.mesh).empty()) << name;
    EXPECT_GT(m.quality.min_scaled_jacobian, 0.0) << name;
    EXPECT_EQ(m.quality.inverted, 0) << name;
  }
}

// The relaxed rings: the pentagon's corner taken as flat cancels its k = +1
// against the -1 on its corner, so the mesh has no irregular interior node,
// and says what was relaxed.
TEST(FuzzFaces, ContradictoryTemplatesAreRelaxedWithANote) {
  for (const char* name : {"bspline_1_37", "elliptic_2_1614"}) {
    std::ifstream in(std::string(MEDIALMESH_SOURCE_DIR) + "/tests/data/fuzz/" + name + ".brep");
    std::stringstream text;
    text << in.rdbuf();
    const FaceModel face = face_model_from_brep_string(text.str(), name);
    PipelineOptions options;
    options.meshing.size = 0.05 * face.size;
    const MeshedFace m = mesh_face(face, options);
    EXPECT_TRUE(test::mesh_validity_problems(face, m.blocks.mesh).empty()) << name;
    EXPECT_TRUE(m.quality.irregular_interior.empty()) << name;
    bool noted = false;
    for (const std::string& note : m.blocks.notes) noted = noted || note.find("taken as flat") != std::string::npos;
    EXPECT_TRUE(noted) << name;
  }
}

}  // namespace
}  // namespace mm

// A meshing run told to a Progress: its stages in order, its blocks
// counted, the same mesh as without one, and a cancel from another thread
// stopping it between steps.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "face_builders.hpp"
#include "pipeline/pipeline.hpp"
#include "support/progress.hpp"

namespace mm {
namespace {

// A plate with a hole off centre: several blocks, a few thousand quads at 0.2.
FaceModel plate() {
  return test::face({test::polygon({{0, 0}, {10, 0}, {10, 6}, {0, 6}}), {test::full_circle({3.5, 3}, 1.5, -1)}},
                    "plate");
}

TEST(Progress, StagesAreToldInOrderAndTheMeshIsTheSame) {
  const FaceModel face = plate();
  PipelineOptions options;
  options.meshing.size = 0.2;
  const MeshedFace without = mesh_face(face, options);

  Progress progress;
  EXPECT_EQ(progress.state().stage, "");
  std::vector<std::string> seen;
  std::atomic<bool> running{true};
  // Read from another thread while meshing, as a GUI does.
  std::thread watcher([&] {
    while (running) {
      const std::string stage = progress.state().stage;
      if (!stage.empty() && (seen.empty() || seen.back() != stage)) seen.push_back(stage);
      std::this_thread::yield();
    }
  });
  options.meshing.progress = &progress;
  const MeshedFace with = mesh_face(face, options);
  running = false;
  watcher.join();

  EXPECT_EQ(with.blocks.mesh.nodes.size(), without.blocks.mesh.nodes.size());
  EXPECT_EQ(with.blocks.mesh.quads, without.blocks.mesh.quads);
  const Progress::State last = progress.state();
  EXPECT_EQ(last.stage, "quality");
  EXPECT_FALSE(progress.cancelled());
  // Whatever the watcher caught, it caught in the pipeline's order.
  const std::vector<std::string> order{"medial axis", "decomposition", "interval counts",
                                       "blocks",      "smoothing",     "quality"};
  std::size_t at = 0;
  for (const std::string& stage : seen) {
    while (at < order.size() && order[at] != stage) ++at;
    EXPECT_LT(at, order.size()) << stage << " out of order";
  }
}

TEST(Progress, CancelStopsARunningMeshInItsBlocks) {
  const FaceModel face = plate();
  PipelineOptions options;
  options.meshing.size = 0.2;
  const std::size_t blocks = mesh_face(face, options).decomposition.blocks.size();

  options.meshing.size = 0.01;  // some 500 000 quads: the blocks take a while
  Progress progress;
  options.meshing.progress = &progress;
  std::atomic<bool> finished{false};
  Progress::State at_cancel;
  std::thread canceller([&] {
    while (!finished && progress.state().stage != "blocks") std::this_thread::yield();
    at_cancel = progress.state();
    progress.cancel();
  });
  try {
    mesh_face(face, options);
    ADD_FAILURE() << "the mesh ran to its end";
  } catch (const Cancelled&) {
  }
  finished = true;
  canceller.join();
  EXPECT_TRUE(progress.cancelled());
  EXPECT_EQ(at_cancel.total, static_cast<int>(blocks));
  EXPECT_EQ(progress.state().stage, "blocks");  // stopped there, not carried on to the end
  EXPECT_LE(progress.state().done, static_cast<int>(blocks));
}

TEST(Progress, CancelledBeforeTheStartStopsAtOnce) {
  PipelineOptions options;
  options.meshing.size = 0.2;
  Progress progress;
  progress.cancel();
  options.meshing.progress = &progress;
  EXPECT_THROW(mesh_face(plate(), options), Cancelled);
  EXPECT_EQ(progress.state().stage, "");
  // Several faces too.
  EXPECT_THROW(mesh_faces({plate()}, options), Cancelled);
}

}  // namespace
}  // namespace mm

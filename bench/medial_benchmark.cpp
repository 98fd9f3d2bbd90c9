// Time of the medial axis against boundary size: square plates with 1, 10,
// 100 and 1000 round holes on a grid. Reports the number of boundary chords
// the Voronoi diagram is built on and fits the growth (expected n log n).
// Then the decomposition alone (from a given axis and flow) and the whole
// way from the boundary model to the blocks, on the same plates.
#include <benchmark/benchmark.h>

#include <cmath>

#include "decomposition/decomposition.hpp"
#include "medial/medial_axis.hpp"
#include "medial/voronoi_graph.hpp"

namespace {

mm::FaceModel plate_with_holes(int holes) {
  const int per_row = static_cast<int>(std::ceil(std::sqrt(holes)));
  const double side = per_row;  // unit cells
  mm::RawFace raw;
  raw.name = std::to_string(holes) + " holes";
  const mm::Vec2 corners[4] = {{0, 0}, {side, 0}, {side, side}, {0, side}};
  std::vector<mm::BoundaryEdge> outer;
  for (int i = 0; i < 4; ++i) {
    const mm::Vec2 a = corners[i], b = corners[(i + 1) % 4];
    outer.push_back({mm::LineCurve{a, mm::normalized(b - a)}, 0.0, mm::distance(a, b), 0, {}, {}});
  }
  raw.loops.push_back(outer);
  for (int h = 0; h < holes; ++h) {
    const mm::Vec2 c{0.5 + h % per_row, 0.5 + h / per_row};
    raw.loops.push_back({{mm::CircleCurve{c, 0.3, 0.0, -1}, 0.0, 2 * mm::kPi, 0, {}, {}}});
  }
  return mm::build_face_model(raw);
}

void BM_MedialAxisOfPlate(benchmark::State& state) {
  const mm::FaceModel face = plate_with_holes(static_cast<int>(state.range(0)));
  const std::size_t chords = mm::interior_voronoi_graph(face, 1e-3 * face.size, 30.0 * mm::kPi / 180.0).segments.size();
  for (auto _ : state) benchmark::DoNotOptimize(mm::compute_medial_axis(face));
  state.counters["chords"] = static_cast<double>(chords);
  state.SetComplexityN(static_cast<int64_t>(chords));
}
BENCHMARK(BM_MedialAxisOfPlate)
    ->Arg(1)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oNLogN);

void BM_DecompositionOfPlate(benchmark::State& state) {
  const mm::FaceModel face = plate_with_holes(static_cast<int>(state.range(0)));
  const mm::MedialAxis axis = mm::compute_medial_axis(face);
  const mm::MeshFlow flow = mm::compute_mesh_flow(face, axis);
  std::size_t blocks = 0;
  for (auto _ : state) blocks = mm::decompose(face, axis, flow, {}).blocks.size();
  state.counters["singularities"] = static_cast<double>(flow.singularities.size());
  state.counters["blocks"] = static_cast<double>(blocks);
}
BENCHMARK(BM_DecompositionOfPlate)->Arg(1)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);

void BM_BoundaryToBlocksOfPlate(benchmark::State& state) {
  const mm::FaceModel face = plate_with_holes(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const mm::MedialAxis axis = mm::compute_medial_axis(face);
    const mm::MeshFlow flow = mm::compute_mesh_flow(face, axis);
    benchmark::DoNotOptimize(mm::decompose(face, axis, flow, {}));
  }
}
BENCHMARK(BM_BoundaryToBlocksOfPlate)->Arg(1)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

#include "pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include "medial/medial_axis.hpp"
#include "singularity/merge.hpp"
#include "singularity/mesh_flow.hpp"

namespace mm {

namespace {

using Clock = std::chrono::steady_clock;
using StageSeconds = std::vector<std::pair<std::string, double>>;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Adds to the stage of that name, appended when new: several faces' stages sum.
void add_stage(StageSeconds& stages, const std::string& name, double seconds) {
  const auto found = std::find_if(stages.begin(), stages.end(), [&](const auto& s) { return s.first == name; });
  if (found == stages.end()) {
    stages.emplace_back(name, seconds);
  } else {
    found->second += seconds;
  }
}

// The settings to fall back on, in turn, when a face's blocks with the
// settings asked for cannot be meshed. Merging is a choice for fewer
// irregular nodes, never a must, and a merged group can get a block its
// geometry does not fit (a polygon wrapped round an aerofoil's nose or a
// blade's trailing edge, whose first placement folds beyond untangling):
// less merging first, then none. Last, splits along every concave corner's
// cross, with the merging asked for and with none: a big submapped region
// with many reflex corners (a gear's ring with a keyway) whose placement
// folds becomes blocks with few. First of all, the decomposition without
// its orthogonal joins (the least change), then submapped blocks typed by
// their corners alone where following the outline's turning was tried: a
// typing with a side far off its direction that the lattice survives.
std::vector<PipelineOptions> fallbacks(const PipelineOptions& options) {
  std::vector<PipelineOptions> list;
  if (options.decomposition.orthogonal_joins) {
    PipelineOptions unjoined = options;
    unjoined.decomposition.orthogonal_joins = false;
    list.push_back(unjoined);
  }
  if (options.decomposition.submap_corners_follow_turning) {
    PipelineOptions by_corners = options;
    by_corners.decomposition.submap_corners_follow_turning = false;
    list.push_back(by_corners);
  }
  PipelineOptions less = options;
  for (int step = 0; options.decomposition.merge && step < 2; ++step) {
    if (options.decomposition.tolerance.mesh_size > 0.0) {
      less.decomposition.tolerance.mesh_size *= 0.5;
    } else if (less.decomposition.tolerance.radius_factor > 0.5) {
      less.decomposition.tolerance.radius_factor = 0.5;
    } else if (less.decomposition.tolerance.radius_factor > 0.25) {
      less.decomposition.tolerance.radius_factor = 0.25;
    } else {
      break;
    }
    list.push_back(less);
  }
  less.decomposition.merge = false;
  if (options.decomposition.merge) list.push_back(less);
  if (options.decomposition.split_concave_corners) return list;
  PipelineOptions split = options;
  split.decomposition.split_concave_corners = true;
  list.push_back(split);
  if (options.decomposition.merge) {
    split.decomposition.merge = false;
    list.push_back(split);
  }
  return list;
}

std::string settings_text(const PipelineOptions& options) {
  std::ostringstream text;
  if (!options.decomposition.merge) {
    text << "no merging";
  } else if (options.decomposition.tolerance.mesh_size > 0.0) {
    text << "merging within " << options.decomposition.tolerance.mesh_size;
  } else {
    text << "merging factor " << options.decomposition.tolerance.radius_factor;
  }
  if (options.decomposition.split_concave_corners) text << " and splits at every concave corner";
  if (!options.decomposition.submap_corners_follow_turning) text << " and submapped corners by the corner rule alone";
  if (!options.decomposition.orthogonal_joins) text << " and no orthogonal joins";
  if (options.decomposition.whole_face) text << " and the whole face as one block";
  if (options.decomposition.frame_wrapped_holes) text << " and the holes a block runs round framed";
  return text.str();
}

// The fallbacks that `used` took against the settings `asked` for.
std::vector<Fallback> option_fallbacks(const PipelineOptions& asked, const PipelineOptions& used) {
  std::vector<Fallback> list;
  if (asked.decomposition.orthogonal_joins && !used.decomposition.orthogonal_joins) list.push_back(Fallback::NoOrthogonalJoins);
  if (asked.decomposition.submap_corners_follow_turning && !used.decomposition.submap_corners_follow_turning)
    list.push_back(Fallback::SubmapCornerRule);
  const bool by_size = used.decomposition.tolerance.mesh_size > 0.0;
  if (asked.decomposition.merge && (!used.decomposition.merge || (by_size && used.decomposition.tolerance.mesh_size < asked.decomposition.tolerance.mesh_size) ||
                      (!by_size && used.decomposition.tolerance.radius_factor < asked.decomposition.tolerance.radius_factor)))
    list.push_back(Fallback::LessMerging);
  if (!asked.decomposition.split_concave_corners && used.decomposition.split_concave_corners) list.push_back(Fallback::ConcaveCornerSplits);
  if (!asked.meshing.wide_untangling && used.meshing.wide_untangling) list.push_back(Fallback::WideUntangling);
  if (!asked.meshing.regrid_wide_folds && used.meshing.regrid_wide_folds) list.push_back(Fallback::WinslowGrid);
  if (!asked.decomposition.whole_face && used.decomposition.whole_face) list.push_back(Fallback::WholeFace);
  if (used.decomposition.merge && by_size && (!asked.decomposition.merge || used.decomposition.tolerance.mesh_size > asked.decomposition.tolerance.mesh_size))
    list.push_back(Fallback::CoarseRetry);
  if (!asked.decomposition.frame_wrapped_holes && used.decomposition.frame_wrapped_holes) list.push_back(Fallback::FramedHoles);
  return list;
}

// The fallbacks the stages took for one face: its axis and flow's, then
// its decomposition's.
std::vector<Fallback> stage_fallbacks(const FaceFlow& flow, const Decomposition& decomposition) {
  std::vector<Fallback> list = flow.fallbacks;
  if (decomposition.fixed_all) list.push_back(Fallback::FixedAll);
  if (decomposition.lenient_typing) list.push_back(Fallback::LenientTyping);
  return list;
}

// The fallbacks behind one face's mesh: the stages', then the pipeline's.
std::vector<Fallback> face_fallbacks(const FaceFlow& flow, const Decomposition& decomposition,
                                     const PipelineOptions& asked, const PipelineOptions& used) {
  std::vector<Fallback> list = stage_fallbacks(flow, decomposition);
  for (const Fallback f : option_fallbacks(asked, used)) list.push_back(f);
  return list;
}

// face_flow, its stages timed into `stages` (a fallback's second axis
// with the singularities).
FaceFlow flow_of_face(const FaceModel& face, StageSeconds& stages) {
  auto t = Clock::now();
  FaceAxis medial = compute_face_medial_axis(face);
  add_stage(stages, "medial_axis", seconds_since(t));
  t = Clock::now();
  FaceFlow result = flow_of_axis(face, std::move(medial));
  add_stage(stages, "singularities", seconds_since(t));
  return result;
}

Decomposition decompose_flow(const FaceFlow& f, const PipelineOptions& options, StageSeconds& stages) {
  const auto t = Clock::now();
  Decomposition result = decompose(f.face, f.axis, f.flow, options.decomposition);
  add_stage(stages, "decomposition", seconds_since(t));
  return result;
}

// What the decomposition sees of the settings: whether it splits at every
// concave corner, how it types submapped corners, whether it joins splits
// orthogonally, and on each face the groups of more than one singularity
// that merging makes. Two settings alike in this decompose alike.
using DecompositionKey = std::tuple<bool, bool, bool, bool, std::vector<std::vector<std::vector<int>>>>;
DecompositionKey decomposition_key(const std::vector<const FaceFlow*>& flows, const PipelineOptions& options) {
  DecompositionKey key{options.decomposition.split_concave_corners,
                       options.decomposition.submap_corners_follow_turning,
                       options.decomposition.orthogonal_joins,
                       options.decomposition.frame_wrapped_holes,
                       {}};
  for (const FaceFlow* f : flows) {
    auto& groups = std::get<4>(key).emplace_back();
    if (!options.decomposition.merge) continue;
    for (const SingularityGroup& g : group_singularities(f->flow.singularities, options.decomposition.tolerance))
      if (g.members.size() > 1) groups.push_back(g.members);
  }
  return key;
}

// Runs `attempt` with the options asked for and, while it fails a
// self-check, with each fallback that decomposes otherwise than those
// tried (a face with nothing to merge skips the merging fallbacks), and
// then with the options asked for and untangling that reaches further
// (MeshingOptions::wide_untangling: a fold in a fine mesh spans more
// elements than the default reach; it comes late because where the default
// reach fails at the default size a fallback's decomposition meshes better,
// fuzz aerofoil_12_390 at 0.39 against 0.11 untangled wide), last with
// widely folded submapped blocks placed by Winslow's grid as well
// (MeshingOptions::regrid_wide_folds), and last of all with the whole face
// as one polygon block (DecompositionOptions::whole_face: a face of one
// loop and few corners whose medial decomposition fails). The first
// failure is the one thrown when all fail. Returns the note to hand on
// (empty if none was needed); the time the failed attempts took is added to
// `stages` as "failed_attempts".
template <typename Attempt>
std::string with_fallbacks(const PipelineOptions& options, const std::vector<const FaceFlow*>& flows,
                           StageSeconds& stages, Attempt attempt) {
  auto start = Clock::now();
  try {
    attempt(options);
    return {};
  } catch (const SelfCheckError& first) {
    std::set<DecompositionKey> tried{decomposition_key(flows, options)};
    for (const PipelineOptions& fallback : fallbacks(options)) {
      if (!tried.insert(decomposition_key(flows, fallback)).second) continue;
      add_stage(stages, "failed_attempts", seconds_since(start));
      start = Clock::now();
      try {
        attempt(fallback);
        return "meshed with " + settings_text(fallback) + ", as a fallback: with " + settings_text(options) +
               " the result did not pass its check (" + first.check() + ")";
      } catch (const SelfCheckError&) {
      }
    }
    // The last resorts, after every fallback: true if `settings` passed.
    std::string note;
    const auto last_resort = [&](const PipelineOptions& settings, const std::string& meshed_with) {
      add_stage(stages, "failed_attempts", seconds_since(start));
      start = Clock::now();
      try {
        attempt(settings);
      } catch (const SelfCheckError&) {
        return false;
      }
      note = "meshed with " + meshed_with + ", as a last fallback: with " + settings_text(options) +
             " and with each other fallback the result did not pass its check (" + first.check() + ")";
      return true;
    };
    PipelineOptions wide = options;
    wide.meshing.wide_untangling = true;
    if (last_resort(wide, "those settings and untangling reaching further")) return note;
    wide.meshing.regrid_wide_folds = true;
    if (last_resort(wide,
                    "those settings, blocks folded widely by their harmonic layout placed by Winslow's grid, and "
                    "untangling reaching further"))
      return note;
    PipelineOptions whole = options;
    whole.decomposition.whole_face = true;
    if (last_resort(whole, "the whole face as one block")) return note;
    add_stage(stages, "failed_attempts", seconds_since(start));
    throw;
  }
}

// A mesh far coarser than asked is made again with the singularities
// merged as at the default size, within a twentieth of the smallest face's
// diagonal: a thin lens's two k = -1 near its wide end, left apart, make
// its body a rectangle with each long side opposite a short one (fuzz
// elliptic_41_264 at a hundredth of the diagonal: 35 elements where area /
// H^2 is 564); merged into one k = -2 the body runs along the lens (835).
// None when that merges as the options asked for already.
std::optional<PipelineOptions> coarse_retry_options(const PipelineOptions& options,
                                                    const std::vector<const FaceFlow*>& flows) {
  PipelineOptions merged = options;
  merged.decomposition.merge = true;
  merged.decomposition.tolerance.mesh_size = std::numeric_limits<double>::infinity();
  for (const FaceFlow* f : flows)
    merged.decomposition.tolerance.mesh_size = std::min(merged.decomposition.tolerance.mesh_size, 0.05 * f->face.size);
  if (decomposition_key(flows, merged) == decomposition_key(flows, options)) return std::nullopt;
  return merged;
}

std::string coarse_retry_note(const PipelineOptions& options, const PipelineOptions& retry, const std::string& why) {
  return "meshed with " + settings_text(retry) +
         " (as at the default size, a twentieth of the diagonal), as a fallback: with " + settings_text(options) + " " +
         why;
}

double total_seconds(const StageSeconds& stages) {
  double total = 0.0;
  for (const auto& stage : stages) total += stage.second;
  return total;
}

// The coarse retry: when `meshed` is far coarser than asked, or its worst
// element's shape is under kVeryPoorMesh, `make` meshes again with
// coarse_retry_options, and that result replaces it (its decomposition time
// in `passed`, the note, its settings in `used`) if it is not coarse and
// either the first was or its worst element is no longer that poor. The thin lens of
// fuzz elliptic_28_944 at 0.01 of its diagonal, its curved sides given the
// intervals their sagitta needs, came out just over the coarse bar (212
// elements where area / H^2 is 520) with needles (shape 0.014) along its
// body; merged as at the default size, 501 elements, 0.198. The time of
// whichever attempt is dropped goes to failed_attempts.
constexpr double kVeryPoorMesh = 0.1;

template <typename Meshed, typename Make, typename IsCoarse, typename Worst, typename BlockSeconds>
void remesh_if_coarse(const PipelineOptions& options, const std::vector<const FaceFlow*>& flows, Meshed& meshed,
                      PipelineOptions& used, StageSeconds& passed, std::string& note, StageSeconds& stages, Make make,
                      IsCoarse coarse, Worst worst, BlockSeconds block_seconds) {
  const bool was_coarse = coarse(meshed);
  const double before = worst(meshed);
  const std::optional<PipelineOptions> retry =
      was_coarse || before < kVeryPoorMesh ? coarse_retry_options(options, flows) : std::nullopt;
  if (!retry) return;
  const auto t = Clock::now();
  try {
    StageSeconds attempt;
    Meshed again = make(*retry, attempt);
    if (!coarse(again) && (was_coarse || worst(again) >= kVeryPoorMesh)) {
      add_stage(stages, "failed_attempts", total_seconds(passed) + block_seconds(meshed));
      meshed = std::move(again);
      used = *retry;
      passed = attempt;
      note = coarse_retry_note(options, *retry,
                               was_coarse ? std::string("the mesh was far coarser than asked")
                                          : "its worst element's shape was " + std::to_string(before));
      return;
    }
  } catch (const SelfCheckError&) {
  }
  add_stage(stages, "failed_attempts", seconds_since(t));
}

// The retry of a poor mesh: when its worst element's Verdict shape is
// under kPoorMesh and a hole is run round by one submapped block, `make`
// meshes again with the settings it was made with (`used`: those asked
// for, or the fallback's or coarse retry's) and such holes framed by the
// splits along their corners' arms, and that result replaces it (its stages in `passed`, the note) if its worst
// element is better. The block's lattice wraps the hole and converges on
// its corners (trimesh_boxsides_179's slots: scaled Jacobian 0.414 at 0.01
// of the diagonal, framed 0.675); but a small slot near the boundary meshes
// well wrapped, and framed gets slanted blocks it does not need
// (trimesh_boxsides_51: 0.843, framed 0.707), so only a poor mesh is
// tried again. The time of whichever attempt is dropped goes to
// failed_attempts.
constexpr double kPoorMesh = 0.5;

template <typename Meshed, typename Make, typename Worst, typename Wrapped, typename BlockSeconds>
void remesh_if_poor(PipelineOptions& used, Meshed& meshed, StageSeconds& passed, std::string& note,
                    StageSeconds& stages, Make make, Worst worst, Wrapped wrapped, BlockSeconds block_seconds) {
  if (used.decomposition.frame_wrapped_holes || used.decomposition.split_concave_corners || !wrapped(meshed)) return;
  const double before = worst(meshed);
  if (before >= kPoorMesh) return;
  PipelineOptions framed = used;
  framed.decomposition.frame_wrapped_holes = true;
  const auto t = Clock::now();
  try {
    StageSeconds attempt;
    Meshed again = make(framed, attempt);
    const double after = worst(again);
    if (after > before) {
      add_stage(stages, "failed_attempts", total_seconds(passed) + block_seconds(meshed));
      meshed = std::move(again);
      passed = attempt;
      used = framed;
      std::ostringstream text;
      if (!note.empty()) text << note << "; ";
      text << "meshed again with the holes one submapped block ran round framed by splits along their corners' "
              "arms, as a fallback: the worst element's shape was "
           << before << ", now " << after;
      note = text.str();
      return;
    }
  } catch (const SelfCheckError&) {
  }
  add_stage(stages, "failed_attempts", seconds_since(t));
}

double worst_shape(const QuadMesh& mesh) {
  return measure_quality(mesh).min_shape();
}

}  // namespace

FaceFlow flow_of_axis(const FaceModel& face, FaceAxis medial) {
  try {
    MeshFlow flow = compute_mesh_flow(medial.face, medial.axis);
    std::vector<Fallback> used;
    if (medial.kinks_as_corners) used.push_back(Fallback::KinksAsCorners);
    return {std::move(medial.face), std::move(medial.axis), std::move(flow), std::move(medial.note), used};
  } catch (const SelfCheckError& first) {
    // A join taken as smooth may still bend enough for a disc tangent on
    // one side to reach over the other: the axis then ends short of it (the
    // branch to a closed B-spline's seam taken for a ripple and pruned) and
    // the flow no longer balances there. With the kinks as corners both are
    // exact, as compute_face_medial_axis does for a failed axis.
    FaceModel kinked = with_kinks_as_corners(face);
    if (kinked.corners.size() != medial.face.corners.size()) {
      const std::size_t kinks = kinked.corners.size() - face.corners.size();
      try {
        MedialAxis axis = compute_medial_axis(kinked);
        MeshFlow flow = compute_mesh_flow(kinked, axis);
        return {std::move(kinked),
                std::move(axis),
                std::move(flow),
                kinks_as_corners_note("the mesh flow", first.check(), kinks),
                {Fallback::KinksAsCorners}};
      } catch (const SelfCheckError&) {
      }
    }
    // The chords may mislead the diagram into losing a whole branch while
    // every point left passes the axis's checks: at the end of a branch into
    // a nearly round lobe, where the distance to the boundary hardly changes
    // along it, the searches from two chords meet at one place and the edge
    // joining the branch to its end is dropped (fuzz bspline_30_42). The
    // flow does not balance where the branch should join; finer chords
    // resolve it.
    try {
      MedialAxis axis = compute_medial_axis(medial.face, kChordRefinement);
      MeshFlow flow = compute_mesh_flow(medial.face, axis);
      std::ostringstream note;
      if (!medial.note.empty()) note << medial.note << "; ";
      note << "the medial axis built again from chords " << kChordRefinement
           << " times finer, as a fallback: on the axis from the default chords the mesh flow did not pass its check ("
           << first.check() << ")";
      std::vector<Fallback> used{Fallback::FinerChords};
      if (medial.kinks_as_corners) used.insert(used.begin(), Fallback::KinksAsCorners);
      return {std::move(medial.face), std::move(axis), std::move(flow), note.str(), used};
    } catch (const SelfCheckError&) {
      throw first;
    }
  }
}

FaceFlow face_flow(const FaceModel& face) {
  return flow_of_axis(face, compute_face_medial_axis(face));
}

DecomposedFace decompose_face(const FaceModel& face, const DecompositionOptions& options) {
  FaceFlow f = face_flow(face);
  Decomposition decomposition = decompose(f.face, f.axis, f.flow, options);
  if (!f.note.empty()) decomposition.notes.insert(decomposition.notes.begin(), f.note);
  std::vector<Fallback> fallbacks = stage_fallbacks(f, decomposition);
  return {std::move(f.face), std::move(f.axis), std::move(decomposition), fallbacks};
}

const char* fallback_name(Fallback fallback) {
  switch (fallback) {
    case Fallback::KinksAsCorners: return "kinks as corners";
    case Fallback::FinerChords: return "finer chords";
    case Fallback::FixedAll: return "every singularity fixed";
    case Fallback::LenientTyping: return "blocks typed by their angles";
    case Fallback::NoOrthogonalJoins: return "no orthogonal joins";
    case Fallback::SubmapCornerRule: return "submapped corners by the corner rule";
    case Fallback::LessMerging: return "less merging";
    case Fallback::ConcaveCornerSplits: return "splits at every concave corner";
    case Fallback::WideUntangling: return "untangling reaching further";
    case Fallback::WinslowGrid: return "Winslow's grid";
    case Fallback::WholeFace: return "the whole face as one block";
    case Fallback::CoarseRetry: return "merging as at the default size";
    case Fallback::FramedHoles: return "holes framed";
  }
  return "?";
}

std::string fallback_names(const std::vector<Fallback>& fallbacks) {
  std::string names;
  for (const Fallback f : fallbacks) names += (names.empty() ? "" : ", ") + std::string(fallback_name(f));
  return names;
}

std::vector<std::string> fallback_list(const std::vector<Fallback>& fallbacks) {
  std::vector<std::string> names;
  for (const Fallback f : fallbacks) names.emplace_back(fallback_name(f));
  return names;
}

MeshedFace mesh_face(const FaceModel& face, const PipelineOptions& options) {
  const auto start = Clock::now();
  MeshedFace result;
  StageSeconds stages;
  Progress* progress = options.meshing.progress;
  start_stage(progress, "medial axis");
  const FaceFlow flow = flow_of_face(face, stages);
  using Meshed = std::pair<Decomposition, BlockMesh>;
  const auto make = [&](const PipelineOptions& o, StageSeconds& attempt) {
    start_stage(progress, "decomposition");
    Decomposition decomposition = decompose_flow(flow, o, attempt);
    BlockMesh blocks = mesh_blocks(flow.face, decomposition, o.meshing);
    return Meshed{std::move(decomposition), std::move(blocks)};
  };
  Meshed meshed;
  StageSeconds passed;             // the stages of the attempt that passed
  PipelineOptions used = options;  // its settings
  std::string note = with_fallbacks(options, {&flow}, stages, [&](const PipelineOptions& o) {
    StageSeconds attempt;
    meshed = make(o, attempt);
    passed = attempt;
    used = o;
  });
  const auto block_seconds = [](const Meshed& m) { return total_seconds(m.second.stage_seconds); };
  const auto worst = [](const Meshed& m) { return worst_shape(m.second.mesh); };
  remesh_if_coarse(
      options, {&flow}, meshed, used, passed, note, stages, make,
      [](const Meshed& m) { return m.second.coarser_than_asked; }, worst, block_seconds);
  remesh_if_poor(
      used, meshed, passed, note, stages, make, worst, [](const Meshed& m) { return !m.first.wrapped_holes.empty(); },
      block_seconds);
  result.fallbacks = face_fallbacks(flow, meshed.first, options, used);
  result.decomposition = std::move(meshed.first);
  result.blocks = std::move(meshed.second);
  if (!flow.note.empty()) result.blocks.notes.push_back(flow.note);
  if (!note.empty()) result.blocks.notes.push_back(note);
  for (const auto& [name, seconds] : passed) add_stage(stages, name, seconds);
  for (const auto& [name, seconds] : result.blocks.stage_seconds) add_stage(stages, name, seconds);
  start_stage(progress, "quality");
  const auto t = Clock::now();
  result.quality = measure_quality(result.blocks.mesh, used.meshing.size);
  stages.emplace_back("quality", seconds_since(t));
  result.quality.stage_seconds = stages;
  result.quality.seconds = seconds_since(start);
  return result;
}

MeshedFaces mesh_faces(const std::vector<FaceModel>& faces, const PipelineOptions& options) {
  if (faces.empty()) throw InputError("no faces to mesh");
  const auto start = Clock::now();
  MeshedFaces result;
  StageSeconds stages;
  Progress* progress = options.meshing.progress;
  const int face_count = static_cast<int>(faces.size());
  start_stage(progress, "medial axis", face_count);
  std::vector<FaceFlow> flows;
  for (const FaceModel& face : faces) {
    flows.push_back(flow_of_face(face, stages));
    step(progress);
  }
  std::vector<FaceModel> taken;  // the faces as their medial axes took them
  for (const FaceFlow& f : flows) taken.push_back(f.face);
  std::vector<const FaceFlow*> flow_list;
  for (const FaceFlow& f : flows) flow_list.push_back(&f);
  using Meshed = std::pair<std::vector<Decomposition>, FaceSetBlockMesh>;
  const auto make = [&](const PipelineOptions& o, StageSeconds& attempt) {
    Meshed m;
    start_stage(progress, "decomposition", face_count);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      m.first.push_back(decompose_flow(flows[f], o, attempt));
      step(progress);
    }
    m.second = mesh_blocks_together(taken, m.first, o.meshing);
    return m;
  };
  Meshed meshed;
  StageSeconds passed;             // the decomposition time of the attempt that passed
  PipelineOptions used = options;  // its settings
  std::string note = with_fallbacks(options, flow_list, stages, [&](const PipelineOptions& o) {
    StageSeconds attempt;
    meshed = make(o, attempt);
    passed = attempt;
    used = o;
  });
  const auto block_seconds = [](const Meshed& m) {
    double seconds = 0.0;
    for (const BlockMesh& f : m.second.faces) seconds += total_seconds(f.stage_seconds);
    return seconds;
  };
  const auto worst_of_faces = [](const Meshed& m) {
    double worst = 1.0;
    for (const BlockMesh& f : m.second.faces) worst = std::min(worst, worst_shape(f.mesh));
    return worst;
  };
  remesh_if_coarse(
      options, flow_list, meshed, used, passed, note, stages, make,
      [](const Meshed& m) {
        return std::any_of(m.second.faces.begin(), m.second.faces.end(),
                           [](const BlockMesh& f) { return f.coarser_than_asked; });
      },
      worst_of_faces, block_seconds);
  remesh_if_poor(
      used, meshed, passed, note, stages, make, worst_of_faces,
      [](const Meshed& m) {
        return std::any_of(m.first.begin(), m.first.end(),
                           [](const Decomposition& d) { return !d.wrapped_holes.empty(); });
      },
      block_seconds);
  std::vector<Decomposition>& decompositions = meshed.first;
  FaceSetBlockMesh& blocks = meshed.second;
  for (const auto& [name, seconds] : passed) add_stage(stages, name, seconds);
  for (std::size_t f = 0; f < faces.size(); ++f)
    if (!flows[f].note.empty()) blocks.faces[f].notes.push_back(flows[f].note);
  if (!note.empty())
    for (BlockMesh& face : blocks.faces) face.notes.push_back(note);
  std::vector<const QuadMesh*> meshes;
  std::vector<QualityReport> reports;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    MeshedFace face;
    face.fallbacks = face_fallbacks(flows[f], decompositions[f], options, used);
    for (const Fallback fallback : face.fallbacks)
      if (std::find(result.fallbacks.begin(), result.fallbacks.end(), fallback) == result.fallbacks.end())
        result.fallbacks.push_back(fallback);
    face.decomposition = std::move(decompositions[f]);
    face.blocks = std::move(blocks.faces[f]);
    face.quality = measure_quality(face.blocks.mesh, used.meshing.size);
    face.quality.stage_seconds = face.blocks.stage_seconds;
    for (const auto& [name, seconds] : face.blocks.stage_seconds) add_stage(stages, name, seconds);
    result.faces.push_back(std::move(face));
  }
  for (const MeshedFace& face : result.faces) {
    meshes.push_back(&face.blocks.mesh);
    reports.push_back(face.quality);
  }
  result.shared = std::move(blocks.shared);
  start_stage(progress, "joining faces");
  auto t = Clock::now();
  result.mesh = merge_face_meshes(taken, meshes, result.shared, blocks.tolerance);
  stages.emplace_back("merge", seconds_since(t));
  start_stage(progress, "quality");
  t = Clock::now();
  result.quality = combine_quality(reports, meshes, result.mesh);
  stages.emplace_back("quality", seconds_since(t));
  result.quality.stage_seconds = stages;
  result.quality.seconds = seconds_since(start);
  return result;
}

}  // namespace mm

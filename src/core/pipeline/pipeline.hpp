#pragma once
// The whole pipeline for one face, stage after stage, timed: medial axis,
// mesh flow, decomposition, block meshing and the quality report. The CLI,
// the Python module and the benchmarks all mesh through here.
#include "decomposition/decomposition.hpp"
#include "meshing/merge_faces.hpp"
#include "meshing/mesh_blocks.hpp"
#include "quality/quality.hpp"
#include "singularity/mesh_flow.hpp"

namespace mm {

struct PipelineOptions {
  MeshingOptions meshing;  // its progress is told every stage, and stops the run when cancelled
  // As decompose takes them: merging by a factor 0.75 of the medial radius
  // unless told otherwise; the fallbacks change the rest.
  DecompositionOptions decomposition;
};

// What made a result when the way asked for did not pass its checks (or,
// for the last two, gave a far too coarse or a poor mesh): each a fallback
// a stage or the pipeline took, in the order taken. A result carries the
// list, and says so wherever a user looks (CLI text, JSON, FreeCAD Status).
enum class Fallback {
  KinksAsCorners,       // the axis or flow with joins up to 0.5 degrees off tangent as corners
  FinerChords,          // the axis built again from chords 4 times finer
  FixedAll,             // the decomposition with every singularity that can be fixed fixed
  LenientTyping,        // the decomposition's blocks that do not close up typed by their angles
  NoOrthogonalJoins,    // splits not joined at right angles
  SubmapCornerRule,     // submapped blocks' corners by the corner rule alone
  LessMerging,          // singularities merged less (or not at all) than asked
  ConcaveCornerSplits,  // splits along the arms of every concave corner
  WideUntangling,       // untangling reaching further
  WinslowGrid,          // widely folded submapped blocks placed by Winslow's grid
  WholeFace,            // the whole face as one polygon block, no medial axis
  CoarseRetry,          // a mesh far coarser than asked made again, merging as at the default size
  FramedHoles,          // a poor mesh made again with holes a block ran round framed
};
// A few words for users ("less merging", "kinks as corners", ...).
const char* fallback_name(Fallback fallback);
// The names joined by ", ": the text after "fallback: " in the CLI and Status.
std::string fallback_names(const std::vector<Fallback>& fallbacks);
// The names one by one, for the JSON reports' "fallbacks".
std::vector<std::string> fallback_list(const std::vector<Fallback>& fallbacks);

struct MeshedFace {
  Decomposition decomposition;
  BlockMesh blocks;
  QualityReport quality;            // with the seconds of every stage
  std::vector<Fallback> fallbacks;  // empty: made as asked
};

// Throws InputError for bad options, SelfCheckError when a stage's result
// fails its check with the options asked for and with each fallback tried
// after them: submapped blocks' corners by the corner rule alone, less
// merging (factor 0.5, 0.25, none), splits at every concave corner, then
// the options asked for with untangling reaching further
// (MeshingOptions::wide_untangling), then with widely folded submapped
// blocks placed by Winslow's grid too (MeshingOptions::regrid_wide_folds),
// last with the whole face as one polygon block (DecompositionOptions::
// whole_face). A mesh far coarser than asked
// (BlockMesh::coarser_than_asked), or whose worst element's shape is under
// 0.1, is made again with the singularities merged within a twentieth of
// the face's diagonal, as at the default size, and kept if it is not coarse
// and (for the poor one) lifts its worst element over 0.1. A mesh whose
// worst element is under 0.5 with a hole one submapped block runs round
// (Decomposition::wrapped_holes) is made again with such holes framed, and
// the better kept. MeshedFace::fallbacks lists what was used, and a note in
// blocks.notes says why.
// With options.meshing.progress, each stage and block is told to it as it
// starts, and Cancelled is thrown between them once it is cancelled.
MeshedFace mesh_face(const FaceModel& face, const PipelineOptions& options);

// The face as the medial axis took it, its axis and its mesh flow, as
// `medialmesh singularities` and the Python analyse() give them. The note
// says when a fallback was needed: the axis built with the face's kinks
// (joins up to 0.5 degrees off tangent) as corners, because the axis
// (compute_face_medial_axis) or else the flow failed its self-check, or,
// when the flow fails with the kinks too or there are none, the axis built
// again from chords 4 times finer. Throws SelfCheckError when all fail.
struct FaceFlow {
  FaceModel face;
  MedialAxis axis;
  MeshFlow flow;
  std::string note;                 // empty, or what was done and why
  std::vector<Fallback> fallbacks;  // KinksAsCorners, FinerChords, or none
};
FaceFlow face_flow(const FaceModel& face);
// The same from the face's axis as compute_face_medial_axis(face) gave it.
FaceFlow flow_of_axis(const FaceModel& face, FaceAxis medial);

// The decomposition alone, as `medialmesh decompose` and the Python
// decompose() give it: the face, axis and note of face_flow, and the
// blocks, that note first among their notes. No fallbacks: a failed check throws.
struct DecomposedFace {
  FaceModel face;
  MedialAxis axis;
  Decomposition decomposition;
  std::vector<Fallback> fallbacks;  // the axis's, the flow's and the decomposition's
};
DecomposedFace decompose_face(const FaceModel& face, const DecompositionOptions& options);

// Several faces meshed together: the pieces of boundary they share in 3-D
// (coplanar or not, a vertex of one inside an edge of another included) get
// the same nodes, and the meshes are joined into one.
struct MeshedFaces {
  std::vector<MeshedFace> faces;    // each face's own result, its quality in its plane
  std::vector<SharedPiece> shared;  // the pieces shared, with their nodes in both faces
  MergedMesh mesh;                  // all faces in 3-D, shared nodes once
  QualityReport quality;            // of the merged mesh (combine_quality), with the stages' seconds
  std::vector<Fallback> fallbacks;  // every face's, each once
};

// Throws as mesh_face, and falls back as it does (the coarse retry merging
// within a twentieth of the smallest face's diagonal; the retry of a poor
// mesh when any face's is poor and has a wrapped hole); SelfCheckError naming
// the faces when the merged mesh fails its checks (merge_face_meshes),
// InputError for no faces.
MeshedFaces mesh_faces(const std::vector<FaceModel>& faces, const PipelineOptions& options);

}  // namespace mm

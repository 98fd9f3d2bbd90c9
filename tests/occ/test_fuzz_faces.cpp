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
// The decomposition's faces stopped in its own area check, each from blocks that overlapped:
// bspline_1_777, a ring whose hole is touched only by an axis edge from a
// fixed junction back to itself (the walk round the hole was dropped as a
// range of no length, so the hole was counted as block); bspline_1_2, a
// closed B-spline whose axis ends at curvature contacts where the touches of
// the last points lie beyond the end's own (a range ran back behind its
// start and the next block covered the same boundary again); bspline_1_1262,
// a singularity fixed where the axis's touches jump along one segment, whose
// split went out to one boundary point and back (a block of no area that no
// typing submaps). plate_1_1391: a notched plate a thousandth of a unit
// across, a split end on a slot's round end that both of OCC's classifiers
// call outside the face although it is on its edge. bspline_1_1272: three
// k = -1 round two junctions a hair apart, where the flow's corner types do
// not close up in every attempt, with or without every singularity fixed;
// the last attempt, typing blocks by their angles, now fixes every
// singularity too when a floating one's block does not close up.
// filleted_4_1700: a switch a thousandth of a step from a fixed junction,
// cut there on its own (a sliver block whose outline crossed itself; now
// the junction's cut takes it). bspline_2_792: an axis missing the branch
// into one lobe, whose k = -1 went into a triangle on the far side of the
// face while the areas still added up (then a self-check failure, and the
// fix-everything fallback decomposed it; since the branch towards its
// reflex corner ends at the corner's contact between its feet, not at the
// peak beyond the corner it folded back to, it decomposes without the
// fallback). filleted_1_915, _950, _1820,
// _1980 and filleted_3_275: filleted stars with holes whose axis points
// wobble back past a junction, so the first step of an edge pointed the
// wrong way and the walk took the edges round the junction out of order
// (blocks that overlapped or corners that did not close up).
// filleted_1_490, _910, _990 and _1490: an edge that overshoots its
// junction along the next edge, turns back and passes the junction again;
// it is taken to leave the junction after the turn, and its end touches
// continue from there (the overshoot's points have their sides swapped).
// filleted_1_880 and filleted_1_1360: a singularity fixed nearer the next
// axis point than the one before it, whose split took the touches of the
// one before: a block outline that crossed itself (now the nearer point's).
// bspline_1_1212 and bspline_1_1442: a k = -1 fixed beside an axis point
// that carries one place as both its touches, whose split went out to one
// boundary point and back (a block of no area that no typing submaps).
// filleted_1_1205: a sharp triangle whose tip the flow gives no element, a
// block no typing submaps; now a triangle round a k = -1 of its own.
// bspline_3_387: a singularity fixed near the end of a branch into a
// curvature contact, where the searches for its split's two touches passed
// each other (the block beyond was turned inside out).
// bspline_1_717: a k = -1 merged with a +1 and a -1 a hair apart on one
// edge (where a pruned ripple branch left it), each cut on its own: two
// splits at one place with a block of no area, turned inside out, between
// them (now one split takes both). aerofoil_1_116: an aerofoil slot whose
// trailing edge is closed by an edge 5e-7 long with a concave corner's
// split at each end; OCC's splitter merged the two ends and left that edge
// as a degenerate wire of its own in a block face (now dropped).
// aerofoil_3_201 and aerofoil_3_288: aerofoils whose meshes were right but
// whose area checks (the mesher's and the tests') bounded what the chords
// cut off by chord x midpoint sagitta, 8x short across a leading edge; now
// the exact area between each chord and its curve. plate_3_686 and
// plate_5_1206: submapped blocks with two reflex corners nearly in line,
// whose counts made the logical outline cross itself (sides facing only
// past the corners, now seen from rays at the reflex corners).
// aerofoil_3_213: split ends 3e-8 apart on the boundary, a collapsed side
// until smoothing slid boundary nodes (within their intervals' turning).
// aerofoil_1_4, aerofoil_1_85, bspline_1_977 and bspline_1_1252: blocks whose
// corners at a split's bend add up to two elements (a k = -2 jump of a pruned
// branch fixed at one point; fix splits of a cluster of switches), an
// interior node in two elements, one of them flat (now joined into one).
// bspline_1_1257: a ring cut once, whose outer loop's two ranges overlapped
// round the closed axis edge (block outlines 0.000517 apart). aerofoil_1_68: a
// tiny aerofoil (area 5e-5) whose blunt trailing edge is shorter than the
// tolerance: the tests' area check took the aerofoil's whole curve for the
// trailing-edge side (a right mesh called wrong, and 40 s in the area
// integral of a closed curve from its own end).
// bspline_1_147, _1157, _112, _1977 and elliptic_1_1724: one of each medial
// axis defect of BranchesRunIntoTheirOwnCurvatureContacts below.
// strip_2_268 (a thin strip's end) and aerofoil_2_226 (a slot): smoothing
// moved an interior node onto its neighbour, a collapsed side between two
// corners of good scaled Jacobian (now a side keeps a hundredth of the side
// facing it). bspline_2_152, filleted_2_975 and bspline_2_1477: see
// JunctionsTouchThreePlacesFlaresReachTheirCornersEdgesNeverTurnBack. cascade_2_381 and
// cascade_2_387: passages whose first placement folds widely round the
// blade's round nose; untangling with boundary nodes free slid two nodes
// off the nose, so one chord cut it off (elements outside the face, none
// inverted: the mesh's own checks passed), or left an element inverted by
// 6e-6 (now boundary intervals turn by at most 135 degrees there too).
// aerofoil_3_217: a high-lift arrangement whose fold in a slot stayed
// inverted once smoothing kept every side above a hundredth of the side
// facing it; what untangling leaves folded is untangled again without it.
// aerofoil_3_361: a slot whose fold needs boundary nodes to slide further
// than 90 degrees an interval (now 135 in the free passes).
// bspline_5_1347: a junction with three candidate places but no junction
// among them, which the held-feet search of bspline_2_152 solved into a
// junction that turned a block inside out (that search is now only for
// junctions left with two places).
#include <gtest/gtest.h>

#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <algorithm>
#include <chrono>
#include <map>
#include <optional>

#include "decomposition_checks.hpp"
#include "geometry/polygon.hpp"
#include "medial/medial_axis.hpp"
#include "medial/nearest_boundary.hpp"
#include "medial_checks.hpp"
#include "mesh_checks.hpp"
#include "occ/occ_face.hpp"
#include "occ/occ_reader.hpp"
#include "occ/occ_split.hpp"
#include "pipeline/pipeline.hpp"
#include "singularity/mesh_flow.hpp"
#include "test_support.hpp"

namespace mm {
namespace {

// The face's mesh at 0.05 of its diagonal, checked: valid, none inverted,
// the worst element above 0. None (and a test failure) if it stops.
std::optional<MeshedFace> valid_mesh_of(const std::string& name, double size_factor = 0.05) {
  const FaceModel face = test::data_face(std::string("fuzz/") + name);
  PipelineOptions options;
  options.meshing.size = size_factor * face.size;
  try {
    MeshedFace m = mesh_face(face, options);
    const std::vector<std::string> problems = test::mesh_validity_problems(face, m.blocks.mesh);
    EXPECT_TRUE(problems.empty()) << name << ": " << ::testing::PrintToString(problems);
    EXPECT_GT(m.quality.min_scaled_jacobian, 0.0) << name;
    EXPECT_EQ(m.quality.inverted, 0) << name;
    return m;
  } catch (const SelfCheckError& e) {
    ADD_FAILURE() << e.what();
    return std::nullopt;
  }
}

// The face's decomposition, with the tests' decomposition checks.
Decomposition checked_decomposition(const FaceModel& face) {
  const MedialAxis axis = compute_medial_axis(face);
  const MeshFlow flow = compute_mesh_flow(face, axis);
  Decomposition d = decompose(face, axis, flow, {});
  const auto problems = test::decomposition_problems(face, flow, d);
  EXPECT_TRUE(problems.empty()) << face.name << ": " << ::testing::PrintToString(problems);
  return d;
}

double area_of(const TopoDS_Face& face) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props, 1e-12);
  return props.Mass();
}

// The face's medial axis if it and the mesh flow pass their own checks and
// the tests' medial checks; a test failure (and nothing) if not.
std::optional<MedialAxis> axis_with_its_flow(const FaceModel& face) {
  try {
    MedialAxis axis = compute_medial_axis(face);
    compute_mesh_flow(face, axis);
    EXPECT_TRUE(test::medial_axis_is_valid(face, axis, 1e-6)) << face.name;
    return axis;
  } catch (const SelfCheckError& e) {
    ADD_FAILURE() << e.what();
    return std::nullopt;
  }
}

// Faces that once stopped or failed a check somewhere in the pipeline.
// filleted_7_740, filleted_8_655 and plate_8_891 stopped with a submapped
// block whose lattice outline met itself for the counts given (sides the
// decomposition did not name as facing, or the arms of an S crossing): the
// counts are now solved again with those sides kept apart. bspline_10_182
// and bspline_10_1787 stopped in the decomposition (a block's corners not
// closing up, pieces of an outline missing each other) on the medial axis
// defects of the two tests below that name them. bspline_5_587: a k = -1
// switch so near a branch's curvature-contact end that its split's two
// radii ended 2e-6 apart on a face 1 500 across, a block of no area between
// them (now the switch is the contact's, fixed on the boundary there).
// plate_5_1451: a singularity fixed on an edge's last segment before a
// junction touching two slots and the outline took its radius to the slot
// the junction touches, not the one the edge runs along (a block outline
// missed itself by 0.15); filleted_14_1695 and filleted_9_1070 stopped on
// the medial defect of the test below that names them. aerofoil_12_63 and
// aerofoil_12_390 (fuzz seed 12): high-lift faces where a slat's cusped
// trailing edge nearly touches the main element's nose, whose blocks there
// folded with any merging; they mesh split at every concave corner, the
// pipeline's last fallback.
TEST(FuzzFaces, EachGetsAValidMesh) {
  for (const char* name :
       {"strip_7_63",       "strip_7_313",     "bspline_8_117",  "elliptic_9_99",   "bspline_1_37",   "elliptic_2_1614",
        "bspline_2_1947",   "bspline_5_357",   "bspline_1_777",  "bspline_1_2",     "bspline_1_1262", "plate_1_1391",
        "bspline_1_1272",   "filleted_4_1700", "bspline_2_792",  "aerofoil_3_201",  "aerofoil_3_288", "plate_3_686",
        "plate_5_1206",     "aerofoil_3_213",  "aerofoil_1_4",   "aerofoil_1_85",   "bspline_1_977",  "bspline_1_1252",
        "bspline_1_1257",   "aerofoil_1_68",   "aerofoil_1_116", "bspline_1_147",   "bspline_1_1157", "bspline_1_112",
        "bspline_1_1977",   "elliptic_1_1724", "strip_2_268",    "aerofoil_2_226",  "bspline_2_152",  "filleted_2_975",
        "bspline_2_1477",   "cascade_2_381",   "cascade_2_387",  "bspline_3_422",   "aerofoil_3_217", "filleted_7_740",
        "filleted_8_655",   "plate_8_891",     "bspline_10_182", "bspline_10_1787", "bspline_5_587",  "plate_5_1451",
        "filleted_14_1695", "filleted_9_1070", "aerofoil_12_63", "aerofoil_12_390"}) {
    valid_mesh_of(name);
  }
}

// The area between a closed curve and ref, integrated from ref at its own
// end round to it (a tiny aerofoil's curve, its ends 6e-7 apart across the
// trailing edge): right, and quick, however near the ends lie to ref.
// bspline_23_1422 (fuzz seed 23): an oval, one closed B-spline whose seam
// bends by 0.075 degrees (taken as smooth) with a jump in curvature. The
// disc ending the branch into the seam reaches over the seam by 1.5e-8, so
// the branch was pruned as a ripple and the flow met a k = -2 where the
// touches jump past it: a flow switch of k = -2, a self-check failure. The
// flow's fallback builds axis and flow again with the kink as a corner: four
// k = -1, and the mesh of a round face.
TEST(FuzzFaces, AFlowThatFailsAtAKinkTakenAsSmoothIsBuiltWithTheKinkAsACorner) {
  const FaceModel face = test::data_face("fuzz/bspline_23_1422");
  const FaceFlow analysed = face_flow(face);
  EXPECT_EQ(analysed.flow.sum_k(), predicted_sum_k(face));
  ASSERT_EQ(analysed.flow.singularities.size(), 4u);
  for (const Singularity& s : analysed.flow.singularities) EXPECT_EQ(s.k, -1);
  const std::optional<MeshedFace> m = valid_mesh_of("bspline_23_1422");
  ASSERT_TRUE(m);
  EXPECT_GT(m->quality.min_scaled_jacobian, 0.5);
  ASSERT_EQ(m->quality.irregular_interior.size(), 4u);
  for (const IrregularNode& n : m->quality.irregular_interior) EXPECT_EQ(n.elements, 3);
}

// bspline_23_682 (fuzz seed 23): a closed B-spline outline with a round
// hole, its seam a reflex corner of 186 degrees. A stub of the chords'
// diagram between two chords of the lobe below the corner found the lobe's
// curvature peak too, and was kept as a branch beside the real one: a
// junction where there is none (its second place 4e-4 beyond its radius, a
// medial axis self-check failure) and two ends on one peak. One branch ends
// at a peak, the one whose end is nearest its centre: two junctions and two
// curvature contacts, a ring's mesh with no irregular interior node. But a
// ripple's end claims no peak: on bspline_26_602 and bspline_26_197 (fuzz
// seed 26, closed B-spline blobs) a ripple's stub nearer a lobe's peak took
// the lobe's whole branch with it before it was pruned itself (a flow
// switch of k = -2 and -3 where the branch had been).
TEST(FuzzFaces, OneBranchEndsAtEachCurvaturePeak) {
  for (const char* name : {"bspline_26_602", "bspline_26_197"}) {
    const FaceModel blob = test::data_face(std::string("fuzz/") + name);
    EXPECT_TRUE(axis_with_its_flow(blob)) << name;
    valid_mesh_of(name);
  }
  const FaceModel face = test::data_face("fuzz/bspline_23_682");
  const std::optional<MedialAxis> axis = axis_with_its_flow(face);
  ASSERT_TRUE(axis);
  std::vector<Vec2> peaks;
  for (const MedialVertex& v : axis->vertices) {
    if (v.kind != MedialVertexKind::CurvatureContact) continue;
    for (Vec2 p : peaks) EXPECT_GT(distance(p, v.p), 1e-6 * face.size) << "two ends at one peak";
    peaks.push_back(v.p);
  }
  EXPECT_EQ(peaks.size(), 2u);
  const std::optional<MeshedFace> m = valid_mesh_of("bspline_23_682");
  ASSERT_TRUE(m);
  EXPECT_GT(m->quality.min_scaled_jacobian, 0.5);
  EXPECT_TRUE(m->quality.irregular_interior.empty());
}

// bspline_29_1052 (fuzz seed 29): a closed B-spline blob with a 176-degree
// corner at its seam. The default chords gave the branch from the corner a
// spurious stub to a ripple, and the junction there touched its third place
// 1.2e-4 off its radius while no boundary lay inside any disc: the axis was
// not built again from finer chords (only boundary inside a disc or a wrong
// topology asked for that) and its radius check failed. The finer chords'
// axis: the corner's flare, four curvature contacts, three junctions.
TEST(FuzzFaces, ADiscMissingItsTouchingPlaceIsBuiltAgainFromFinerChords) {
  const FaceModel face = test::data_face("fuzz/bspline_29_1052");
  const std::optional<MedialAxis> axis = axis_with_its_flow(face);
  ASSERT_TRUE(axis);
  std::map<MedialVertexKind, int> kinds;
  for (const MedialVertex& v : axis->vertices) ++kinds[v.kind];
  EXPECT_EQ(kinds[MedialVertexKind::Flare], 1);
  EXPECT_EQ(kinds[MedialVertexKind::CurvatureContact], 4);
  EXPECT_EQ(kinds[MedialVertexKind::Junction], 3);
  EXPECT_EQ(axis->edges.size(), 7u);
  const std::optional<MeshedFace> m = valid_mesh_of("bspline_29_1052");
  ASSERT_TRUE(m);
  EXPECT_GT(m->quality.min_scaled_jacobian, 0.2);
}

// bspline_30_42 (fuzz seed 30): a smooth closed B-spline blob with three
// lobes. On the default chords the lowest lobe's end is nearly round about
// the branch's end, the searches from two chords there met at one place, the
// edge joining the branch to its end was dropped, and the branch was pruned
// as a stub: an axis of two ends whose every point passes the checks, and a
// flow switch of k = -2 where the branch should join. The flow's fallback
// builds the axis from finer chords: three curvature contacts round one
// junction, and four k = -1.
TEST(FuzzFaces, AFlowThatFailsOnAnAxisMissingABranchIsBuiltAgainFromFinerChords) {
  const FaceModel face = test::data_face("fuzz/bspline_30_42");
  const FaceFlow analysed = face_flow(face);
  EXPECT_NE(analysed.note.find("chords 4 times finer"), std::string::npos) << analysed.note;
  EXPECT_EQ(analysed.fallbacks, std::vector<Fallback>{Fallback::FinerChords});
  EXPECT_TRUE(test::medial_axis_is_valid(analysed.face, analysed.axis, 1e-6));
  std::map<MedialVertexKind, int> kinds;
  for (const MedialVertex& v : analysed.axis.vertices) ++kinds[v.kind];
  EXPECT_EQ(kinds[MedialVertexKind::CurvatureContact], 3);
  EXPECT_EQ(kinds[MedialVertexKind::Junction], 1);
  EXPECT_EQ(analysed.flow.sum_k(), predicted_sum_k(face));
  const std::optional<MeshedFace> m = valid_mesh_of("bspline_30_42");
  ASSERT_TRUE(m);
  EXPECT_GT(m->quality.min_scaled_jacobian, 0.3);
}

// elliptic_28_1269 (fuzz seed 28 at --size 0.01): a lens 0.007 across with
// 9-degree tips, meshed with elements hugging its arc within 5e-7. The
// checker's inside test ran on polylines within 1e-4 of the face's size of
// the curves, so centres between a polyline chord and the arc were called
// outside by more than the mesh's own (finer) sagitta: a false alarm that
// the probe's exact side test near curves now settles.
TEST(FuzzFaces, ElementsHuggingACurveInAFineMeshAreInside) {
  const std::optional<MeshedFace> m = valid_mesh_of("elliptic_28_1269", 0.01);
  ASSERT_TRUE(m);
  EXPECT_GT(m->quality.quads, 1000);
}

// elliptic_28_944 (fuzz seed 28 at --size 0.01): a thin lens with an
// 11.6-degree tip. Its two k = -1 near the wide end, left apart, make its
// long body one submapped block typed as a rectangle, each long side
// opposite a short one: 14 elements at any size from 0.03 of the diagonal
// down, where area / H^2 is 1 500 at 0.01. The block mesh says it is far
// coarser than asked; the pipeline then merges the singularities as at the
// default size (within a twentieth of the diagonal): one k = -2 at the wide
// end, the body along the lens, and a note that says so.
TEST(FuzzFaces, AMeshFarCoarserThanAskedIsMadeAgainWithTheDefaultSizesMerging) {
  const FaceModel face = test::data_face("fuzz/elliptic_28_944");
  const double size = 0.01 * face.size;
  MeshingOptions meshing;
  meshing.size = size;
  const BlockMesh first = mesh_blocks(face, test::decompose_face(face, 0.75), meshing);
  EXPECT_TRUE(first.coarser_than_asked);
  EXPECT_TRUE(std::any_of(first.notes.begin(), first.notes.end(), [](const std::string& note) {
    return note.find("coarser than asked") != std::string::npos;
  }));
  const std::optional<MeshedFace> m = valid_mesh_of("elliptic_28_944", 0.01);
  ASSERT_TRUE(m);
  EXPECT_FALSE(m->blocks.coarser_than_asked);
  EXPECT_EQ(test::element_count_problem(face, m->blocks.mesh, size), "");
  EXPECT_TRUE(std::any_of(m->blocks.notes.begin(), m->blocks.notes.end(), [](const std::string& note) {
    return note.find("meshed with merging within") != std::string::npos &&
           note.find("as a fallback: with merging factor 0.75 the mesh was far coarser than asked") !=
               std::string::npos;
  }));
  PipelineOptions options;  // several faces meshed together retry the same way
  options.meshing.size = size;
  const MeshedFaces together = mesh_faces({face}, options);
  EXPECT_FALSE(together.faces.front().blocks.coarser_than_asked);
  EXPECT_EQ(together.faces.front().quality.quads, m->quality.quads);
  const std::optional<MeshedFace> as_asked = valid_mesh_of("bspline_29_1052");  // no such note
  ASSERT_TRUE(as_asked);
  for (const std::string& note : as_asked->blocks.notes) EXPECT_EQ(note.find("coarser"), std::string::npos) << note;
}

// elliptic_33_274 (fuzz seed 33): a rectangle capped by a half ellipse, its
// short sides meeting the ellipse tangentially. The self-check's nearest
// boundary point skipped the chord from an edge's last sample to the next
// edge's first, where a short side's foot lay 1.1e-3 nearer than the
// ellipse's local minimum the search from the join settled on: an axis
// point whose disc held boundary passed its own check (a broken invariant).
// Both chords at a sample are now asked, along the loop.
TEST(FuzzFaces, TheNearestBoundaryPointOnAnEdgesLastStretchIsFound) {
  const FaceModel face = test::data_face("fuzz/elliptic_33_274");
  const BoundaryIndex index(face);
  const NearestBoundary boundary(index);
  const Vec2 p{609.502725, 922.986008};
  const BoundaryPlace nearest = boundary.nearest(p);
  EXPECT_EQ(nearest.edge, 2);
  EXPECT_NEAR(distance(nearest.point, p), 97.254505, 1e-6);
  EXPECT_TRUE(axis_with_its_flow(face));
  const std::optional<MeshedFace> m = valid_mesh_of("elliptic_33_274");
  ASSERT_TRUE(m);
  EXPECT_GT(m->quality.min_scaled_jacobian, 0.8);
}

// filleted_33_390 (fuzz seed 33): a filleted polygon with two holes, one of
// its fillets 7.6e-7 long between two lines. Along a block's outline the
// touches stepped back over that fillet (a whole edge in loop positions)
// and the touched arc then counted as no length, its ends a sliver apart:
// the run came out a whole edge short, the block's boundary stopped before
// the fillet while its split ended 0.061 beyond it, and the decomposition
// failed its check with every fallback. Ends a sliver apart now step the
// short way round.
TEST(FuzzFaces, ARangeOverAFilletShorterThanASliverKeepsItsLength) {
  const FaceModel face = test::data_face("fuzz/filleted_33_390");
  const std::optional<MedialAxis> axis = axis_with_its_flow(face);
  ASSERT_TRUE(axis);
  const MeshFlow flow = compute_mesh_flow(face, *axis);
  const Decomposition d = decompose(face, *axis, flow, {});
  EXPECT_TRUE(test::decomposition_problems(face, flow, d).empty());
  EXPECT_FALSE(d.fallback);
  const std::optional<MeshedFace> m = valid_mesh_of("filleted_33_390");
  ASSERT_TRUE(m);
  EXPECT_GT(m->quality.min_scaled_jacobian, 0.2);
}

TEST(FuzzFaces, AreaIntegralOfAClosedCurveFromItsEnd) {
  const FaceModel face = test::data_face("fuzz/aerofoil_1_68");
  const auto start = std::chrono::steady_clock::now();
  for (const Loop& loop : face.loops) {
    for (const BoundaryEdge& e : loop.edges) {
      // From ref = its start and from its middle (well away from the ends)
      // the integrals differ by the triangle of ref's step and the chord.
      const Vec2 from = edge_point(e, e.t_start).p, to = edge_point(e, e.t_end).p;
      const Vec2 middle = edge_point(e, 0.5 * (e.t_start + e.t_end)).p;
      const double from_middle = edge_area_integral(e, e.t_start, e.t_end, middle);
      const double length = edge_length(e);
      EXPECT_NEAR(edge_area_integral(e, e.t_start, e.t_end, e.start),
                  from_middle - 0.5 * cross(e.start - middle, to - from),
                  1e-9 * (std::abs(from_middle) + length * length));
    }
  }
  // Every knot span to the depth cap took 40 s; one pass takes milliseconds.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

// Closed wavy B-splines whose medial axis failed its own check: an edge
// point's feet, found by nearest-point searches from its Voronoi sites'
// chords, settled on a bump next to the one the disc reaches into (or both
// on one bump, bspline_1_117), so the boundary came nearer than the radius.
// bspline_1_1257 also passed its self-check wrongly once that was fixed: the
// check's nearest place missed a hole's edge a hair farther than the outline
// from every one of the six nearest samples. bspline_6_1277 (one closed
// B-spline with a reflex corner at its seam) passed its self-check with an
// edge point 2e-6 nearer the boundary than its radius: the search from that
// corner tried the edge's start twice (the edge before the corner is the
// edge after it) and never its end, where the nearer foot was. Each axis is
// now exact, checked against an independent fine probe of the boundary.
TEST(FuzzFaces, MedialPointsTouchTheirGlobalNearestPlaces) {
  for (const char* name : {"bspline_1_117", "bspline_1_717", "bspline_1_1257", "bspline_1_1762", "bspline_1_1832",
                           "bspline_3_17", "bspline_3_767", "bspline_6_1277"}) {
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
    MedialAxis axis;
    try {
      axis = compute_medial_axis(face);
    } catch (const SelfCheckError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    EXPECT_TRUE(test::medial_axis_is_valid(face, axis, 1e-6)) << name;
  }
}

// Faces whose mesh flow found the medial axis folding back (its touches
// running backwards) or a flow switch of k = -2, or whose axis failed its
// disc check (fuzz seed 1). On 22 closed B-spline outlines with wavy caps and
// on bspline_1_1802 a branch's curvature-contact end was snapped to the peak
// next to the one the branch runs into (both discs empty, both centres
// about as near the discretised end); on bspline_1_112, _497, _1157 and
// _1797 the peak lay just past the nearly flat reflex corner at the seam of
// the closed B-spline, where the search stopped. bspline_1_1977: a point
// beside a pruned ripple branch repaired onto the ripple's own bisector.
// elliptic_1_1724: a junction solved with two of its three places slid into
// one (an ordinary point of the flare's edge). bspline_3_1347 (a junction
// touching a reflex corner along both its edges) and bspline_5_1012 (an end
// node far from its end, the shorter way between its feet the wrong side)
// went wrong with a first fix; bspline_3_982 (two touches of an end node
// that are one place, beside a reflex corner) with a second. Fuzz seed 10:
// bspline_10_32 and bspline_10_202, a foot of a curvature-contact end taken
// to the far end of the closed curve by the nearest-point search (the disc
// off its radius); bspline_10_1002 and 1567 (the axis folding back) passed
// once that search stayed local; bspline_10_172, a lobe with two peaks whose
// end node's feet had met between them, the end put on the peak outside the
// feet of the branch's last points. Each axis must
// pass the medial checks, every edge must run on into its curvature-contact
// ends (its last step turning by less than a right angle) and the mesh flow
// must pass its own checks.
// Takes about 0.3 s.
TEST(FuzzFaces, BranchesRunIntoTheirOwnCurvatureContacts) {
  for (const char* name :
       {"bspline_1_147",  "bspline_1_212",  "bspline_1_267",   "bspline_1_522",   "bspline_1_702",  "bspline_1_802",
        "bspline_1_1002", "bspline_1_1012", "bspline_1_1157",  "bspline_1_1167",  "bspline_1_1197", "bspline_1_1302",
        "bspline_1_1347", "bspline_1_1472", "bspline_1_1477",  "bspline_1_1507",  "bspline_1_1572", "bspline_1_1622",
        "bspline_1_1887", "bspline_1_1917", "bspline_1_1927",  "bspline_1_1977",  "bspline_1_1802", "bspline_1_112",
        "bspline_1_497",  "bspline_1_1797", "elliptic_1_1724", "bspline_3_1347",  "bspline_5_1012", "bspline_3_982",
        "bspline_10_32",  "bspline_10_202", "bspline_10_172",  "bspline_10_1002", "bspline_10_1567"}) {
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
    const std::optional<MedialAxis> checked = axis_with_its_flow(face);
    if (!checked) continue;
    const MedialAxis& axis = *checked;
    for (const MedialEdge& e : axis.edges) {
      const std::size_t n = e.points.size();
      if (n < 3) continue;
      for (const bool at_end : {false, true}) {
        const int v = at_end ? e.to : e.from;
        if (v < 0 || axis.vertices[v].kind != MedialVertexKind::CurvatureContact) continue;
        const Vec2 a = e.points[at_end ? n - 3 : 2].p, b = e.points[at_end ? n - 2 : 1].p;
        const Vec2 end = e.points[at_end ? n - 1 : 0].p;
        // Nearer than a thousandth of the radius, the axis does not resolve
        // a direction (bspline_1_1802 has a point 1.6e-5 from its end).
        if (distance(b, end) < 1e-3 * axis.vertices[v].r) continue;
        EXPECT_GT(dot(b - a, end - b), 0.0)
            << name << ": the edge turns back into its end at (" << end.x << ", " << end.y << ")";
      }
    }
  }
}

// Fuzz seed 2. bspline_2_152: a junction beside a curvature contact, where
// from the discretised junction the distance to the side curving nearly
// round it has no local minimum near the exact foot, so two of its three
// places slid into one and the junction kept two (its disc 4e-6 off the
// boundary). filleted_2_975: an edge whose sites' searches slid round a
// fillet onto the neighbouring edge's side, so that it ran past its
// junction along that edge and turned back (the mesh flow saw the axis fold
// back). bspline_2_1477: a branch whose curvature-contact end is on the
// peak it runs into kept two points of a pruned ripple beyond it, 25 from
// the end on a radius of 2 700, the second with its sides swapped (the mesh
// flow saw the axis fold back). bspline_3_422: a blob whose seam is a
// convex corner of 175.5 degrees; the chords' diagram lost the last stretch
// of the corner's flare, and the branch, ending at no curvature peak, was
// pruned with the big lobe it crossed (the mesh flow found k = -2).
// Fuzz seed 10: elliptic_10_129, elliptic_10_1574 and bspline_10_1797, a
// junction whose third foot the nearest-point search took to the corner at
// the far end of its edge (the junction kept as the discretised point, 0.6
// off its radius); bspline_10_182, the exact point of a pruned ripple's
// junction short of the edge point placed before it (the edge turned back
// there and its touches jumped to and fro). filleted_4_1455: the branch
// added from the centre of a nearly flat fillet ran to the first kept
// Voronoi edge its ray crossed, but the crossing test had the sign of the
// edge's parameter wrong: it passed the edge just beside the centre and
// joined an edge between two holes across a hole (a junction with no exact
// point, kept 0.002 off its radius). bspline_15_1532: a branch into a broad
// lobe kept a point 8 past its curvature contact (radius 643.5 against the
// contact's 649) and turned back 150 degrees onto the contact, short of the
// turn-back test's 155 (the mesh flow saw the axis fold back). Each
// axis must pass the medial checks and the mesh flow its own; every
// junction touches three distinct places, every convex corner has its
// flare and no edge turns back.
TEST(FuzzFaces, JunctionsTouchThreePlacesFlaresReachTheirCornersEdgesNeverTurnBack) {
  for (const char* name :
       {"bspline_2_152", "filleted_2_975", "bspline_2_1477", "bspline_3_422", "elliptic_10_129", "elliptic_10_1574",
        "bspline_10_1797", "bspline_10_182", "filleted_4_1455", "bspline_15_1532"}) {
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
    const std::optional<MedialAxis> checked = axis_with_its_flow(face);
    if (!checked) continue;
    const MedialAxis& axis = *checked;
    for (const MedialVertex& v : axis.vertices) {
      if (v.kind != MedialVertexKind::Junction) continue;
      int distinct = 0;
      for (std::size_t i = 0; i < v.touches.size(); ++i) {
        bool seen = false;
        for (std::size_t j = 0; j < i; ++j)
          seen = seen || distance(v.touches[i].point, v.touches[j].point) < 1e-6 * face.size;
        distinct += seen ? 0 : 1;
      }
      EXPECT_GE(distinct, 3) << name << ": junction at (" << v.p.x << ", " << v.p.y << ")";
    }
    for (const Corner& c : face.corners) {
      if (c.angle >= kPi) continue;
      EXPECT_TRUE(std::any_of(axis.vertices.begin(), axis.vertices.end(),
                              [&](const MedialVertex& v) {
                                return v.kind == MedialVertexKind::Flare &&
                                       distance(v.p, c.position) <= 1e-9 * face.size;
                              }))
          << name << ": no flare at the convex corner (" << c.position.x << ", " << c.position.y << ")";
    }
    for (const MedialEdge& e : axis.edges) {
      for (std::size_t k = 1; k + 1 < e.points.size(); ++k) {
        const Vec2 in = e.points[k].p - e.points[k - 1].p, out = e.points[k + 1].p - e.points[k].p;
        EXPECT_GT(dot(in, out), -0.9 * norm(in) * norm(out))
            << name << ": the edge turns back at (" << e.points[k].p.x << ", " << e.points[k].p.y << ")";
      }
    }
  }
}

// filleted_14_1695 (fuzz seed 14) and filleted_9_1070 (seed 9): where five
// places lie almost on one circle, two neighbouring Voronoi nodes both took
// the one exact junction touching most of their edges: two vertices at one
// point, and an edge beside them that touched one hole at one end and the
// other hole at the other (a block outline then missed itself by 0.0027,
// or ran clockwise). Junctions joined by an edge are apart, and the edge
// touches one loop on each side all along.
TEST(FuzzFaces, JunctionsJoinedByAnEdgeAreApartAndShareItsTwoLoops) {
  for (const char* name : {"filleted_14_1695", "filleted_9_1070"}) {
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
    const std::optional<MedialAxis> checked = axis_with_its_flow(face);
    if (!checked) continue;
    const MedialAxis& axis = *checked;
    for (const MedialEdge& e : axis.edges) {
      if (e.from < 0 || axis.vertices[e.from].kind != MedialVertexKind::Junction ||
          axis.vertices[e.to].kind != MedialVertexKind::Junction)
        continue;
      const MedialVertex &a = axis.vertices[e.from], &b = axis.vertices[e.to];
      EXPECT_GT(distance(a.p, b.p), 1e-9 * face.size)
          << name << ": two junctions at (" << a.p.x << ", " << a.p.y << ")";
      const MedialPoint &first = e.points.front(), &last = e.points.back();
      EXPECT_EQ(first.left.loop, last.left.loop) << name << ": edge from (" << a.p.x << ", " << a.p.y << ")";
      EXPECT_EQ(first.right.loop, last.right.loop) << name << ": edge from (" << a.p.x << ", " << a.p.y << ")";
    }
  }
}

// Faces whose meshes were valid but far coarser than asked: a side facing a
// much shorter one in a mapped block took the short one's count, since
// interval assignment charged at most one goal's worth for any coarsening.
// elliptic_1_119, a teardrop whose 25 degree tip sits in a block folded there
// (its long sides face the halves of the cut across it): 19 quads for
// area / H^2 = 52, boundary intervals up to 9 H. bspline_1_1957 and
// elliptic_1_609, rings meshed as radial grids whose outer loops are 5.5 and
// 2 times the inner one: the outer loop took the hole's count (60 quads for
// 151, intervals 5.5 H; 42 for 120). The radial grid stays.
TEST(FuzzFaces, ElementCountFollowsTheTargetSize) {
  for (const auto& [name, ring] : std::vector<std::pair<std::string, bool>>{
           {"elliptic_1_119", false}, {"bspline_1_1957", true}, {"elliptic_1_609", true}}) {
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
    PipelineOptions options;
    options.meshing.size = 0.05 * face.size;
    const MeshedFace m = mesh_face(face, options);
    const QuadMesh& mesh = m.blocks.mesh;
    EXPECT_TRUE(test::mesh_validity_problems(face, mesh).empty()) << name;
    EXPECT_EQ(test::element_count_problem(face, mesh, options.meshing.size), "") << name;
    if (!ring) continue;
    EXPECT_TRUE(m.quality.irregular_interior.empty()) << name;
    double longest = 0.0;  // boundary interval: a side of one element only
    std::map<std::pair<int, int>, int> sides;
    for (const auto& q : mesh.quads)
      for (int i = 0; i < 4; ++i) ++sides[{std::min(q[i], q[(i + 1) % 4]), std::max(q[i], q[(i + 1) % 4])}];
    for (const auto& [side, uses] : sides)
      if (uses == 1) longest = std::max(longest, norm(mesh.nodes[side.first] - mesh.nodes[side.second]));
    // 5.5 H when the outer loop took the hole's count; smoothing for shape
    // slides the outer loop's nodes to 3.1 H on elliptic_1_609.
    EXPECT_LT(longest, 3.5 * options.meshing.size) << name;
  }
}

// The relaxed rings: the pentagon's corner taken as flat cancels its k = +1
// against the -1 on its corner, so the mesh has no irregular interior node,
// and says what was relaxed.
TEST(FuzzFaces, ContradictoryTemplatesAreRelaxedWithANote) {
  for (const char* name : {"bspline_1_37", "elliptic_2_1614"}) {
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
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

// B-spline outlines round a small hole (fuzz seeds 15 and 10): one submapped
// ring opened by one split, meshed as one radial grid with the outline
// taking about the hole's count (54 and 26 elements for area / H^2 = 138
// and 142). Both get their count since the submap typing change (the two
// walks of a split balance only each other; sides far off their direction
// are typed again); bspline_15_1782 by the fallback that types its corners
// by the corner rule alone.
TEST(FuzzFaces, RingsRoundASmallHoleGetTheElementsAsked) {
  for (const char* name : {"bspline_15_1782", "bspline_10_342"}) {
    const std::optional<MeshedFace> m = valid_mesh_of(name);
    if (!m) continue;
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
    const double size = 0.05 * face.size;
    EXPECT_EQ(test::element_count_problem(face, m->blocks.mesh, size), "") << name;
    EXPECT_GT(static_cast<double>(m->quality.quads), 0.75 * face.area / (size * size)) << name;
    EXPECT_GT(m->quality.min_scaled_jacobian, 0.35) << name;  // bspline_10_342: 0.39 at the hole's bottom
  }
}

// Faces whose merged singularities got a block their geometry does not fit:
// aerofoil_4_313, aerofoil_9_293 and aerofoil_14_248, merged k = +1 in
// 5-sided blocks with a side turning 150 to 170 degrees round a section's nose. Their first
// placement folded beyond untangling (inverted elements, the mesh check
// stopped them); merging is a choice, so the face is meshed again with less
// of it, and the result says so. aerofoil_14_248 meshes as asked since a
// submapped block with a side more than 135 degrees off its logical
// direction is typed again following its outline's turning
// (MeshReference.GlyphRingWithACuspGetsCornersRoundItsHole). Since
// smoothing raises Verdict's shape rather than the scaled Jacobian,
// aerofoil_4_313's merged block untangles (its wrapped section then
// framed) and aerofoil_9_293's no longer does. All three hold elements of
// shape under 0.1 round the sections' noses either way: an open cause of
// issue 40 (docs/quality.md).
TEST(FuzzFaces, LessMergingWhereAMergedBlockCannotBeMeshed) {
  for (const char* name : {"aerofoil_14_248", "aerofoil_4_313"}) {
    const std::optional<MeshedFace> turned = valid_mesh_of(name);
    ASSERT_TRUE(turned) << name;
    EXPECT_GT(turned->quality.min_scaled_jacobian, 0.1) << name;
    // As asked: none of the pipeline's fallbacks but, at most, its poor mesh
    // made again with its sections framed. (aerofoil_14_248's decomposition
    // types a block by its angles, the lenient typing: the typed fallbacks
    // showed it on 2026-12-07, where the notes had not.)
    for (const Fallback f : turned->fallbacks)
      EXPECT_TRUE(f == Fallback::FramedHoles || f == Fallback::LenientTyping) << name << ": " << fallback_name(f);
  }
  const std::optional<MeshedFace> less = valid_mesh_of("aerofoil_9_293");
  ASSERT_TRUE(less);
  EXPECT_GT(less->quality.min_scaled_jacobian, 0.05);
  EXPECT_EQ(less->fallbacks, std::vector<Fallback>{Fallback::LessMerging});
  bool noted = false;
  for (const std::string& note : less->blocks.notes)
    noted = noted ||
            note.find("meshed with merging factor 0.25, as a fallback: with merging factor 0.75") != std::string::npos;
  EXPECT_TRUE(noted) << ::testing::PrintToString(less->blocks.notes);
}

// Passages whose blade's trailing edge is the one point both splits round
// the blade end at: the k = +2 behind the blade kept a 6-sided block wrapped
// round the whole blade, a disc only through that point, and its template's
// lines from the centre crossed the blade. cascade_12_40 (fuzz seed 12) then
// folded and was meshed with less merging; cascade_2_381 (seed 2) and
// cascade_33_391 (seed 33) passed every check of the mesher with elements
// across the blade's nose (a silent wrong mesh: the tests' inside check
// caught cascade_33_391). Such a polygon's singularity is now fixed instead.
TEST(FuzzFaces, APolygonBlockNeverWrapsRoundAHole) {
  for (const char* name : {"cascade_12_40", "cascade_2_381", "cascade_33_391"}) {
    checked_decomposition(test::data_face(std::string("fuzz/") + name));
    const std::optional<MeshedFace> m = valid_mesh_of(name);
    if (!m) continue;
    EXPECT_TRUE(m->blocks.notes.empty()) << name << ": " << ::testing::PrintToString(m->blocks.notes);
    EXPECT_GT(m->quality.min_scaled_jacobian, 0.5) << name;
  }
}

// The interior angle of a block's outline at one of its corners, in degrees.
double corner_angle(const Block& b, Vec2 corner) {
  const std::vector<Vec2>& o = b.outline;
  const std::size_t n = o.size();
  std::size_t at = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (distance(o[i], corner) < distance(o[at], corner)) at = i;
  const double tiny = 1e-9 * norm(o[(at + n / 2) % n] - o[at]);
  std::size_t before = (at + n - 1) % n, after = (at + 1) % n;
  while (distance(o[before], o[at]) <= tiny) before = (before + n - 1) % n;
  while (distance(o[after], o[at]) <= tiny) after = (after + 1) % n;
  const Vec2 in = o[at] - o[before], out = o[after] - o[at];
  return 180.0 - std::atan2(cross(in, out), dot(in, out)) * 180.0 / M_PI;
}

// Smooth blobs (fuzz seeds 1, 2 and 26) cut into wedges, each between two
// cuts and the boundary, and halves: blocks of two or three corners and no
// singularity. Submapped, such a block needed more corners on its smooth
// side, one element at each with an angle near 180 degrees, ever nearer as
// the elements shrink (minimum 0.28 to 0.35 at 0.05 of the diagonal, 0.06
// to 0.10 at 0.01). Now a polygon of its m corners round a k = m - 4 of its
// own: no convex corner where a convex block's outline runs on, every
// boundary node with the elements its angle asks, and the quality holds
// under refinement.
TEST(FuzzFaces, BlocksOfTwoOrThreeCornersArePolygonsNotSubmapsWithCornersOnACurve) {
  for (const auto& [name, least] : std::vector<std::pair<std::string, double>>{
           {"bspline_1_2", 0.7}, {"bspline_1_1917", 0.7}, {"bspline_2_792", 0.7}, {"bspline_26_197", 0.45}}) {
    const FaceModel face = test::data_face("fuzz/" + name);
    const Decomposition d = checked_decomposition(face);
    int polygons = 0;
    for (const Block& b : d.blocks) {
      // (bspline_26_197 keeps one such corner in a submap with a reflex corner.)
      const bool convex =
          std::none_of(b.corners.begin(), b.corners.end(), [](const BlockCorner& c) { return c.type > 1; });
      for (const BlockCorner& c : b.corners) {
        if (convex && c.type == 1) {
          EXPECT_LT(corner_angle(b, c.p), 157.5) << name << " corner at " << c.p.x << ", " << c.p.y;
        }
      }
      const int m = static_cast<int>(b.corners.size());
      if (b.kind != BlockKind::Polygon || m > 3) continue;
      ++polygons;
      ASSERT_GE(b.singularity, 0) << name;
      EXPECT_EQ(d.singularities[b.singularity].k, m - 4) << name;
      EXPECT_TRUE(inside_polygon(b.outline, d.singularities[b.singularity].p)) << name;
    }
    EXPECT_GE(polygons, 2) << name;
    for (const double size_factor : {0.05, 0.01}) {
      const std::optional<MeshedFace> m = valid_mesh_of(name, size_factor);
      if (!m) continue;
      EXPECT_TRUE(m->quality.irregular_boundary.empty()) << name << " at " << size_factor;
      EXPECT_GT(m->quality.min_scaled_jacobian, least) << name << " at " << size_factor;
    }
  }
}

// Filleted plates (fuzz seeds 1 and 6): the k = -1 of each fillet's finite
// contact could not keep a convex block and was fixed on its arc, a convex
// corner in the fillet's middle with one element there, its angle near 180
// degrees (minimum 0.39 to 0.45 at 0.05 of the diagonal, 0.31 to 0.42 at
// 0.01; 3 to 5 boundary nodes off their element count). Now the arc's sector,
// cut off by the two radii from the fillet's centre, is a triangle round
// that singularity, floating again.
TEST(FuzzFaces, AFilletsFixedSingularityGetsTheArcsSectorAsItsTriangle) {
  for (const char* name : {"filleted_1_1490", "filleted_1_1980", "filleted_1_910", "filleted_6_915"}) {
    const FaceModel face = test::data_face(std::string("fuzz/") + name);
    const Decomposition d = checked_decomposition(face);
    int sectors = 0;  // triangles whose curved side is one whole circle edge
    for (const Block& b : d.blocks) {
      if (b.kind != BlockKind::Polygon || b.corners.size() != 3) continue;
      for (const BlockSide& side : b.sides) {
        const OutlinePiece& piece = side.pieces.front();
        if (piece.split >= 0) continue;
        const BoundaryEdge& edge = face.loops[piece.loop].edges[piece.edge];
        if (curve_type(edge.curve) != CurveType::Circle) continue;
        const double from = side.pieces.front().t_from, to = side.pieces.back().t_to;
        if (std::abs(std::abs(to - from) - std::abs(edge.t_end - edge.t_start)) > 1e-9) continue;
        ++sectors;
        ASSERT_GE(b.singularity, 0) << name;
        EXPECT_EQ(d.singularities[b.singularity].k, -1) << name;
        EXPECT_FALSE(d.singularities[b.singularity].fixed) << name;
      }
    }
    EXPECT_GE(sectors, 3) << name;
    for (const double size_factor : {0.05, 0.01}) {
      const std::optional<MeshedFace> m = valid_mesh_of(name, size_factor);
      if (!m) continue;
      EXPECT_TRUE(m->quality.irregular_boundary.empty()) << name << " at " << size_factor;
      EXPECT_GT(m->quality.min_scaled_jacobian, 0.5) << name << " at " << size_factor;
      // filleted_6_915 keeps a needle (shape 0.0002 at 0.05, sides 0.0002
      // and 2) at the foot of a column of thin elements between two splits
      // that nearly coincide: a decomposition defect, open (docs/quality.md).
      if (std::string(name) != "filleted_6_915")
        EXPECT_GT(m->quality.min_shape(), 0.1) << name << " at " << size_factor;
    }
  }
}

// A smooth blob round a hole (fuzz seed 44): the k = -1 at the junction
// below the hole is fixed, its radii go to each place its edges touch. The
// boundary between two of those places is an arc round the junction whose
// branch the medial axis pruned, a sector with no edge in it: no block
// walked it (the areas fell 3 % short) or the branch beside it was walked
// into it (its singularity outside its block), and every attempt stopped.
// Now the block beside that sector takes it in.
TEST(FuzzFaces, AFixedJunctionsSectorWithNoEdgeBelongsToTheBlockBesideIt) {
  const FaceModel face = test::data_face("fuzz/bspline_44_152");
  const Decomposition d = checked_decomposition(face);
  EXPECT_FALSE(d.fallback);
  double area = 0.0;
  for (const Block& b : d.blocks) area += b.area;
  EXPECT_NEAR(area, face.area, 1e-6 * face.area);
  for (const double size_factor : {0.05, 0.01}) {
    const std::optional<MeshedFace> m = valid_mesh_of("bspline_44_152", size_factor);
    if (!m) continue;
    EXPECT_GT(m->quality.min_scaled_jacobian, 0.6) << size_factor;
  }
}

// A blob (fuzz seed 47) whose medial axis meets in a junction of five
// branches with two k = -1 switches beside it: every decomposition attempt
// left a block's outline pieces 600 apart (the splits round the junction
// miss each other), so the face stopped, with or without merging. A face
// of one loop with no reflex corner and at most six corners now falls back
// last of all on the whole face as one polygon block: here the 0-sided
// template of a disc, four valence-3 nodes.
TEST(FuzzFaces, AFaceWhoseMedialDecompositionFailsMeshesAsOneBlock) {
  for (const double size_factor : {0.05, 0.01}) {
    const std::optional<MeshedFace> m = valid_mesh_of("bspline_47_787", size_factor);
    ASSERT_TRUE(m) << size_factor;
    ASSERT_EQ(m->decomposition.blocks.size(), 1u);
    EXPECT_EQ(m->decomposition.blocks[0].kind, BlockKind::Polygon);
    ASSERT_FALSE(m->blocks.notes.empty());
    EXPECT_NE(m->blocks.notes.back().find("the whole face as one block"), std::string::npos);
    EXPECT_EQ(m->fallbacks, std::vector<Fallback>{Fallback::WholeFace});
    EXPECT_EQ(m->quality.irregular_interior.size(), 4u);
    for (const IrregularNode& n : m->quality.irregular_interior) EXPECT_EQ(n.elements, 3);
    EXPECT_GT(m->quality.min_scaled_jacobian, 0.8) << size_factor;
  }
}

// Blobs whose submapped block wrapped half round their hole (fuzz seed 45),
// its side along the hole turning in by about 190 degrees with no corner:
// at a hundredth of the diagonal the harmonic layout folded over a band of
// 5 to 8 % of the block beside the hole, and every attempt stopped. Now
// the block is cut across from the middle of that side, and each half
// submaps with a side turning half as far. The glyph 6 at 0.005 of its
// diagonal needed untangling 24 rings wide (min 0.04); now a fallback's
// blocks mesh it at over 0.3.
TEST(FuzzFaces, ABlockWrappedHalfRoundAHoleIsCutAcrossFromThatSidesMiddle) {
  for (const char* name : {"bspline_45_1597"}) {
    const Decomposition d = checked_decomposition(test::data_face(std::string("fuzz/") + name));
    EXPECT_TRUE(std::any_of(d.notes.begin(), d.notes.end(), [](const std::string& n) {
      return n.find("cut across") != std::string::npos;
    })) << ::testing::PrintToString(d.notes);
    const std::optional<MeshedFace> m = valid_mesh_of(name, 0.01);
    ASSERT_TRUE(m);
    EXPECT_TRUE(m->fallbacks.empty()) << fallback_names(m->fallbacks);
    EXPECT_GT(m->quality.min_scaled_jacobian, 0.45);
  }
  const FaceModel glyph = test::data_face("glyph6_1206_smd");
  PipelineOptions options;
  options.meshing.size = 0.005 * glyph.size;
  const MeshedFace m = mesh_face(glyph, options);
  EXPECT_EQ(m.quality.inverted, 0);
  EXPECT_GT(m.quality.min_scaled_jacobian, 0.3);
}

// A blob with a long submapped block round its hole (fuzz seed 10) at a
// tenth of the default size: every attempt but the last folds, the last
// with the block's harmonic layout folded over a band of it too. Placed by
// Winslow's grid, which follows the hole round, it meshes (poorly).
TEST(FuzzFaces, AWidelyFoldedBlockIsPlacedByWinslowsGridWhenAllElseFolds) {
  const std::optional<MeshedFace> m = valid_mesh_of("bspline_10_342", 0.005);
  ASSERT_TRUE(m);
  const auto& notes = m->blocks.notes;
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(), [](const std::string& n) {
    return n.find("Winslow's grid") != std::string::npos;
  })) << ::testing::PrintToString(notes);
  const FaceModel face = test::data_face("fuzz/bspline_10_342");
  EXPECT_GT(m->quality.quads, 0.75 * face.area / (0.005 * face.size * 0.005 * face.size));
}

// The blocks tile the face: their areas (exact line integrals) add up to the
// face's, every check a user would make holds, and OCC cuts the face along
// the splits into valid faces whose areas add up to the face's.
// filleted_6_915 (fuzz seed 6): the boundary walk round a fillet 1.4e-5 long
// labelled a piece's end with that arc while its point lay 0.62 further on,
// on the next edge; the decomposition passed its checks and the mesh
// stopped joining block outlines. The decomposition now checks that its
// pieces meet each other and their edges: such a face stops there, loudly.
TEST(FuzzFaces, DecompositionPiecesMeetTheirEdgesOrTheStageSaysSo) {
  const FaceModel face = test::data_face("fuzz/filleted_6_915");
  const MedialAxis axis = compute_medial_axis(face);
  const MeshFlow flow = compute_mesh_flow(face, axis);
  try {
    const Decomposition d = decompose(face, axis, flow, {});
    const auto problems = test::decomposition_problems(face, flow, d);
    EXPECT_TRUE(problems.empty()) << ::testing::PrintToString(problems);
  } catch (const SelfCheckError& e) {
    EXPECT_NE(std::string(e.what()).find("decomposition"), std::string::npos) << e.what();
  }
}

// aerofoil_10_67 (a high-lift arrangement 0.01 across) and strip_3_3 (a
// strip 0.004 long with edges of 2e-6): OCC's splitter, which works to an
// absolute 1e-7, left splits uncut (4 block faces for 8 blocks, their areas
// 2e-5 of the face off) or returned one invalid face; such faces are now
// cut at unit size and scaled back.
TEST(FuzzFaces, DecompositionsTileTheFace) {
  // With whether the decomposition must say it fell back.
  for (const auto& [name, fallback] : std::vector<std::pair<std::string, bool>>{
           {"bspline_1_777", false},   {"bspline_1_2", false},     {"bspline_1_1262", false},
           {"plate_1_1391", false},    {"bspline_1_1272", true},   {"filleted_4_1700", false},
           {"bspline_2_792", false},   {"filleted_1_915", false},  {"filleted_1_950", false},
           {"filleted_1_1820", false}, {"filleted_1_1980", false}, {"filleted_3_275", false},
           {"filleted_1_490", false},  {"filleted_1_910", false},  {"filleted_1_990", false},
           {"filleted_1_1490", false}, {"filleted_1_880", false},  {"filleted_1_1360", false},
           {"bspline_1_1212", false},  {"bspline_1_1442", false},  {"filleted_1_1205", false},
           {"bspline_3_387", false},   {"bspline_1_717", false},   {"aerofoil_1_116", false},
           {"aerofoil_10_67", false},  {"strip_3_3", true}}) {
    const std::string text = test::data_brep_text(std::string("fuzz/") + name);
    const FaceModel face = face_model_from_brep_string(text, name);
    const MedialAxis axis = compute_medial_axis(face);
    const MeshFlow flow = compute_mesh_flow(face, axis);
    Decomposition d;
    try {
      d = decompose(face, axis, flow, {});
    } catch (const SelfCheckError& e) {
      ADD_FAILURE() << e.what();
      continue;
    }
    const auto problems = test::decomposition_problems(face, flow, d);
    EXPECT_TRUE(problems.empty()) << ::testing::PrintToString(problems);
    EXPECT_EQ(d.fallback, fallback) << name;
    if (d.fallback) {
      EXPECT_FALSE(d.notes.empty()) << name << ": a fallback must say why";
    }
    double area = 0.0;
    for (const Block& b : d.blocks) area += b.area;
    EXPECT_NEAR(area, face.area, 1e-9 * face.area) << name;
    std::vector<std::vector<Vec2>> lines;
    for (const Split& s : d.splits) lines.push_back(s.polyline);
    const TopoDS_Face occ_face = face_from_brep_string(text, name);
    std::vector<TopoDS_Face> pieces;
    ASSERT_NO_THROW(pieces = split_face(occ_face, face.frame, lines)) << name;
    EXPECT_EQ(pieces.size(), d.blocks.size()) << name;
    double occ_area = 0.0;
    for (const TopoDS_Face& piece : pieces) {
      EXPECT_TRUE(BRepCheck_Analyzer(piece).IsValid()) << name;
      occ_area += area_of(piece);
    }
    // Splitting B-spline edges moves them within OCC's tolerance: on a face a
    // fortieth of a unit across (aerofoil_1_116) that term, tolerance x size,
    // is the larger, as split_face's own check allows.
    EXPECT_NEAR(occ_area, area_of(occ_face), 1e-8 * face.area + face.tolerance * face.size) << name;
  }
}

}  // namespace
}  // namespace mm

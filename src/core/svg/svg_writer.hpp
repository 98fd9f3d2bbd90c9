#pragma once
// A small SVG canvas in face coordinates (y up) and the drawing of a face.
#include <sstream>
#include <string>
#include <vector>

#include "boundary/face_model.hpp"
#include "decomposition/decomposition.hpp"
#include "medial/medial_axis.hpp"
#include "meshing/quad_mesh.hpp"
#include "quality/quality.hpp"
#include "singularity/mesh_flow.hpp"

namespace mm {

class SvgCanvas {
 public:
  // Fits the box into a picture `width` pixels wide, with a margin.
  SvgCanvas(Box box, double width);
  void polyline(const std::vector<Vec2>& points, bool closed, const std::string& style);
  // Closed polylines filled together with the even-odd rule (a face with holes).
  void region(const std::vector<std::vector<Vec2>>& loops, const std::string& style);
  void dot(Vec2 p, double radius_px, const std::string& style);
  void text(Vec2 p, const std::string& label, double size_px, const std::string& style);
  double pixels_per_unit() const { return scale_; }
  std::string str() const;
  void save(const std::string& path) const;  // throws InputError if it cannot write

 private:
  Vec2 map(Vec2 p) const;
  Box box_;
  double scale_;
  double width_, height_, margin_;
  std::ostringstream body_;
};

// A row of coloured dots with labels under the face's bounding box.
void draw_legend(SvgCanvas& canvas, const FaceModel& face,
                 const std::vector<std::pair<std::string, std::string>>& items);
// The face filled and outlined.
void draw_face(SvgCanvas& canvas, const FaceModel& face);
// The face's corners coloured by nc, with a legend under the picture.
void draw_corners(SvgCanvas& canvas, const FaceModel& face);
// The medial axis, its vertices coloured by kind, with a legend.
void draw_medial_axis(SvgCanvas& canvas, const FaceModel& face, const MedialAxis& axis);

// A singularity as drawn: where it is and its k.
struct SingularityMark {
  Vec2 p;
  int k = 0;
};
// The medial axis coloured by flow type (n = 0, 1, 2) and the singularities
// marked red (k > 0) or blue (k < 0) with their k, with a legend.
void draw_mesh_flow(SvgCanvas& canvas, const FaceModel& face, const MeshFlow& flow,
                    const std::vector<SingularityMark>& marks);

// The blocks shaded and labelled with their number of sides (or "submap"),
// the medial axis faintly, the splits, and the singularities (fixed ones
// ringed), with a legend: the picture of the paper's Figs. 21 to 26.
void draw_decomposition(SvgCanvas& canvas, const FaceModel& face, const MedialAxis& axis,
                        const Decomposition& decomposition);

// The quad mesh over its blocks' shading, the splits drawn bold, and the
// irregular nodes marked by valence (boundary nodes off their corner's nc in
// orange), with a legend.
void draw_quad_mesh(SvgCanvas& canvas, const FaceModel& face, const Decomposition& decomposition, const QuadMesh& mesh,
                    const QualityReport& quality);

// Several faces' merged mesh seen along the mean of their normals or an
// octant diagonal, whichever sees the most edge-on face best (coplanar faces
// face on), nearer elements over further: each face's
// elements in its own colour, the shared pieces (chains of merged nodes)
// drawn bold purple, the irregular nodes marked by valence. Makes the canvas.
SvgCanvas draw_merged_mesh(const MergedMesh& mesh, const std::vector<std::vector<int>>& shared_chains,
                           const QualityReport& quality, double width);

}  // namespace mm

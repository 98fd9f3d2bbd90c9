#pragma once
// Faces of the aerodynamic class, built from their analytic definitions, for
// the tests and the random-face fuzzer: NACA 4- and 5-digit sections in a
// far field, a three-element high-lift arrangement, a turbine cascade
// passage. Every curved side is a B-spline interpolated through a few
// hundred points, as OCC holds such a section read from a STEP file. All
// lengths are in chords times `scale`.
#include <TopoDS_Face.hxx>
#include <string>
#include <vector>

namespace mm::test {

// A NACA section: "0012", "4412" (4-digit: camber %, its position in tenths,
// thickness %) or "23012" (5-digit, standard camber line: design lift in
// 0.15 steps, camber position in twentieths, 0, thickness %). Sharp trailing
// edge (the closed thickness form) or blunt (the original form, its open end
// closed by a straight edge). Placed with its leading edge at (x, y) and
// turned by `angle` degrees about it (positive: nose up).
struct AerofoilSection {
  std::string digits = "0012";
  bool blunt = false;
  double chord = 1.0;
  double x = 0.0, y = 0.0;
  double angle = 0.0;
};

// The section alone: the end face of a wing, slat or flap. Throws
// std::invalid_argument for a designation it does not know.
TopoDS_Face section_face(const AerofoilSection& section, double scale);

// Sections as holes in a far-field rectangle 10 chords wide and 4 high
// (x from -4.5 to 5.5, y from -2 to 2). Throws std::invalid_argument for a
// designation it does not know.
TopoDS_Face far_field_face(const std::vector<AerofoilSection>& sections, double scale);

// Slat, main element and flap in the far field: the main element a NACA
// 2412 of chord 0.8 from (0, 0), a 0.15 slat deflected by slat_angle ahead
// of it and a 0.3 flap deflected by flap_angle under its trailing edge,
// each moved out along its slot until the narrowest gap is `gap` (a fraction
// of the chord, 0.003 to 0.03 in the tests).
struct HighLift {
  double gap = 0.01;
  double slat_angle = 25.0;
  double flap_angle = 30.0;
  std::string slat = "6409", main = "2412", flap = "4412";
  bool blunt = false;
};
TopoDS_Face high_lift_face(const HighLift& layout, double scale);

// One passage of a turbine cascade (axial x, pitchwise y): the blade as the
// hole, a cubic camber line from inlet metal angle `inlet` to outlet angle
// `outlet` (degrees, in blade coordinates) turned by `stagger`, thickness
// `thickness` (of the chord) on the NACA form, a sharp trailing edge or one
// rounded by a tangent arc of radius te_radius; the two periodic sides are
// the camber line moved by +-pitch/2 along y, carried half a chord upstream
// and downstream along the metal angles, each one B-spline; straight inlet
// and outlet.
struct Cascade {
  double stagger = 10.0;
  double inlet = 40.0;
  double outlet = -55.0;
  double pitch = 0.9;
  double thickness = 0.15;
  bool rounded = false;
  double te_radius = 0.01;
};
TopoDS_Face cascade_face(const Cascade& cascade, double scale);

}  // namespace mm::test

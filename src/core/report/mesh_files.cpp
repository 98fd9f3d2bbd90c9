#include "report/mesh_files.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace mm {
namespace {

// All three formats number an 8-node quad's nodes the same way: the four
// corners counter-clockwise, then the mid-side node of each side i (corner i
// to i + 1). So one element node list serves every writer.
struct ElementNodes {
  std::array<int, 8> ids{};
  std::size_t count = 4;
  const int* begin() const { return ids.data(); }
  const int* end() const { return ids.data() + count; }
};

ElementNodes element_nodes(const MergedMesh& mesh, std::size_t q) {
  ElementNodes nodes;
  std::copy(mesh.quads[q].begin(), mesh.quads[q].end(), nodes.ids.begin());
  if (mesh.order() == 2) {
    std::copy(mesh.midside[q].begin(), mesh.midside[q].end(), nodes.ids.begin() + 4);
    nodes.count = 8;
  }
  return nodes;
}

// 17 significant digits: a double read back is the double written. The
// .inp format keeps 12: CalculiX reads at most 20 characters a field and
// silently misreads longer numbers.
constexpr int kExactDigits = 17;
constexpr int kInpDigits = 12;

void put_number(std::ostream& out, double v, int digits = kExactDigits) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, v, std::chars_format::general, digits).ptr;
  out.write(text, end - text);
}

void put_point_3d(std::ostream& out, const std::array<double, 3>& q, const char* separator, int digits = kExactDigits) {
  put_number(out, q[0], digits);
  out << separator;
  put_number(out, q[1], digits);
  out << separator;
  put_number(out, q[2], digits);
}

void check_mesh(const MergedMesh& mesh, const std::string& path) {
  const int n = static_cast<int>(mesh.nodes.size());
  if (!mesh.midside.empty() && mesh.midside.size() != mesh.quads.size())
    throw InputError(path + ": mesh has " + std::to_string(mesh.quads.size()) + " quads but " +
                     std::to_string(mesh.midside.size()) + " mid-side node sets");
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    for (int v : element_nodes(mesh, q)) {
      if (v < 0 || v >= n)
        throw InputError(path + ": quad " + std::to_string(q) + " refers to node " + std::to_string(v) + " of " +
                         std::to_string(n));
    }
  }
}

void write_inp(std::ostream& out, const MergedMesh& mesh, const MeshFileOptions& options) {
  const bool quadratic = mesh.order() == 2;
  const char* type = options.shell_elements ? (quadratic ? "S8" : "S4") : (quadratic ? "CPS8" : "CPS4");
  out << "*HEADING\nMedialMesh quad mesh\n*NODE, NSET=NALL\n";
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    out << n + 1 << ", ";
    put_point_3d(out, mesh.nodes[n], ", ", kInpDigits);
    out << '\n';
  }
  // Plane-stress elements must run counter-clockwise seen from +z: those of
  // a face looking down the z axis are reversed.
  out << "*ELEMENT, TYPE=" << type << ", ELSET=EALL\n";
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    ElementNodes nodes = element_nodes(mesh, q);
    const int face = q < mesh.face_of_quad.size() ? mesh.face_of_quad[q] : 0;
    if (!options.shell_elements && face < static_cast<int>(mesh.normals.size()) && mesh.normals[face][2] < 0) {
      // Corners 0 3 2 1; the sides then run 3, 2, 1, 0 backwards.
      std::reverse(nodes.ids.begin() + 1, nodes.ids.begin() + 4);
      std::reverse(nodes.ids.begin() + 4, nodes.ids.begin() + nodes.count);
    }
    out << q + 1;
    for (int v : nodes) out << ", " << v + 1;
    out << '\n';
  }
  std::vector<int> boundary;
  for (std::size_t n = 0; n < mesh.on_boundary.size() && n < mesh.nodes.size(); ++n) {
    if (mesh.on_boundary[n]) boundary.push_back(static_cast<int>(n));
  }
  if (boundary.empty()) return;
  out << "*NSET, NSET=NBOUNDARY\n";
  // Abaqus reads at most 16 entries on a data line.
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    out << boundary[i] + 1 << ((i + 1) % 16 == 0 || i + 1 == boundary.size() ? "\n" : ", ");
  }
}

void write_msh(std::ostream& out, const MergedMesh& mesh) {
  std::array<double, 3> low{0, 0, 0};
  std::array<double, 3> high{0, 0, 0};
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const auto& q = mesh.nodes[n];
    for (int k = 0; k < 3; ++k) {
      low[k] = n == 0 ? q[k] : std::min(low[k], q[k]);
      high[k] = n == 0 ? q[k] : std::max(high[k], q[k]);
    }
  }
  const std::size_t nodes = mesh.nodes.size();
  const std::size_t quads = mesh.quads.size();
  const int type = mesh.order() == 2 ? 16 : 3;
  // One surface entity in one physical group, so that Gmsh and the solvers
  // reading its files keep the elements.
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  out << "$PhysicalNames\n1\n2 1 \"face\"\n$EndPhysicalNames\n";
  out << "$Entities\n0 0 1 0\n1";
  for (double v : {low[0], low[1], low[2], high[0], high[1], high[2]}) {
    out << ' ';
    put_number(out, v);
  }
  out << " 1 1 0\n$EndEntities\n";
  out << "$Nodes\n1 " << nodes << " 1 " << nodes << "\n2 1 0 " << nodes << '\n';
  for (std::size_t n = 0; n < nodes; ++n) out << n + 1 << '\n';
  for (std::size_t n = 0; n < nodes; ++n) {
    put_point_3d(out, mesh.nodes[n], " ");
    out << '\n';
  }
  out << "$EndNodes\n$Elements\n1 " << quads << " 1 " << quads << "\n2 1 " << type << ' ' << quads << '\n';
  for (std::size_t q = 0; q < quads; ++q) {
    out << q + 1;
    for (int v : element_nodes(mesh, q)) out << ' ' << v + 1;
    out << '\n';
  }
  out << "$EndElements\n";
}

void write_vtu(std::ostream& out, const MergedMesh& mesh) {
  const bool quadratic = mesh.order() == 2;
  const std::size_t per_element = quadratic ? 8 : 4;
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.nodes.size() << "\" NumberOfCells=\""
      << mesh.quads.size() << "\">\n";
  out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const auto& p : mesh.nodes) {
    put_point_3d(out, p, " ");
    out << '\n';
  }
  out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    const auto nodes = element_nodes(mesh, q);
    for (std::size_t i = 0; i < nodes.count; ++i) out << nodes.ids[i] << (i + 1 == nodes.count ? '\n' : ' ');
  }
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) out << (q + 1) * per_element << '\n';
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  const char* type = quadratic ? "23\n" : "9\n";  // VTK_QUADRATIC_QUAD, VTK_QUAD
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) out << type;
  out << "</DataArray>\n</Cells>\n";
  // The decomposition block of each element, for colouring in a viewer, and
  // its face when there are several.
  const bool blocks = mesh.block_of_quad.size() == mesh.quads.size() && !mesh.quads.empty();
  const bool faces = mesh.normals.size() > 1 && mesh.face_of_quad.size() == mesh.quads.size();
  if (blocks || faces) {
    out << "<CellData Scalars=\"block\">\n";
    if (blocks) {
      out << "<DataArray type=\"Int32\" Name=\"block\" format=\"ascii\">\n";
      for (int block : mesh.block_of_quad) out << block << '\n';
      out << "</DataArray>\n";
    }
    if (faces) {
      out << "<DataArray type=\"Int32\" Name=\"face\" format=\"ascii\">\n";
      for (int face : mesh.face_of_quad) out << face << '\n';
      out << "</DataArray>\n";
    }
    out << "</CellData>\n";
  }
  out << "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// A single face's mesh placed in 3-D by its frame; its boundary nodes are those
// on the face's curves.
MergedMesh placed(const QuadMesh& mesh, const Frame& frame) {
  MergedMesh placed;
  for (const Vec2& p : mesh.nodes) placed.nodes.push_back(to_3d(frame, p));
  placed.quads = mesh.quads;
  placed.midside = mesh.midside;
  placed.face_of_quad.assign(mesh.quads.size(), 0);
  placed.block_of_quad = mesh.block_of_quad;
  placed.on_boundary.assign(mesh.nodes.size(), false);
  for (std::size_t n = 0; n < mesh.places.size() && n < mesh.nodes.size(); ++n)
    placed.on_boundary[n] = mesh.places[n].loop >= 0;
  const auto& x = frame.x_dir;
  const auto& y = frame.y_dir;
  placed.normals = {{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]}};
  return placed;
}

}  // namespace

void write_mesh_file(const QuadMesh& mesh, const Frame& frame, const std::string& path,
                     const MeshFileOptions& options) {
  write_mesh_file(placed(mesh, frame), path, options);
}

void write_mesh_file(const MergedMesh& mesh, const std::string& path, const MeshFileOptions& options) {
  enum class Format { inp, msh, vtu };
  Format format;
  if (ends_with(path, ".inp")) {
    format = Format::inp;
  } else if (ends_with(path, ".msh")) {
    format = Format::msh;
  } else if (ends_with(path, ".vtu")) {
    format = Format::vtu;
  } else {
    throw InputError(path + ": unknown mesh file extension (expected .inp, .msh or .vtu)");
  }
  check_mesh(mesh, path);
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open the file for writing");
  switch (format) {
    case Format::inp: write_inp(out, mesh, options); break;
    case Format::msh: write_msh(out, mesh); break;
    case Format::vtu: write_vtu(out, mesh); break;
  }
  out.close();
  if (!out) throw InputError(path + ": writing the mesh failed");
}

}  // namespace mm

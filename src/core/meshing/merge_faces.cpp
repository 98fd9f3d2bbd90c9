#include "meshing/merge_faces.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "meshing/union_find.hpp"

namespace mm {
namespace {

using Point3 = std::array<double, 3>;
using Side = std::pair<int, int>;

double distance3(const Point3& a, const Point3& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

Side side(int a, int b) {
  return {std::min(a, b), std::max(a, b)};
}

std::string at(const Point3& p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

}  // namespace

MergedMesh merge_face_meshes(const std::vector<FaceModel>& faces, const std::vector<const QuadMesh*>& meshes,
                             const std::vector<SharedPiece>& shared, double tolerance) {
  if (faces.size() != meshes.size())
    throw std::invalid_argument("merge_face_meshes: " + std::to_string(faces.size()) + " faces but " +
                                std::to_string(meshes.size()) + " meshes");
  std::string names;
  for (const FaceModel& f : faces) names += (names.empty() ? "" : ", ") + f.name;
  const auto fail = [&](const std::string& check) { throw SelfCheckError(names, "merged mesh: " + check); };
  const int order = meshes.empty() ? 1 : meshes.front()->order();
  std::vector<int> offset{0};
  for (const QuadMesh* m : meshes) {
    if (m->order() != order) fail("the faces' meshes are of different orders");
    offset.push_back(offset.back() + static_cast<int>(m->nodes.size()));
  }
  const int total = offset.back();
  std::vector<Point3> position(total);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (std::size_t n = 0; n < meshes[f]->nodes.size(); ++n)
      position[offset[f] + n] = to_3d(faces[f].frame, meshes[f]->nodes[n]);
  }
  std::vector<int> parent(total);
  std::iota(parent.begin(), parent.end(), 0);
  // The lowest node of a class stands for it: the first face's position.
  const auto join = [&](int a, int b) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  std::vector<bool> on_shared(total, false);
  for (const SharedPiece& p : shared) {
    const std::string pair = faces[p.face_a].name + " and " + faces[p.face_b].name;
    const std::string edges = "the piece of Edge" + std::to_string(p.edge_a) + " of " + faces[p.face_a].name +
                              " shared with Edge" + std::to_string(p.edge_b) + " of " + faces[p.face_b].name;
    if (p.nodes_a.size() != p.nodes_b.size())
      throw SelfCheckError(pair, "merged mesh: " + edges + " has " + std::to_string(p.nodes_a.size()) +
                                     " nodes in one face and " + std::to_string(p.nodes_b.size()) + " in the other");
    for (std::size_t k = 0; k < p.nodes_a.size(); ++k) {
      const int a = offset[p.face_a] + p.nodes_a[k];
      const int b = offset[p.face_b] + p.nodes_b[k];
      const double gap = distance3(position[a], position[b]);
      if (!(gap <= tolerance)) {
        throw SelfCheckError(pair, "merged mesh: node " + std::to_string(k + 1) + " of " + edges + " lies " +
                                       std::to_string(gap) + " from its partner at " + at(position[a]) +
                                       " (tolerance " + std::to_string(tolerance) + ")");
      }
      join(a, b);
      on_shared[a] = on_shared[b] = true;
    }
  }
  // Order 2: the mid-side nodes of shared element sides, each face having
  // put its own on its own curve.
  if (order == 2) {
    std::map<Side, int> middle;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const QuadMesh& mesh = *meshes[f];
      for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
        for (int i = 0; i < 4; ++i) {
          const int a = find_root(parent, offset[f] + mesh.quads[q][i]);
          const int b = find_root(parent, offset[f] + mesh.quads[q][(i + 1) % 4]);
          const int m = offset[f] + mesh.midside[q][i];
          const auto found = middle.emplace(side(a, b), m);
          if (found.second || find_root(parent, found.first->second) == find_root(parent, m)) continue;
          const double gap = distance3(position[found.first->second], position[m]);
          if (!(gap <= tolerance))
            fail("the mid-side nodes of a shared element side at " + at(position[m]) + " lie " + std::to_string(gap) +
                 " apart");
          join(found.first->second, m);
          on_shared[m] = true;
        }
      }
    }
  }

  MergedMesh out;
  std::vector<int> id(total, -1);
  out.node_of.resize(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (std::size_t n = 0; n < meshes[f]->nodes.size(); ++n) {
      const int root = find_root(parent, offset[f] + static_cast<int>(n));
      if (id[root] < 0) {
        id[root] = static_cast<int>(out.nodes.size());
        out.nodes.push_back(position[root]);
      }
      out.node_of[f].push_back(id[root]);
    }
    const auto& x = faces[f].frame.x_dir;
    const auto& y = faces[f].frame.y_dir;
    out.normals.push_back({x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]});
  }
  std::vector<bool> shared_node(out.nodes.size(), false);
  for (int g = 0; g < total; ++g) {
    if (on_shared[g]) shared_node[id[find_root(parent, g)]] = true;
  }
  // How many faces have each merged side on their own boundary.
  std::map<Side, int> faces_at;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const QuadMesh& mesh = *meshes[f];
    const std::vector<int>& to = out.node_of[f];
    std::map<Side, int> own;
    for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
      std::array<int, 4> quad;
      for (int i = 0; i < 4; ++i) {
        quad[i] = to[mesh.quads[q][i]];
        ++own[side(mesh.quads[q][i], mesh.quads[q][(i + 1) % 4])];
      }
      out.quads.push_back(quad);
      if (order == 2) {
        std::array<int, 4> middle;
        for (int i = 0; i < 4; ++i) middle[i] = to[mesh.midside[q][i]];
        out.midside.push_back(middle);
      }
      out.face_of_quad.push_back(static_cast<int>(f));
      out.block_of_quad.push_back(q < mesh.block_of_quad.size() ? mesh.block_of_quad[q] : 0);
    }
    for (const auto& [s, count] : own) {
      if (count == 1) ++faces_at[side(to[s.first], to[s.second])];
    }
  }

  // Every side in two elements, or in as many as faces have it on their
  // boundary (one: the union's outline; two: a shared piece; three or more
  // where so many faces meet at an edge).
  std::map<Side, int> uses;
  for (const auto& q : out.quads) {
    for (int i = 0; i < 4; ++i) {
      const int a = q[i];
      const int b = q[(i + 1) % 4];
      if (a == b) fail("an element side collapsed at " + at(out.nodes[a]) + " when the faces were joined");
      ++uses[side(a, b)];
    }
  }
  out.on_boundary.assign(out.nodes.size(), false);
  for (const auto& [s, count] : uses) {
    const auto found = faces_at.find(s);
    const int expected = found == faces_at.end() ? 2 : found->second;
    if (count != expected) {
      const Point3& p = out.nodes[s.first];
      fail("the element side at " + at(p) + " is in " + std::to_string(count) + " elements but " +
           std::to_string(expected) + (found == faces_at.end() ? " inside a face" : " faces meet there"));
    }
    if (count == 1) out.on_boundary[s.first] = out.on_boundary[s.second] = true;
  }
  for (std::size_t q = 0; q < out.midside.size(); ++q) {
    for (int i = 0; i < 4; ++i) {
      if (out.on_boundary[out.quads[q][i]] && out.on_boundary[out.quads[q][(i + 1) % 4]] &&
          uses[side(out.quads[q][i], out.quads[q][(i + 1) % 4])] == 1)
        out.on_boundary[out.midside[q][i]] = true;
    }
  }
  for (const SharedPiece& p : shared) {
    for (std::size_t k = 0; k + 1 < p.nodes_a.size(); ++k) {
      const int a = out.node_of[p.face_a][p.nodes_a[k]];
      const int b = out.node_of[p.face_a][p.nodes_a[k + 1]];
      if (uses[side(a, b)] < 2)
        fail("the piece of Edge" + std::to_string(p.edge_a) + " of " + faces[p.face_a].name + " shared with " +
             faces[p.face_b].name + " is open at " + at(out.nodes[a]));
    }
  }
  // No node left beside a shared node: a piece shared but not found so.
  // Two nodes of one face's mesh are two on purpose (the ends of an edge
  // shorter than a loose file's tolerance: CrankArm.brep face 24's 0.076
  // edge beside a tolerance of 0.095), so only nodes of no common face count.
  // Nodes in cells of the tolerance's size; a shared node's neighbours are
  // in its cell and the 26 around it.
  std::vector<std::vector<int>> faces_of(out.nodes.size());
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int n : out.node_of[f])
      if (faces_of[n].empty() || faces_of[n].back() != static_cast<int>(f)) faces_of[n].push_back(static_cast<int>(f));
  const auto share_a_face = [&](int a, int b) {
    for (int f : faces_of[a])
      if (std::find(faces_of[b].begin(), faces_of[b].end(), f) != faces_of[b].end()) return true;
    return false;
  };
  std::map<std::array<long long, 3>, std::vector<int>> cells;
  const auto cell = [&](const Point3& p) {
    return std::array<long long, 3>{static_cast<long long>(std::floor(p[0] / tolerance)),
                                    static_cast<long long>(std::floor(p[1] / tolerance)),
                                    static_cast<long long>(std::floor(p[2] / tolerance))};
  };
  for (std::size_t n = 0; n < out.nodes.size(); ++n) cells[cell(out.nodes[n])].push_back(static_cast<int>(n));
  for (std::size_t a = 0; a < out.nodes.size(); ++a) {
    if (!shared_node[a]) continue;
    const auto c = cell(out.nodes[a]);
    for (long long dx = -1; dx <= 1; ++dx) {
      for (long long dy = -1; dy <= 1; ++dy) {
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (found == cells.end()) continue;
          for (int b : found->second) {
            if (b != static_cast<int>(a) && distance3(out.nodes[a], out.nodes[b]) <= tolerance &&
                !share_a_face(static_cast<int>(a), b))
              fail("nodes " + std::to_string(a + 1) + " and " + std::to_string(b + 1) + " at " + at(out.nodes[a]) +
                   " are one point but were not joined");
          }
        }
      }
    }
  }
  return out;
}

}  // namespace mm

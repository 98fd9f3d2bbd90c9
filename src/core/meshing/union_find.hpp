#pragma once
// The root of x's set in a union-find forest (parent[x] == x at a root),
// halving the path on the way: nodes that are one point, joined.
#include <vector>

namespace mm {

inline int find_root(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace mm

#pragma once
// The exact nearest boundary place to any point, for checking a medial axis
// (and later stages): nearest samples from a grid, refined on the curves.
#include <memory>

#include "medial/nearest.hpp"

namespace mm {

class NearestBoundary {
 public:
  explicit NearestBoundary(const BoundaryIndex& index);
  ~NearestBoundary();
  BoundaryPlace nearest(Vec2 p) const;

 private:
  struct Samples;
  const BoundaryIndex& index_;
  std::unique_ptr<Samples> samples_;
  double spacing_ = 0.0;  // the largest gap between samples along straight stretches
};

}  // namespace mm

// The controls the corner terms (corner_terms.hpp) and the node solve
// (nodal_solver.hpp) share: the order of the reconstruction at the nodes and
// how the node sums gather the corners' M_cp and B_cp (docs/method.md §A4).
#pragma once

namespace lagremap {

enum class Gather { Crs, Atomics };

struct CornerControls {
  int order = 2;  // 1: piecewise constant, 2: limited linear reconstruction
  Gather gather = Gather::Crs;
};

}  // namespace lagremap

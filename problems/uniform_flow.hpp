// The box a uniform flow crosses in remap mode, shared by the problems whose
// exact solution is their initial state translated at the flow's velocity
// (`advection`, problems/advection.cpp; `bump`, problems/bump.cpp): a slab
// (one cell thick in z, open in x and y) or a bar (one row of cells along x),
// whose open sides carry the flow's pressure p0 as a traction (what flows in
// is the boundary cell's own state, docs/method.md §5.8), the other sides
// symmetry planes. Uniform velocity and pressure stay uniform; only the
// densities move.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "../src/problem.hpp"

namespace lagremap {

struct FlowBox {
  bool two_d = true;          // a slab in x-y; false: a bar along x
  double length = 0.0;        // along x (and y for a slab)
  double height = 0.0;        // along y: length for a slab, one cell for a bar
  double thickness = 0.0;     // along z, one cell
  double dx = 0.0, dy = 0.0;  // the (uniform) cell's sides in x and y
  // The area the L1 integrals are divided by (a slab's thickness, a bar's y-z section).
  double crossSection() const { return two_d ? thickness : height * thickness; }
};

// domain.length, geometry.thickness (a cell length: --scale keeps the cells
// cubic), the mesh (cells x cells x 1, or cells x 1 x 1 for a bar) and the
// boundaries: traction sigma = -p0 I on the open sides.
void declareFlowBox(Config& config, bool two_d, double length, int cells, double thickness,
                    double p0);
// The box of the keys; throws ConfigError naming `problem` for a
// non-positive size or an open side that is not a traction of sigma = -p0 I
// (the state would not stay uniform).
FlowBox readFlowBox(const Config& config, const std::string& problem, bool two_d, double p0);
// The box's mesh (setupBlock) with the problem's materials and its cells' shapes.
ProblemSetup setupFlowBox(const Config& config, const FlowBox& box,
                          std::vector<MaterialParams> materials, CellShapes& shapes);

// L1 errors of the final state against the flow's exact solution: velocity
// v0 and pressure p0 everywhere, and the density exact_density(c) of cell c
// (owned cells; summed exactly over the ranks, collective where the fields
// are distributed). Velocity: |V - v0| on a slab, the x-component's
// difference on a bar. `what`: the exact density, for the note.
L1Errors flowL1Errors(const FinalFields& fields, const FlowBox& box, const Vec3& v0, double p0,
                      const std::function<double(Index)>& exact_density, const std::string& what);

}  // namespace lagremap

#include "uniform_flow.hpp"

#include <cmath>
#include <utility>

#include "../src/exact_sum.hpp"

namespace lagremap {

void declareFlowBox(Config& config, bool two_d, double length, int cells, double thickness,
                    double p0) {
  config.addReal("domain.length", length, "m", "fixed mesh extent along x (and y for a slab)");
  config.addCellLength("geometry.thickness", thickness, "slab thickness along z (one cell)");
  if (two_d) {
    declareMeshKeys(config, cells, cells, 1);
    declareBoundaryKeys(config,
                        {"traction", "traction", "traction", "traction", "symmetry", "symmetry"});
  } else {
    declareMeshKeys(config, cells, 1, 1);
    declareBoundaryKeys(config,
                        {"traction", "traction", "symmetry", "symmetry", "symmetry", "symmetry"});
  }
  for (int side = 0; side < (two_d ? 4 : 2); ++side) {
    declareTractionKeys(config, side, SymMat3{-p0, -p0, -p0, 0, 0, 0});  // (tension > 0)
  }
}

FlowBox readFlowBox(const Config& config, const std::string& problem, bool two_d, double p0) {
  FlowBox box;
  box.two_d = two_d;
  box.length = config.real("domain.length");
  box.thickness = config.real("geometry.thickness");
  if (!(box.thickness > 0 && box.length > 0)) {
    throw ConfigError(problem + ": need geometry.thickness > 0 and domain.length > 0");
  }
  box.dx = box.length / double(config.integer("mesh.nx"));
  box.height = two_d ? box.length : box.dx;
  box.dy = box.height / double(config.integer("mesh.ny"));
  const char* sides[4] = {"xmin", "xmax", "ymin", "ymax"};
  for (int side = 0; side < (two_d ? 4 : 2); ++side) {
    const std::string prefix = std::string("bc.") + sides[side];
    if (config.text(prefix) != "traction" || config.real(prefix + ".sigma_xx") != -p0 ||
        config.real(prefix + ".sigma_yy") != -p0 || config.real(prefix + ".sigma_zz") != -p0 ||
        config.real(prefix + ".sigma_xy") != 0.0 || config.real(prefix + ".sigma_yz") != 0.0 ||
        config.real(prefix + ".sigma_xz") != 0.0) {
      throw ConfigError(problem + ": " + prefix +
                        " must be a traction of the gas pressure (sigma = -gas.p I)");
    }
  }
  return box;
}

ProblemSetup setupFlowBox(const Config& config, const FlowBox& box,
                          std::vector<MaterialParams> materials, CellShapes& shapes) {
  return setupBlock(config, {0, 0, 0}, {box.length, box.height, box.thickness},
                    std::move(materials), shapes);
}

L1Errors flowL1Errors(const FinalFields& fields, const FlowBox& box, const Vec3& v0, double p0,
                      const std::function<double(Index)>& exact_density, const std::string& what) {
  std::vector<ExactSum> l1(3);  // rho, V, p
  const double per_area = 1.0 / box.crossSection();
  const Index n_cells = Index(fields.rho.extent(0));
  for (Index c = 0; c < n_cells; ++c) {
    if (!fields.counts(c)) continue;
    const double weight = fields.vol(c) * per_area;
    const double dv[3] = {fields.v(c, 0) - v0.x, fields.v(c, 1) - v0.y, fields.v(c, 2) - v0.z};
    const double velocity =
        box.two_d ? std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]) : std::abs(dv[0]);
    l1[0] += weight * std::abs(fields.rho(c) - exact_density(c));
    l1[1] += weight * velocity;
    l1[2] += weight * std::abs(fields.p(c) - p0);
  }
  if (fields.distributed) ExactSum::sumOverRanks(l1);
  const std::string note =
      box.two_d
          ? "integral over the slab of |q - q_exact| dV divided by its thickness (kg/m, m^3/s, "
            "Pa m^2); velocity: |V - V_exact|; exact: uniform V and p, "
          : "integral over the bar of |q - q_exact| dV divided by its cross-section area "
            "(kg/m^2, m^2/s, Pa m); velocity: the x-component; exact: uniform V and p, ";
  return {l1[0].value(), l1[1].value(), l1[2].value(), note + what};
}

}  // namespace lagremap

// Set-up helpers: a block mesh for this rank, the cells' shapes on the
// host, and material regions filled from shapes.
#include <algorithm>
#include <utility>
#include <vector>

#include "../kernels/hex.hpp"
#include "../src/problem.hpp"

namespace lagremap {

void hostCellShapes(const HostMesh& mesh, std::vector<double>& volume,
                    std::vector<Vec3>& centroid) {
  const Index n_cells = Index(mesh.cell_nodes.extent(0));
  volume.resize(n_cells);
  centroid.resize(n_cells);
  for (Index c = 0; c < n_cells; ++c) {
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(mesh.x_n, mesh.cell_nodes(c, p));
    const hex::CellShape shape = hex::cellShape(x);
    volume[c] = shape.volume;
    centroid[c] = shape.centroid;
  }
}

void fillMaterialRegions(ProblemSetup& setup, const MaterialRegions& regions,
                         int samples_per_edge) {
  const Kokkos::Timer timer;
  const HostMesh mesh = copyToHost(setup.mesh);
  const Index n_cells = setup.mesh.n_cells;
  const int n_materials = int(setup.materials.size());
  InitialCells& cells = setup.cells;
  cells = InitialCells();
  cells.alpha_k.assign(std::size_t(n_cells) * n_materials, 0.0);
  cells.rho_k.assign(std::size_t(n_cells) * n_materials, 0.0);
  cells.e_k.assign(std::size_t(n_cells) * n_materials, 0.0);
  cells.v.assign(std::size_t(n_cells), Vec3{0, 0, 0});
  const int n = samples_per_edge;
  std::vector<double> weight_k(static_cast<std::size_t>(n_materials));
  for (Index c = 0; c < n_cells; ++c) {
    Vec3 x[8];
    for (int p = 0; p < 8; ++p) x[p] = loadVec3(mesh.x_n, mesh.cell_nodes(c, p));
    std::fill(weight_k.begin(), weight_k.end(), 0.0);
    Vec3 momentum{0, 0, 0};
    double mass = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          // Trilinear map of VTK hexahedron nodes (0..3 at zeta = 0, 4..7 at zeta = 1).
          const double a = (i + 0.5) / n, b = (j + 0.5) / n, g = (k + 0.5) / n;
          const double w[8] = {(1 - a) * (1 - b) * (1 - g),
                               a * (1 - b) * (1 - g),
                               a * b * (1 - g),
                               (1 - a) * b * (1 - g),
                               (1 - a) * (1 - b) * g,
                               a * (1 - b) * g,
                               a * b * g,
                               (1 - a) * b * g};
          Vec3 point{0, 0, 0}, dxa{0, 0, 0}, dxb{0, 0, 0}, dxg{0, 0, 0};
          for (int p = 0; p < 8; ++p) point += w[p] * x[p];
          dxa = (1 - b) * (1 - g) * (x[1] - x[0]) + b * (1 - g) * (x[2] - x[3]) +
                (1 - b) * g * (x[5] - x[4]) + b * g * (x[6] - x[7]);
          dxb = (1 - a) * (1 - g) * (x[3] - x[0]) + a * (1 - g) * (x[2] - x[1]) +
                (1 - a) * g * (x[7] - x[4]) + a * g * (x[6] - x[5]);
          dxg = (1 - a) * (1 - b) * (x[4] - x[0]) + a * (1 - b) * (x[5] - x[1]) +
                a * b * (x[6] - x[2]) + (1 - a) * b * (x[7] - x[3]);
          const double jacobian = dot(dxa, cross(dxb, dxg));
          const int material = regions.material_at(point);
          if (material < 0 || material >= n_materials) {
            throw std::logic_error("problem set-up: a point has no material");
          }
          weight_k[material] += jacobian;
          mass += jacobian * regions.rho[material];
          momentum += (jacobian * regions.rho[material]) * regions.velocity(material, point);
        }
    double total = 0.0;
    for (double weight : weight_k) total += weight;
    for (int m = 0; m < n_materials; ++m) {
      const std::size_t at = std::size_t(c) * n_materials + m;
      cells.alpha_k[at] = weight_k[m] / total;
      cells.rho_k[at] = regions.rho[m];
      cells.e_k[at] = regions.e[m];
    }
    cells.v[c] = (1.0 / mass) * momentum;
  }
  setup.sample_seconds += timer.seconds();
}

ProblemSetup setupBlock(const Config& config, const Vec3& lo, const Vec3& hi,
                        std::vector<MaterialParams> materials, CellShapes& shapes,
                        std::function<Vec3(const Vec3&)> mapping) {
  BlockSpec block;
  block.nx = int(config.integer("mesh.nx"));
  block.ny = int(config.integer("mesh.ny"));
  block.nz = int(config.integer("mesh.nz"));
  block.lo = lo;
  block.hi = hi;
  block.mapping = std::move(mapping);
  block.part = thisRanksPart(block.nx, block.ny, block.nz);
  ProblemSetup setup;
  setup.mesh = buildBlockMesh(block, readBoundaries(config));
  setup.materials = std::move(materials);
  hostCellShapes(copyToHost(setup.mesh), shapes.volume, shapes.centroid);
  return setup;
}

}  // namespace lagremap

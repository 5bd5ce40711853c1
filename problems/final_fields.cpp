// Final-field analysis problems share (a material's front, alpha crossings
// along a ray, half crossings) and the writers of their result files, in
// cell order on any rank count.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "../src/outputs.hpp"
#include "../src/problem.hpp"

namespace lagremap {

std::vector<double> recordsOfAllRanks(const FinalFields& fields, std::vector<double> mine) {
  return fields.distributed ? parallel::gatherOnAll(mine) : mine;
}

double materialFrontX(const FinalFields& fields, int material, double y_line) {
  const Index n_cells = Index(fields.x_c.extent(0));
  // The row of cells whose centroids are nearest to the line (on a line
  // between two rows, the one above it): the first such cell in global order.
  double row_y = NAN, best = INFINITY;
  long best_cell = -1;
  for (Index c = 0; c < n_cells; ++c) {
    if (!fields.counts(c)) continue;
    const double dy = fields.x_c(c, 1) - y_line;
    const double distance = std::abs(dy) - (dy >= 0.0 ? 1e-12 * (1.0 + std::abs(y_line)) : 0.0);
    if (distance < best) {
      best = distance;
      best_cell = fields.globalCell(c);
      row_y = fields.x_c(c, 1);
    }
  }
  if (fields.distributed) {  // (distance, global id, y) of each rank's nearest cell
    const std::vector<double> nearest = parallel::gatherOnAll({best, double(best_cell), row_y});
    for (std::size_t r = 0; r < nearest.size(); r += 3) {
      const bool nearer = nearest[r] < best || (nearest[r] == best && nearest[r + 1] < best_cell);
      if (nearest[r + 1] >= 0 && nearer) {
        best = nearest[r];
        best_cell = long(nearest[r + 1]);
        row_y = nearest[r + 2];
      }
    }
  }
  std::vector<double> mine;  // (x, alpha) of the row's cells
  for (Index c = 0; c < n_cells; ++c) {
    if (fields.counts(c) && std::abs(fields.x_c(c, 1) - row_y) <= 1e-9 * (1.0 + std::abs(row_y))) {
      mine.insert(mine.end(), {fields.x_c(c, 0), fields.alpha(c, material)});
    }
  }
  return outwardHalfCrossing(fields, mine);
}

double outwardHalfCrossing(const FinalFields& fields, const std::vector<double>& mine) {
  const std::vector<double> records = recordsOfAllRanks(fields, mine);
  std::vector<std::pair<double, double>> row;  // (coordinate, alpha)
  for (std::size_t i = 0; i + 1 < records.size(); i += 2) {
    row.emplace_back(records[i], records[i + 1]);
  }
  std::sort(row.begin(), row.end());
  for (std::size_t i = row.size(); i-- > 1;) {
    const auto [x1, a1] = row[i];
    const auto [x0, a0] = row[i - 1];
    if (a0 >= 0.5 && a1 < 0.5) return x0 + (a0 - 0.5) / (a0 - a1) * (x1 - x0);
  }
  return NAN;
}

namespace {

// The cell centres of a uniform slab: cell (i, j)'s is first + i dx + j dy,
// read from global cells 0, 1 and nx (from their owners on distributed fields).
struct SlabCentres {
  Vec3 first;
  double dx = 0.0, dy = 0.0;
};

SlabCentres slabCentres(const FinalFields& fields) {
  const long nx = fields.nx;
  std::vector<double> mine;  // (global id, x, y) of cells 0, 1 and nx
  for (Index c = 0; c < Index(fields.x_c.extent(0)); ++c) {
    const long cell = fields.globalCell(c);
    if (fields.counts(c) && (cell == 0 || cell == 1 || cell == nx)) {
      mine.insert(mine.end(), {double(cell), fields.x_c(c, 0), fields.x_c(c, 1)});
    }
  }
  double x[3] = {NAN, NAN, NAN}, y[3] = {NAN, NAN, NAN};
  const std::vector<double> records = recordsOfAllRanks(fields, mine);
  for (std::size_t r = 0; r < records.size(); r += 3) {
    const long cell = long(records[r]);
    const int which = cell == 0 ? 0 : cell == 1 ? 1 : 2;
    x[which] = records[r + 1];
    y[which] = records[r + 2];
  }
  return {{x[0], y[0], 0.0}, x[1] - x[0], y[2] - y[0]};
}

// The bilinear stencil of the point (x, y) among the centres: cells (i, j)
// to (i + 1, j + 1) with weights from a and b; constant beyond the outer centres.
struct SlabStencil {
  int i, j;
  double a, b;
};

SlabStencil stencilAt(const SlabCentres& centres, int nx, int ny, double x, double y) {
  const double fi = std::clamp((x - centres.first.x) / centres.dx, 0.0, double(nx - 1));
  const double fj = std::clamp((y - centres.first.y) / centres.dy, 0.0, double(ny - 1));
  const int i = std::min(int(fi), nx - 2), j = std::min(int(fj), ny - 2);
  return {i, j, fi - i, fj - j};
}

}  // namespace

std::vector<AlphaCrossing> alphaCrossingsAlongRay(const FinalFields& fields, int material,
                                                  const Vec3& origin, const Vec3& direction) {
  const int nx = fields.nx, ny = fields.ny;
  if (fields.nz != 1 || nx < 2 || ny < 2) {
    throw std::logic_error(
        "alphaCrossingsAlongRay: needs a slab one cell thick, 2 x 2 cells or more");
  }
  const SlabCentres centres = slabCentres(fields);
  const double dx = centres.dx, dy = centres.dy;
  const double length = std::hypot(direction.x, direction.y);
  const double ux = direction.x / length, uy = direction.y / length;
  const double step = 0.125 * std::min(dx, dy);
  // the block's extent; outside the outer centroids the values are constant
  const double lo_x = centres.first.x - 0.5 * dx, hi_x = centres.first.x + (nx - 0.5) * dx;
  const double lo_y = centres.first.y - 0.5 * dy, hi_y = centres.first.y + (ny - 0.5) * dy;
  // The samples: the origin, then every `step` until the ray leaves the block.
  std::vector<std::pair<double, SlabStencil>> samples{
      {0.0, stencilAt(centres, nx, ny, origin.x, origin.y)}};
  for (double s = step;; s += step) {
    const double x = origin.x + s * ux, y = origin.y + s * uy;
    if (x < lo_x || x > hi_x || y < lo_y || y > hi_y) break;  // out of the block
    samples.emplace_back(s, stencilAt(centres, nx, ny, x, y));
  }
  // The volume fractions of the samples' cells: the whole block's, or the
  // cells the samples read, from their owners.
  std::unordered_map<long, double> alpha_near;
  if (fields.distributed) {
    std::vector<long> wanted;
    for (const auto& [s, at] : samples)
      for (int jj : {at.j, at.j + 1})
        for (int ii : {at.i, at.i + 1}) wanted.push_back(ii + long(nx) * jj);
    std::sort(wanted.begin(), wanted.end());
    std::vector<double> mine;  // (global id, alpha)
    for (Index c = 0; c < Index(fields.alpha.extent(0)); ++c) {
      const long cell = fields.globalCell(c);
      if (fields.counts(c) && std::binary_search(wanted.begin(), wanted.end(), cell)) {
        mine.insert(mine.end(), {double(cell), fields.alpha(c, material)});
      }
    }
    const std::vector<double> records = parallel::gatherOnAll(mine);
    for (std::size_t r = 0; r < records.size(); r += 2)
      alpha_near[long(records[r])] = records[r + 1];
  }
  const auto value = [&](int ii, int jj) {
    const long cell = ii + long(nx) * jj;
    return fields.distributed ? alpha_near.at(cell) : fields.alpha(cell, material);
  };
  const auto alphaAt = [&](const SlabStencil& at) {
    const double a = at.a, b = at.b;
    return (1 - a) * (1 - b) * value(at.i, at.j) + a * (1 - b) * value(at.i + 1, at.j) +
           (1 - a) * b * value(at.i, at.j + 1) + a * b * value(at.i + 1, at.j + 1);
  };
  std::vector<AlphaCrossing> crossings;
  double s0 = 0.0, a0 = alphaAt(samples.front().second);
  for (std::size_t n = 1; n < samples.size(); ++n) {
    const double s1 = samples[n].first, a1 = alphaAt(samples[n].second);
    if ((a0 - 0.5) * (a1 - 0.5) < 0.0 || (a1 == 0.5 && a0 != 0.5)) {
      crossings.push_back({s0 + (0.5 - a0) / (a1 - a0) * (s1 - s0), a1 > a0});
    }
    s0 = s1;
    a0 = a1;
  }
  return crossings;
}

void writeCellOutlines(const std::string& path, const FinalFields& fields) {
  std::ostringstream rows;  // keyed by global cell id
  rows << std::setprecision(8);
  for (Index c = 0; c < Index(fields.rho.extent(0)); ++c) {
    if (!fields.counts(c)) continue;
    rows << fields.globalCell(c) << ' ';
    for (int p = 0; p < 4; ++p) {
      const Index node = fields.mesh.cell_nodes(c, p);
      rows << fields.mesh.x_n(node, 0) << ',' << fields.mesh.x_n(node, 1) << ',';
    }
    rows << fields.rho(c) << '\n';
  }
  ResultFile csv(path);
  csv << "x0,y0,x1,y1,x2,y2,x3,y3,density\n";
  writeRowsInCellOrder(rows.str(), fields.distributed, csv);
  csv.write();
}

void ResultFile::write() const {
  if (!path_.empty()) writeTextFile(path_, str());
}

void writeRowsInCellOrder(const std::string& keyed_lines, bool distributed, std::ostream& out) {
  std::vector<parallel::KeyedLine> lines;
  std::istringstream in(keyed_lines);
  for (std::string line; std::getline(in, line);) {
    const std::size_t space = line.find(' ');
    lines.push_back({std::stol(line.substr(0, space)), line.substr(space + 1)});
  }
  std::sort(lines.begin(), lines.end(), [](const auto& a, const auto& b) { return a.key < b.key; });
  if (distributed) {
    parallel::writeMergedOnRoot(lines, &out);
  } else {
    for (const auto& line : lines) out << line.text << '\n';
  }
}

}  // namespace lagremap

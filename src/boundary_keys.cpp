#include "boundary_keys.hpp"

#include "input/config.hpp"

namespace lagremap {

const char* sideName(int side) {
  static const char* names[kNumSides] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  return names[side];
}

BoundaryKind parseBoundaryKind(const std::string& key, const std::string& text) {
  if (text == "free") return BoundaryKind::Free;
  if (text == "wall" || text == "symmetry") return BoundaryKind::Wall;
  if (text == "fixed") return BoundaryKind::Fixed;
  if (text == "traction") return BoundaryKind::Traction;
  throw ConfigError("bad boundary condition '" + abbreviated(text) + "' for key '" + key +
                    "': expected free|wall|symmetry|fixed|traction");
}

const char* boundaryKindName(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::Free:
      return "free";
    case BoundaryKind::Wall:
      return "wall";
    case BoundaryKind::Fixed:
      return "fixed";
    case BoundaryKind::Traction:
      return "traction";
  }
  return "?";
}

}  // namespace lagremap

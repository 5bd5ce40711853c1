// One allocation shared by work arrays whose lifetimes never overlap: typed
// Views are carved out of it one after another (the remap's work arrays and
// the Lagrangian step's corner arrays, RemapStep; docs/method.md §7.7).
#pragma once

#include <cstddef>
#include <stdexcept>

#include "types.hpp"

namespace lagremap {

class WorkArena {
 public:
  // Sizing only: carve() returns empty Views and counts what they would take.
  WorkArena() = default;
  // Carves from `memory` (throws when it is too small).
  explicit WorkArena(const RealView& memory) : memory_(memory) {}

  // The next View of type ViewType with these extents, at a 128-byte boundary.
  template <class ViewType, class... Extents>
  ViewType carve(Extents... extents) {
    const std::size_t bytes = ViewType::required_allocation_size(std::size_t(extents)...);
    const std::size_t start = used_;
    const std::size_t doubles = (bytes + sizeof(Real) - 1) / sizeof(Real);
    used_ += (doubles + kAlignment - 1) / kAlignment * kAlignment;
    if (memory_.data() == nullptr) return ViewType();
    if (used_ > memory_.extent(0)) throw std::logic_error("WorkArena: the memory is too small");
    return ViewType(memory_.data() + start, extents...);
  }
  // Doubles carved so far.
  std::size_t used() const { return used_; }

 private:
  static constexpr std::size_t kAlignment = 16;  // doubles
  RealView memory_;
  std::size_t used_ = 0;
};

}  // namespace lagremap

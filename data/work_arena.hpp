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

  // The next View of type ViewType with these extents, at a 128-byte
  // boundary and at its own place within a 4 KiB page: the k-th View starts
  // k x 640 bytes into a page after the first. (Arrays of one per-cell size
  // carved end to end start at the same place in a page when that size is a
  // multiple of 4 KiB, as taylor's 17,600 cells x 16 doubles are; a kernel
  // that reads or writes them at one index then hits one cache set and the
  // CPU's 4K-aliasing stall: the remap ran 1.5x slower.)
  template <class ViewType, class... Extents>
  ViewType carve(Extents... extents) {
    const std::size_t bytes = ViewType::required_allocation_size(std::size_t(extents)...);
    const std::size_t skew = (carved_ * kSkew) % kPage;
    const std::size_t start = used_ + (skew + kPage - used_ % kPage) % kPage;
    const std::size_t doubles = (bytes + sizeof(Real) - 1) / sizeof(Real);
    used_ = start + (doubles + kAlignment - 1) / kAlignment * kAlignment;
    ++carved_;
    if (memory_.data() == nullptr) return ViewType();
    if (used_ > memory_.extent(0)) throw std::logic_error("WorkArena: the memory is too small");
    return ViewType(memory_.data() + start, extents...);
  }
  // Doubles carved so far.
  std::size_t used() const { return used_; }

 private:
  static constexpr std::size_t kAlignment = 16;  // doubles: 128 bytes
  static constexpr std::size_t kPage = 512;      // doubles: 4 KiB
  static constexpr std::size_t kSkew = 80;       // doubles: 640 bytes, 32 places in a page
  RealView memory_;
  std::size_t used_ = 0, carved_ = 0;
};

}  // namespace lagremap

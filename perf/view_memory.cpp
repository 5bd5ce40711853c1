// A Kokkos tools library that takes the inventory of a run's Views: it follows
// every allocation and deallocation Kokkos reports (by label and memory space)
// and, at the end, writes the live bytes of each label at the moment the sum
// over all labels peaked. perf/memory.sh builds it and reads its output; it has
// no dependency but the C ABI of Kokkos' tools interface (stable since Kokkos 3):
//
//   KOKKOS_PROFILE_LIBRARY (Kokkos 3) or KOKKOS_TOOLS_LIBS (Kokkos 4) = libview_memory.so
//   LAGREMAP_VIEW_MEMORY_OUT = file to write (default: standard error)
//
// Output, one line per label with live bytes at the peak, largest first:
//   <bytes> <space> <label>
// after a first line "# peak <bytes> views <count>".
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace {

struct Allocation {
  std::string key;  // "<space> <label>"
  std::uint64_t bytes;
};

struct Inventory {
  std::mutex mutex;
  std::map<const void*, Allocation> live;
  std::map<std::string, std::uint64_t> bytes_by_key;
  std::uint64_t total = 0;
  std::uint64_t peak = 0;
  std::map<std::string, std::uint64_t> at_peak;
};

Inventory& inventory() {
  static Inventory* the_inventory = new Inventory;  // outlives static destruction
  return *the_inventory;
}

}  // namespace

// The tools interface's memory-space handle (Kokkos_Profiling_C_Interface.h).
struct Kokkos_Profiling_SpaceHandle {
  char name[64];
};

extern "C" {

void kokkosp_init_library(int, uint64_t, uint32_t, void*) {}

void kokkosp_allocate_data(const Kokkos_Profiling_SpaceHandle space, const char* label,
                           const void* const ptr, const uint64_t size) {
  Inventory& inv = inventory();
  std::lock_guard<std::mutex> lock(inv.mutex);
  std::string key = std::string(space.name) + " " + (label[0] != '\0' ? label : "(unlabelled)");
  inv.bytes_by_key[key] += size;
  inv.live[ptr] = Allocation{std::move(key), size};
  inv.total += size;
  if (inv.total > inv.peak) {
    inv.peak = inv.total;
    inv.at_peak = inv.bytes_by_key;
  }
}

void kokkosp_deallocate_data(const Kokkos_Profiling_SpaceHandle, const char*, const void* const ptr,
                             const uint64_t) {
  Inventory& inv = inventory();
  std::lock_guard<std::mutex> lock(inv.mutex);
  const auto found = inv.live.find(ptr);
  if (found == inv.live.end()) return;
  inv.bytes_by_key[found->second.key] -= found->second.bytes;
  inv.total -= found->second.bytes;
  inv.live.erase(found);
}

void kokkosp_finalize_library() {
  Inventory& inv = inventory();
  std::lock_guard<std::mutex> lock(inv.mutex);
  const char* path = std::getenv("LAGREMAP_VIEW_MEMORY_OUT");
  FILE* out = path != nullptr ? std::fopen(path, "w") : stderr;
  if (out == nullptr) return;
  std::vector<std::pair<std::uint64_t, std::string>> rows;
  for (const auto& [key, bytes] : inv.at_peak)
    if (bytes > 0) rows.emplace_back(bytes, key);
  std::sort(rows.rbegin(), rows.rend());
  std::fprintf(out, "# peak %llu views %zu\n", static_cast<unsigned long long>(inv.peak),
               rows.size());
  for (const auto& [bytes, key] : rows)
    std::fprintf(out, "%llu %s\n", static_cast<unsigned long long>(bytes), key.c_str());
  if (out != stderr) std::fclose(out);
}

}  // extern "C"

#include "resources.hpp"

#include <sys/resource.h>

namespace lagremap {

long peakResidentBytes() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return long(usage.ru_maxrss) * 1024L;  // Linux: kilobytes
}

}  // namespace lagremap

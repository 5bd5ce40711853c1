#include "resources.hpp"

#include <sys/resource.h>

#include <cstdlib>
#include <fstream>
#include <string>

namespace lagremap {

long peakResidentBytes() {
  struct rusage usage {};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return long(usage.ru_maxrss) * 1024L;  // Linux: kilobytes
}

long sharedResidentBytes() {
  std::ifstream status("/proc/self/status");
  long kilobytes = 0;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("RssFile:", 0) == 0 || line.rfind("RssShmem:", 0) == 0) {
      kilobytes += std::atol(line.c_str() + line.find(':') + 1);
    }
  }
  return kilobytes * 1024L;
}

}  // namespace lagremap

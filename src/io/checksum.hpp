// Checksums of what a checkpoint holds (docs/running.md §5): a flipped bit on disk
// must not restart a run with other fields. HDF5's own Fletcher32 filter
// would need chunked datasets, and it leaves the attributes (the loop's
// counters) unprotected; these hashes cover both and cost one 64-bit
// reduction per checkpoint.
#pragma once

#include <cstdint>
#include <cstring>

namespace lagremap::io {

// A bijection of 64-bit words that changes about half the output bits for
// any changed input bit (the output function of SplitMix64, Steele, Lea and
// Flood, OOPSLA 2014).
constexpr std::uint64_t scramble(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Hash of a sequence of 64-bit words. Each word enters through a bijection
// of the state, so two sequences that differ in one word (one flipped bit)
// always hash differently, not just almost always.
class WordHash {
 public:
  explicit WordHash(std::uint64_t seed = 0) : state_(scramble(seed)) {}
  void add(std::uint64_t word) { state_ = scramble(state_ ^ word); }
  void add(double value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    add(bits);
  }
  // The length, then the bytes eight at a time (the last word zero-padded).
  void addBytes(const void* bytes, std::size_t n) {
    add(std::uint64_t(n));
    const auto* p = static_cast<const unsigned char*>(bytes);
    for (std::size_t i = 0; i < n; i += 8) {
      std::uint64_t word = 0;
      std::memcpy(&word, p + i, n - i < 8 ? n - i : 8);
      add(word);
    }
  }
  std::uint64_t value() const { return state_; }

 private:
  std::uint64_t state_;
};

// Checksum of a table of rows that every partition of its rows over the
// ranks gives alike: the sum modulo 2^64 of each row's hash, seeded with its
// global row number (rows swapped or written to the wrong place change it
// too). Each rank adds the rows it owns; parallel::sum of the parts is the
// table's checksum, exact in any order since unsigned sums wrap.
class RowsChecksum {
 public:
  void add(std::int64_t row, const double* values, int n) {
    WordHash hash{std::uint64_t(row)};
    for (int j = 0; j < n; ++j) hash.add(values[j]);
    sum_ += hash.value();
  }
  std::uint64_t value() const { return sum_; }

 private:
  std::uint64_t sum_ = 0;
};

}  // namespace lagremap::io

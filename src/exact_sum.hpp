// Exact sums of doubles, the same bits whatever the order of the terms and
// however they are split over the ranks (host side; the problems' checks).
//
// A check summed over cells (a mass, an L1 norm, a radial bin) is computed
// by each rank over its owned cells and then combined: a floating-point sum
// would depend on the rank count in its last bits. Here every term is added
// exactly into a fixed-point integer that spans all finite doubles (32-bit
// digits in 64-bit words, positive and negative terms apart); integer
// addition is associative, so any order of the terms, and MPI's sum of the
// ranks' digits, gives one integer, which value() turns into a double the
// same way every time (within a few ulps of the exact sum).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace lagremap {

class ExactSum {
 public:
  // Adds a term exactly; a NaN or infinite term makes the sum NaN.
  void add(double term);
  ExactSum& operator+=(double term) {
    add(term);
    return *this;
  }
  // Adds another sum's terms (a thread's or a part's).
  ExactSum& operator+=(const ExactSum& other);
  // The sum, the same bits for the same terms in any order or split.
  double value() const;
  // Every rank's sum (collective; nothing on one rank).
  void sumOverRanks();
  // The same for several sums in one reduction.
  static void sumOverRanks(std::vector<ExactSum>& sums);

  // (32-bit digits; bit 0 of digit 0 is 2^-kLowestExponent: the last bit of
  // the smallest subnormal's 53-bit integer significand)
  static constexpr int kLowestExponent = 1126;
  static constexpr int kDigits = 70;  // 2,240 bits: every finite double and carry room

 private:
  void carry();                                     // each digit back into [0, 2^32)
  std::array<std::int64_t, 2 * kDigits> digits_{};  // positive terms, then negative
  long pending_ = 0;                                // terms since the last carry
  bool invalid_ = false;                            // a NaN or infinite term
};

}  // namespace lagremap

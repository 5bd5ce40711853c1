#include "exact_sum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "parallel.hpp"

namespace lagremap {

namespace {
constexpr std::int64_t kDigitMask = 0xffffffff;
// Each term adds less than 2^32 to a digit: 2^30 terms fit in 63 bits.
constexpr long kTermsBetweenCarries = 1L << 30;
}  // namespace

void ExactSum::add(double term) {
  if (term == 0.0) return;
  if (!std::isfinite(term)) {
    invalid_ = true;
    return;
  }
  // term = significand * 2^(exponent - 53), significand a 53-bit integer
  int exponent = 0;
  const double fraction = std::frexp(std::fabs(term), &exponent);
  const auto significand = std::int64_t(std::ldexp(fraction, 53));
  const int bit = exponent - 53 + kLowestExponent;  // of the significand's last bit
  const int digit = bit / 32, shift = bit % 32;
  std::int64_t* into = digits_.data() + (term < 0.0 ? kDigits : 0) + digit;
  // significand << shift, up to 84 bits, over three digits
  const std::uint64_t low = std::uint64_t(significand & kDigitMask) << shift;
  const std::uint64_t high = std::uint64_t(significand >> 32) << shift;
  into[0] += std::int64_t(low & kDigitMask);
  into[1] += std::int64_t(low >> 32) + std::int64_t(high & kDigitMask);
  into[2] += std::int64_t(high >> 32);
  if (++pending_ >= kTermsBetweenCarries) carry();
}

ExactSum& ExactSum::operator+=(const ExactSum& other) {
  ExactSum normal = other;
  normal.carry();
  carry();
  for (std::size_t i = 0; i < digits_.size(); ++i) digits_[i] += normal.digits_[i];
  invalid_ = invalid_ || other.invalid_;
  carry();
  return *this;
}

void ExactSum::carry() {
  for (int part = 0; part < 2; ++part) {
    std::int64_t* d = digits_.data() + part * kDigits;
    for (int i = 0; i + 1 < kDigits; ++i) {
      d[i + 1] += d[i] >> 32;
      d[i] &= kDigitMask;
    }
  }
  pending_ = 0;
}

double ExactSum::value() const {
  if (invalid_) return std::numeric_limits<double>::quiet_NaN();
  ExactSum normal = *this;
  normal.carry();
  const std::int64_t* positive = normal.digits_.data();
  const std::int64_t* negative = positive + kDigits;
  // the sign of positive - negative: the top digit where they differ
  int sign = 0;
  for (int i = kDigits - 1; i >= 0 && sign == 0; --i) {
    if (positive[i] != negative[i]) sign = positive[i] > negative[i] ? 1 : -1;
  }
  if (sign == 0) return 0.0;
  const std::int64_t* larger = sign > 0 ? positive : negative;
  const std::int64_t* smaller = sign > 0 ? negative : positive;
  // |positive - negative| digit by digit (with borrows), into a double from
  // the smallest digit up: a fixed order, so a fixed result
  double magnitude = 0.0;
  std::int64_t borrow = 0;
  for (int i = 0; i < kDigits; ++i) {
    std::int64_t digit = larger[i] - smaller[i] - borrow;
    borrow = digit < 0 ? 1 : 0;
    if (digit < 0) digit += kDigitMask + 1;
    if (digit != 0) magnitude += std::ldexp(double(digit), 32 * i - kLowestExponent);
  }
  return sign * magnitude;
}

void ExactSum::sumOverRanks() {
  std::vector<ExactSum> one{*this};
  sumOverRanks(one);
  *this = one[0];
}

void ExactSum::sumOverRanks(std::vector<ExactSum>& sums) {
  if (parallel::size() == 1 || sums.empty()) return;
  // every digit below 2^32 first: a sum over up to 2^31 ranks fits
  const std::size_t n = sums[0].digits_.size();
  std::vector<std::int64_t> digits(n * sums.size() + sums.size());
  for (std::size_t s = 0; s < sums.size(); ++s) {
    sums[s].carry();
    std::copy(sums[s].digits_.begin(), sums[s].digits_.end(), digits.begin() + long(s * n));
    digits[n * sums.size() + s] = sums[s].invalid_ ? 1 : 0;
  }
  parallel::sum(digits.data(), int(digits.size()));
  for (std::size_t s = 0; s < sums.size(); ++s) {
    std::copy(digits.begin() + long(s * n), digits.begin() + long((s + 1) * n),
              sums[s].digits_.begin());
    sums[s].invalid_ = digits[n * sums.size() + s] > 0;
    sums[s].carry();
  }
}

}  // namespace lagremap

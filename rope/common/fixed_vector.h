// SPDX-License-Identifier: MIT
#pragma once
// A vector of at most N values stored in place: the few control points around one knot that a
// removal plan or a removal check works on (d + 2 to d + 6 of them), made for every candidate knot of
// every step, where five heap buffers per candidate cost more than the arithmetic and kept a rope's
// steady state allocating (issue 13). The subset of std::vector's interface that
// KnotRemoval::apply and KnotInsertion::apply use. Exceeding N is a programming error: it throws
// std::length_error rather than write past the storage.
//
// Not API: internal to rope/ (not installed).

#include <array>
#include <cstddef>
#include <stdexcept>
#include <type_traits>

namespace rope {

template <class T, int N>
class FixedVector {
 public:
  using value_type = T;

  // The whole storage starts at zero, so that copies (which copy all of it) read nothing
  // uninitialised: an Eigen vector's default constructor leaves its coefficients unset.
  FixedVector() { values_.fill(zero()); }

  std::size_t size() const { return size_; }
  static constexpr std::size_t capacity() { return static_cast<std::size_t>(N); }

  T& operator[](std::size_t i) { return values_[i]; }
  const T& operator[](std::size_t i) const { return values_[i]; }
  T* data() { return values_.data(); }
  const T* data() const { return values_.data(); }
  T* begin() { return values_.data(); }
  T* end() { return values_.data() + size_; }
  const T* begin() const { return values_.data(); }
  const T* end() const { return values_.data() + size_; }

  template <class Iterator>
  void assign(Iterator first, Iterator last) {
    size_ = 0;
    for (; first != last; ++first) push_back(*first);
  }
  void resize(std::size_t count) {
    require(count);
    size_ = count;
  }
  void push_back(const T& value) {
    require(size_ + 1);
    values_[size_++] = value;
  }
  // Inserts value before position, shifting the rest right by one.
  T* insert(T* position, const T& value) {
    require(size_ + 1);
    const std::size_t at = static_cast<std::size_t>(position - values_.data());
    for (std::size_t i = size_; i > at; --i) values_[i] = values_[i - 1];
    values_[at] = value;
    ++size_;
    return values_.data() + at;
  }
  // Removes the value at position, shifting the rest left by one.
  T* erase(T* position) {
    const std::size_t at = static_cast<std::size_t>(position - values_.data());
    for (std::size_t i = at; i + 1 < size_; ++i) values_[i] = values_[i + 1];
    --size_;
    return values_.data() + at;
  }

 private:
  static T zero() {
    if constexpr (std::is_arithmetic_v<T>) {
      return T(0);
    } else {
      return T::Zero();  // Eigen types
    }
  }
  static void require(std::size_t count) {
    if (count > capacity()) throw std::length_error("rope::FixedVector: more values than its capacity");
  }
  std::array<T, N> values_;  // [0, size_) in use, the rest zero or stale
  std::size_t size_ = 0;
};

}  // namespace rope

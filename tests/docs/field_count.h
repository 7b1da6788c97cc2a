// SPDX-License-Identifier: MIT
#pragma once
// The number of fields of an aggregate, counted at compile time: the largest N for which T{x1, ..., xN}
// is well formed with arguments that convert to any type (the technique of Boost.PFR). A settings
// struct that gains a field then no longer matches the list of fields a test keeps for it.

#include <cstddef>
#include <type_traits>
#include <utility>

namespace rope::docs {

// Converts to any field type; only ever used in unevaluated contexts, so it needs no definition.
struct AnyField {
  template <class T>
  operator T() const;
};

template <class T, class Indices, class = void>
struct BraceInitializable : std::false_type {};

template <class T, std::size_t... I>
struct BraceInitializable<T, std::index_sequence<I...>, std::void_t<decltype(T{(void(I), AnyField{})...})>>
    : std::true_type {};

template <class T, std::size_t N = 0>
constexpr std::size_t fieldCount() {
  static_assert(std::is_aggregate_v<T>, "fieldCount needs an aggregate");
  if constexpr (BraceInitializable<T, std::make_index_sequence<N + 1>>::value) {
    return fieldCount<T, N + 1>();
  } else {
    return N;
  }
}

}  // namespace rope::docs

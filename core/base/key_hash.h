// Cache keys from the stage inputs themselves. Each options struct that shapes a
// cached result hashes its own fields, in one function next to its definition:
//
//   void hash_fields(KeyWriter& k, const FormFactorOptions& o);  // in form_factors.h
//
// which names every field that changes the result (k.field("rays_per_patch", ...))
// and says in a comment which ones it leaves out on purpose (thread counts, progress
// callbacks, file locations). Beside each definition,
//
//   static_assert(field_count<FormFactorOptions>() == 3, "...");
//
// stops the build when a field is added, so that whoever adds it decides whether it
// goes into the key; the tests then change each field in turn and check the key.
//
// KeyWriter appends a canonical text, one item a line: "name=" and a value that
// delimits itself (integers and doubles end at the newline, doubles in the shortest
// form that reads back exactly, strings length-prefixed, optionals marked, sequences
// counted, structs braced). So two different inputs never give the same text, and
// the text shows which field two keys differ in. The cache digests it (job/model_cache.cpp).
#pragma once

#include <Eigen/Core>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace ilp {

class KeyWriter;

namespace key_detail {

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};
template <class T>
struct is_vector : std::false_type {};
template <class T, class A>
struct is_vector<std::vector<T, A>> : std::true_type {};
template <class T>
struct is_pair : std::false_type {};
template <class A, class B>
struct is_pair<std::pair<A, B>> : std::true_type {};

// Converts to any field's type in a brace-initialisation that is only tested, never
// run: declared, not defined. From an rvalue only, so that for a std::optional member
// the conversion and optional's converting constructor tie (no initialisation, and no
// instantiation of that constructor, which does not compile for an Eigen type); such a
// member takes std::nullopt instead.
struct AnyField {
  template <class T>
  operator T() && noexcept;  // NOLINT: implicit on purpose
};

// An Eigen matrix or vector (deduces through the derived-to-base conversion only for
// Eigen types, without instantiating EigenBase<T> for others).
template <class D>
std::true_type eigen_probe(const Eigen::EigenBase<D>*);
std::false_type eigen_probe(...);
template <class T>
inline constexpr bool is_eigen = decltype(eigen_probe(static_cast<const T*>(nullptr)))::value;

// Fields are counted from the first: each takes an AnyField, else std::nullopt (an
// optional), else there is none.
template <class T, class... Fields>
constexpr std::size_t count_fields() {
  if constexpr (sizeof...(Fields) >= 256) {
    return sizeof...(Fields);
  } else if constexpr (requires { T{std::declval<Fields>()..., AnyField{}}; }) {
    return count_fields<T, Fields..., AnyField>();
  } else if constexpr (requires { T{std::declval<Fields>()..., std::nullopt}; }) {
    return count_fields<T, Fields..., std::nullopt_t>();
  } else {
    return sizeof...(Fields);
  }
}

}  // namespace key_detail

// The number of fields of an aggregate: the most initialisers T{...} accepts. For
// structs of plain fields (no base classes, C arrays or references): a field of a type
// no AnyField or std::nullopt initialises would end the count there.
template <class T>
consteval std::size_t field_count() {
  static_assert(std::is_aggregate_v<T> && !std::is_array_v<T>, "field_count: an aggregate struct");
  return key_detail::count_fields<T>();
}

class KeyWriter {
 public:
  // One named field: "name=" and its value. Names are identifiers (no '=' or newline).
  template <class T>
  KeyWriter& field(std::string_view name, const T& value) {
    text_.append(name);
    text_ += '=';
    return this->value(value);
  }

  // A value alone: bool, integer, enum, floating point, string, optional, vector,
  // pair, Eigen matrix, or a struct with a hash_fields(KeyWriter&, const T&) found by ADL.
  template <class T>
  KeyWriter& value(const T& v) {
    if constexpr (std::is_same_v<T, bool>) {
      text_ += v ? "b1\n" : "b0\n";
    } else if constexpr (std::is_enum_v<T>) {
      text_ += 'e';
      integer(static_cast<std::underlying_type_t<T>>(v));
    } else if constexpr (std::is_integral_v<T>) {
      text_ += std::is_signed_v<T> ? 'i' : 'u';
      integer(v);
    } else if constexpr (std::is_floating_point_v<T>) {
      real(static_cast<double>(v));
    } else if constexpr (std::is_convertible_v<const T&, std::string_view>) {
      const std::string_view s(v);
      text_ += 's';
      integer(s.size(), ':');
      text_.append(s);
      text_ += '\n';
    } else if constexpr (key_detail::is_optional<T>::value) {
      if (v) {
        text_ += "o+\n";
        value(*v);
      } else {
        text_ += "o-\n";
      }
    } else if constexpr (key_detail::is_vector<T>::value) {
      text_ += 'n';
      integer(v.size());
      for (const auto& item : v) value(item);
    } else if constexpr (key_detail::is_pair<T>::value) {
      value(v.first);
      value(v.second);
    } else if constexpr (key_detail::is_eigen<T>) {
      text_ += 'm';
      integer(v.rows(), 'x');
      integer(v.cols());
      for (Eigen::Index j = 0; j < v.cols(); ++j)
        for (Eigen::Index i = 0; i < v.rows(); ++i) real(static_cast<double>(v(i, j)));
    } else {
      text_ += "{\n";
      hash_fields(*this, v);
      text_ += "}\n";
    }
    return *this;
  }

  const std::string& text() const { return text_; }

 private:
  template <class I>
  void integer(I v, char end = '\n') {
    char buffer[24];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
    text_.append(buffer, static_cast<std::size_t>(r.ptr - buffer));
    text_ += end;
  }
  void real(double v) {
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);  // shortest that reads back exactly
    text_ += 'd';
    text_.append(buffer, static_cast<std::size_t>(r.ptr - buffer));
    text_ += '\n';
  }

  std::string text_;
};

// The canonical text of one value, e.g. for a test that compares keys.
template <class T>
std::string key_text_of(const T& value) {
  KeyWriter k;
  k.value(value);
  return k.text();
}

}  // namespace ilp

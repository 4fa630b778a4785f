// Checks that a struct's cache-key function covers the struct (core/base/key_hash.h):
// one case per field, as many as field_count<T>() finds, each changing that field
// alone; a field the key must see changes the key, one it leaves out on purpose (a
// thread count, a progress callback, a file location) does not. A field added to the
// struct without a case fails the count; a case whose field is not hashed fails the
// key comparison.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "core/base/key_hash.h"

namespace ilp::test {

template <class T>
struct FieldCase {
  std::string field;
  std::function<void(T&)> change;  // changes `field` alone
  bool in_key = true;              // false: left out of the key on purpose
};

// Left out of the key on purpose: changing the field must not change it.
template <class T>
FieldCase<T> left_out(std::string field, std::function<void(T&)> change) {
  return {std::move(field), std::move(change), false};
}

template <class T>
void expect_key_covers_fields(const char* type, const T& base, const std::vector<FieldCase<T>>& cases,
                              const std::function<std::string(const T&)>& key = key_text_of<T>) {
  EXPECT_EQ(cases.size(), field_count<T>())
      << type << " has " << field_count<T>() << " fields and the test " << cases.size()
      << " cases: give the new field a case (in the key, or left out on purpose)";
  const std::string base_key = key(base);
  EXPECT_EQ(key(base), base_key) << type << ": the key is a function of the value";
  std::set<std::string> seen;
  for (const FieldCase<T>& c : cases) {
    EXPECT_TRUE(seen.insert(c.field).second) << type << "." << c.field << ": two cases";
    T changed = base;
    c.change(changed);
    if (c.in_key)
      EXPECT_NE(key(changed), base_key) << type << "." << c.field
                                        << " changes the operator but not the key: hash it in its hash_fields";
    else
      EXPECT_EQ(key(changed), base_key) << type << "." << c.field << " is left out of the key on purpose, yet changes it";
  }
}

}  // namespace ilp::test

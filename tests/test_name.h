#pragma once
// GoogleTest names: letters, digits and '_' only, so case names such as gate_house.20k or
// psv:stack become test and folder names with every other character as '_'.
#include <cctype>
#include <string>

#include <gtest/gtest.h>

namespace shadowcts::test_support {

inline std::string test_name(std::string name) {
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

// The name generator of INSTANTIATE_TEST_SUITE_P over case names.
inline std::string param_test_name(const ::testing::TestParamInfo<std::string>& info) {
  return test_name(info.param);
}

}  // namespace shadowcts::test_support

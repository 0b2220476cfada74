// Test-only helpers for checking user-facing error messages and temporary files.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/model/scene_yaml.h"
#include "core/util/errors.h"

namespace disco::test_support {

// `msg` must start with `prefix` (e.g. "scene.yaml:12: key 'robots[0].mass': ") and
// contain `fragment`.
inline void expect_prefix(const std::string& msg, const std::string& prefix,
                          const std::string& fragment) {
  EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "expected prefix: " << prefix << "\n     got: " << msg;
  EXPECT_NE(msg.find(fragment), std::string::npos)
      << "expected fragment: " << fragment << "\n     got: " << msg;
}

// The InputError message of parsing scene `text` (as "s.yaml"), or "" if it loads.
inline std::string scene_error_of(const std::string& text) {
  try {
    parse_scene(text, "s.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A path in the temporary directory, unique to the running test.
inline std::string temp_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return (std::filesystem::temp_directory_path() /
          ("disco_" + std::string(info->name()) + "_" + name))
      .string();
}

}  // namespace disco::test_support

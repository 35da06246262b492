// The expectation every file-input error meets: the right code, and a one-line message that
// names the file and says what is wrong.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <initializer_list>
#include <string>

#include "tessera/error.hpp"

namespace tessera::test {

// Calls load(path) and expects Error(code) whose one-line message names the file and holds
// every one of `parts`.
template <typename Load>
void expect_file_error(Load&& load, const std::filesystem::path& path, ErrorCode code,
                       std::initializer_list<std::string> parts) {
  try {
    load(path);
    ADD_FAILURE() << "expected tessera::Error for " << path;
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.code(), code) << message;
    EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

}  // namespace tessera::test

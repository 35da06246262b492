// The expectation every argument or input error meets: the right code, and a message that
// holds the words naming what was wrong.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "tessera/error.hpp"

namespace tessera::test {

template <typename F>
void expect_error(F&& f, ErrorCode code, const std::string& words) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one naming " << words;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

}  // namespace tessera::test

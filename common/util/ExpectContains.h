#pragma once
// EXPECT_CONTAINS(text, part): a GoogleTest expectation that an error message (or any text)
// contains a part; on failure it prints the whole text. For *_test.cpp files only.

#include <string>

#include <gtest/gtest.h>

#define EXPECT_CONTAINS(haystack, needle)                                        \
    do {                                                                         \
        const std::string igiHaystack_ = (haystack);                             \
        EXPECT_NE(igiHaystack_.find(needle), std::string::npos)                  \
            << "'" << igiHaystack_ << "' does not contain '" << (needle) << "'"; \
    } while (0)

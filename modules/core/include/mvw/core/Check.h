#pragma once
// Checks for programmer bugs (never for bad input): print both values and abort.
#include <cstdlib>
#include <iostream>

#define MVW_CHECK(cond)                                                                  \
  do {                                                                                   \
    if (!(cond)) {                                                                       \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << std::endl; \
      std::abort();                                                                      \
    }                                                                                    \
  } while (0)

#define MVW_CHECK_OP(a, op, b)                                                                 \
  do {                                                                                         \
    const auto& mvw_a_ = (a);                                                                  \
    const auto& mvw_b_ = (b);                                                                  \
    if (!(mvw_a_ op mvw_b_)) {                                                                 \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #a " " #op " " #b << " (" \
                << mvw_a_ << " vs " << mvw_b_ << ")" << std::endl;                             \
      std::abort();                                                                            \
    }                                                                                          \
  } while (0)

#define MVW_CHECK_EQ(a, b) MVW_CHECK_OP(a, ==, b)
#define MVW_CHECK_LT(a, b) MVW_CHECK_OP(a, <, b)
#define MVW_CHECK_LE(a, b) MVW_CHECK_OP(a, <=, b)

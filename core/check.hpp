// check.hpp — programmer-invariant checks that print both operands.
//
// The first of the three error tiers of STYLE.md §10: a broken invariant is a bug in frontsteal, so it
// aborts with the expression, both operand values and the source location. Bad *input* never reaches these
// macros; it is reported as a recoverable exception naming what was wrong.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace frontsteal::detail {

[[noreturn]] inline void check_failed(const char* expr, const std::string& detail, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: FRONTSTEAL_CHECK failed: %s%s\n", file, line, expr, detail.c_str());
  std::fflush(stderr);
  std::abort();
}

template <class A, class B>
std::string describe_operands(const A& a, const B& b) {
  std::ostringstream out;
  out << " (left = " << a << ", right = " << b << ")";
  return out.str();
}

}  // namespace frontsteal::detail

#define FRONTSTEAL_CHECK(cond)                                                                 \
  do {                                                                                         \
    if (!(cond)) ::frontsteal::detail::check_failed(#cond, std::string(), __FILE__, __LINE__); \
  } while (0)

#define FRONTSTEAL_CHECK_OP(a, op, b)                                                                               \
  do {                                                                                                              \
    const auto& frontsteal_lhs_ = (a);                                                                              \
    const auto& frontsteal_rhs_ = (b);                                                                              \
    if (!(frontsteal_lhs_ op frontsteal_rhs_))                                                                      \
      ::frontsteal::detail::check_failed(#a " " #op " " #b,                                                         \
                                         ::frontsteal::detail::describe_operands(frontsteal_lhs_, frontsteal_rhs_), \
                                         __FILE__, __LINE__);                                                       \
  } while (0)

#define FRONTSTEAL_CHECK_EQ(a, b) FRONTSTEAL_CHECK_OP(a, ==, b)
#define FRONTSTEAL_CHECK_LE(a, b) FRONTSTEAL_CHECK_OP(a, <=, b)
#define FRONTSTEAL_CHECK_LT(a, b) FRONTSTEAL_CHECK_OP(a, <, b)

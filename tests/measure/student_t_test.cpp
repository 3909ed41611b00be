// student_t_test.cpp — Student's t quantiles against published tables, the closed forms for df = 1 and 2,
// symmetry, and the CDF and the quantile inverting each other.
#include "measure/student_t.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

namespace ms = frontsteal::measure;

namespace {

struct TableValue {
  double df, p, t;
};

}  // namespace

TEST_CASE("t quantiles match the published table to 1e-3", "[student_t]") {
  // Two-sided 95 % (p = .975) and one row at p = .8, from any t table (e.g. NIST/SEMATECH e-Handbook 1.3.6.7.2);
  // df = 1e6 is the normal quantile to the table's precision.
  const std::vector<TableValue> table = {
      {1, 0.975, 12.7062}, {2, 0.975, 4.3027},  {3, 0.975, 3.1824},    {5, 0.975, 2.5706},
      {10, 0.975, 2.2281}, {30, 0.975, 2.0423}, {1e6, 0.975, 1.95996}, {10, 0.8, 0.8791},
      {1, 0.995, 63.6567}, {4, 0.95, 2.1318},   {20, 0.9, 1.3253},     {1e6, 0.8, 0.8416},
  };
  for (const TableValue& v : table) {
    INFO("df " << v.df << "  p " << v.p << "  table " << v.t);
    CHECK(ms::student_t_quantile(v.p, v.df) == Approx(v.t).margin(1e-3));
  }
}

TEST_CASE("small df have heavier tails than the normal: a normal quantile would fail this", "[student_t]") {
  // The negative control for the table: the normal 1.96 is wrong by far more than the tolerance at small df.
  CHECK(std::fabs(ms::student_t_quantile(0.975, 3) - 1.95996) > 1.0);
  CHECK(std::fabs(ms::student_t_quantile(0.975, 10) - 1.95996) > 0.25);
  // The quantile falls toward the normal one as df grows.
  double previous = ms::student_t_quantile(0.975, 1);
  for (double df : {2.0, 3.0, 5.0, 10.0, 30.0, 100.0, 1e4}) {
    const double q = ms::student_t_quantile(0.975, df);
    INFO("df " << df);
    CHECK(q < previous);
    CHECK(q > 1.95996);
    previous = q;
  }
}

TEST_CASE("the CDF has the closed forms of df = 1 (Cauchy) and df = 2", "[student_t]") {
  const double pi = std::acos(-1.0);
  for (double t : {-30.0, -3.0, -1.0, -0.2, 0.0, 0.5, 1.0, 2.5, 12.0, 100.0}) {
    INFO("t " << t);
    CHECK(ms::student_t_cdf(t, 1) == Approx(0.5 + std::atan(t) / pi).margin(1e-12));
    CHECK(ms::student_t_cdf(t, 2) == Approx(0.5 + t / (2.0 * std::sqrt(2.0 + t * t))).margin(1e-12));
  }
}

TEST_CASE("quantiles below one half mirror those above, and the median is 0", "[student_t]") {
  for (double df : {1.0, 2.0, 3.0, 7.5, 29.0, 1e5}) {
    CHECK(ms::student_t_quantile(0.5, df) == 0.0);
    CHECK(ms::student_t_cdf(0.0, df) == Approx(0.5).margin(1e-15));
    for (double p : {0.001, 0.025, 0.1, 0.3, 0.49}) {
      INFO("df " << df << "  p " << p);
      const double q = ms::student_t_quantile(p, df);
      CHECK(q < 0);
      CHECK(q == Approx(-ms::student_t_quantile(1.0 - p, df)).epsilon(1e-12));
      CHECK(ms::student_t_cdf(-q, df) == Approx(1.0 - ms::student_t_cdf(q, df)).margin(1e-13));
    }
  }
}

TEST_CASE("the CDF and the quantile invert each other", "[student_t]") {
  for (double df : {1.0, 2.0, 3.0, 4.5, 10.0, 30.0, 200.0, 1e6}) {
    for (double p : {0.0005, 0.01, 0.1, 0.25, 0.6, 0.8, 0.9, 0.975, 0.995, 0.9995}) {
      INFO("df " << df << "  p " << p);
      CHECK(ms::student_t_cdf(ms::student_t_quantile(p, df), df) == Approx(p).margin(1e-9));
    }
    // |t| <= 4: beyond it the upper tail 1 - p falls below double's resolution near 1 at large df.
    for (double t : {-4.0, -2.0, -0.3, 0.7, 1.5, 4.0}) {
      INFO("df " << df << "  t " << t);
      CHECK(ms::student_t_quantile(ms::student_t_cdf(t, df), df) == Approx(t).epsilon(1e-7));
    }
    // The CDF rises with t (strictly, while the upper tail is above double's resolution near 1).
    double previous = 0;
    for (double t = -10; t <= 10; t += 0.25) {
      const double c = ms::student_t_cdf(t, df);
      INFO("df " << df << "  t " << t);
      CHECK(c >= previous);
      if (std::fabs(t) <= 5) CHECK(c > previous);
      CHECK(c <= 1.0);
      previous = c;
    }
  }
}

// talus/core/sample_statistics.hpp: the upper median and the power-law fit.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "talus/core/error.hpp"
#include "talus/core/sample_statistics.hpp"

namespace talus {
namespace {

TEST(SampleStatistics, UpperMedian) {
  EXPECT_EQ(upper_median({3.0, 1.0, 2.0}), 2.0);
  EXPECT_EQ(upper_median({4.0, 1.0, 3.0, 2.0}), 3.0);  // even: the upper middle value
  EXPECT_EQ(upper_median({7.5}), 7.5);
  EXPECT_EQ(upper_median({2.0, 2.0, 1.0, 9.0, 9.0}), 2.0);
  EXPECT_TRUE(std::isnan(upper_median({})));
}

TEST(SampleStatistics, PowerLawExponentOfAnExactPowerLaw) {
  std::vector<double> x, y;
  for (const double v : {1.0, 2.0, 5.0, 10.0, 40.0}) {
    x.push_back(v);
    y.push_back(3.0 * std::pow(v, 2.5));
  }
  EXPECT_NEAR(power_law_exponent(x, y), 2.5, 1e-12);
  // Two points: the slope through them.
  const std::vector<double> x2{10.0, 1000.0}, y2{4.0, 0.04};
  EXPECT_NEAR(power_law_exponent(x2, y2), -1.0, 1e-12);
}

TEST(SampleStatistics, PowerLawExponentIsTheLeastSquaresSlope) {
  // log y = (0, 1, 1) against log x = (0, 1, 2) (base e): slope 1/2.
  const double e = std::exp(1.0);
  const std::vector<double> x{1.0, e, e * e}, y{1.0, e, e};
  EXPECT_NEAR(power_law_exponent(x, y), 0.5, 1e-12);
}

TEST(SampleStatistics, PowerLawExponentRejectsBadInput) {
  const std::vector<double> one{1.0}, two{1.0, 2.0}, three{1.0, 2.0, 3.0};
  EXPECT_THROW(power_law_exponent(one, one), InputError);
  EXPECT_THROW(power_law_exponent(two, three), InputError);
  const std::vector<double> zero{0.0, 2.0}, negative{1.0, -2.0};
  EXPECT_THROW(power_law_exponent(zero, two), InputError);
  EXPECT_THROW(power_law_exponent(two, negative), InputError);
  const std::vector<double> same{3.0, 3.0};
  EXPECT_TRUE(std::isnan(power_law_exponent(same, two)));
}

}  // namespace
}  // namespace talus

// The profile CSV that `talus profile -o` and `talus plan` (trajectory.csv) write, and the
// checks every feasible one must pass, re-derived from the rows alone.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace talus::cli_test {

/// One parsed row of the profile CSV.
struct ProfileRow {
  double s, x, y, z, v, a, t, v_max;
  std::string binding;
};

/// Reads the CSV, checking the header and the column count of every row.
inline std::vector<ProfileRow> read_profile_csv(const std::string& file) {
  std::vector<ProfileRow> rows;
  for (const std::vector<std::string>& f : read_csv(file, "s,x,y,z,v,a,t,v_max,binding")) {
    ProfileRow r{};
    double* numbers[] = {&r.s, &r.x, &r.y, &r.z, &r.v, &r.a, &r.t, &r.v_max};
    for (std::size_t c = 0; c < 8; ++c) *numbers[c] = parse_number(f[c]);
    r.binding = f[8];
    rows.push_back(r);
  }
  return rows;
}

/// What a feasible profile's rows must satisfy on their own: it starts at s = t = 0 with
/// `start_speed`, ends at `length` [m] and `travel_time` [s] with `end_speed`, never exceeds
/// v_max, names a known binding constraint, and every step is one constant s'' from its speed to
/// the next (v1^2 = v0^2 + 2 a ds, t1 - t0 = 2 ds / (v0 + v1)).
inline void expect_consistent_rows(const std::vector<ProfileRow>& rows, double travel_time,
                                   double length, double start_speed, double end_speed) {
  static const std::set<std::string> kBindings = {"none",    "sliding",   "tipover",
                                                  "contact", "max_speed", "pitchover"};
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows.front().s, 0.0);
  EXPECT_EQ(rows.front().t, 0.0);
  EXPECT_DOUBLE_EQ(rows.back().t, travel_time);
  EXPECT_NEAR(rows.back().s, length, 1e-9 * (1.0 + rows.back().s));
  EXPECT_NEAR(rows.front().v, start_speed, 1e-9);
  EXPECT_NEAR(rows.back().v, end_speed, 1e-9);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const ProfileRow& r = rows[k];
    EXPECT_LE(r.v, r.v_max + 1e-9) << "station " << k;
    EXPECT_GE(r.v, 0.0) << "station " << k;
    EXPECT_TRUE(kBindings.count(r.binding)) << "station " << k << ": " << r.binding;
    EXPECT_EQ(std::isinf(r.v_max), r.binding == "none") << "station " << k;
    for (const double value : {r.s, r.x, r.y, r.z, r.v, r.a, r.t}) {
      EXPECT_TRUE(std::isfinite(value)) << "station " << k;
    }
    if (k == 0) continue;
    const ProfileRow& p = rows[k - 1];
    const double ds = r.s - p.s;
    EXPECT_GT(ds, 0.0) << "station " << k;
    EXPECT_GT(r.t, p.t) << "station " << k;
    EXPECT_NEAR(r.v * r.v, p.v * p.v + 2.0 * p.a * ds, 1e-7 * (1.0 + r.v * r.v)) << "station " << k;
    EXPECT_NEAR(r.t - p.t, 2.0 * ds / (p.v + r.v), 1e-9 * (r.t - p.t)) << "station " << k;
  }
}

}  // namespace talus::cli_test

// The time-series and node CSV rows (writeSeriesRow, Simulation::writeNodeRows; docs/cli.md
// columns) are built in memory with std::to_chars; they must read as a stream with
// std::setprecision(10) writes them, the format every table and reference file was made with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {
namespace {

// Numbers whose %.10g form has an exponent, ten significant digits, a sign of zero, a subnormal,
// an integral value and the non-finite forms.
const std::vector<double> kTricky = {0.1,
                                     -0.0,
                                     1.0 / 3.0,
                                     -2.0 / 3.0e-7,
                                     1e-300,
                                     std::numeric_limits<double>::denorm_min(),
                                     123456789012.0,
                                     -2.5e10,
                                     9.9999999995,
                                     1.0,
                                     65.82,
                                     std::numeric_limits<double>::max(),
                                     std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::quiet_NaN()};

// The row as an ostream writes it: the reference format.
std::string streamRow(const SeriesValues& v) {
  std::ostringstream s;
  s << std::setprecision(10) << v.t;
  for (const Eigen::Vector3d* x : {&v.payload, &v.payload_velocity, &v.cab, &v.jib_tip, &v.trolley})
    s << ',' << x->x() << ',' << x->y() << ',' << x->z();
  s << ',' << v.rope_top_tension << ',' << v.rope_length << ',' << v.slew_angle << ','
    << v.trolley_radius << ',' << v.energy << ',' << v.constraint_error << ',' << v.subdomains
    << ',' << v.tension_ratio << ',' << v.load_chart_ratio << ',' << v.warnings << ','
    << v.full_order_steps << ',' << (v.payload_landed ? 1 : 0) << ',' << v.contact_force;
  for (double sigma : v.stresses) s << ',' << sigma;
  s << '\n';
  return s.str();
}

TEST(SeriesCsv, RowsReadAsTheStreamWritesThem) {
  // Every column takes each tricky number in turn (shifted so that the row mixes them).
  const std::size_t n = kTricky.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto at = [&](std::size_t j) { return kTricky[(k + j) % n]; };
    SeriesValues v;
    v.t = at(0);
    v.payload = {at(1), at(2), at(3)};
    v.payload_velocity = {at(4), at(5), at(6)};
    v.cab = {at(7), at(8), at(9)};
    v.jib_tip = {at(10), at(11), at(12)};
    v.trolley = {at(13), at(14), at(0)};
    v.rope_top_tension = at(1);
    v.rope_length = at(2);
    v.slew_angle = at(3);
    v.trolley_radius = at(4);
    v.energy = at(5);
    v.constraint_error = at(6);
    v.subdomains = static_cast<int>(k) - 3;
    v.tension_ratio = at(7);
    v.load_chart_ratio = at(8);
    v.warnings = 1 << static_cast<int>(k);
    v.full_order_steps = 1234567890123L * static_cast<long>(k);
    v.payload_landed = k % 2 == 1;
    v.contact_force = at(9);
    v.stresses = {at(10), at(11), -at(12)};
    std::ostringstream row;
    writeSeriesRow(row, v);
    EXPECT_EQ(row.str(), streamRow(v)) << "row " << k;
  }
}

TEST(SeriesCsv, NodeRowsReadAsTheStreamWritesThem) {
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";
  const CraneModel m =
      buildCraneModel(loadScene(scene, {"rope.elements=12", "structure.model=rigid"}));
  std::unique_ptr<Simulation> sim = makeSimulation(m);
  sim->initialize();
  for (int k = 0; k < 3; ++k) sim->step();
  std::ostringstream expected, written;
  for (int j = 0; j < sim->ropeNodes(); ++j) {
    const Eigen::Vector3d r = sim->ropeNode(j);
    expected << std::setprecision(10) << sim->time() << ',' << j << ',' << r.x() << ',' << r.y()
             << ',' << r.z() << '\n';
  }
  sim->writeNodeRows(written);
  const std::string rows = written.str();
  EXPECT_EQ(rows, expected.str());
  EXPECT_EQ(std::count(rows.begin(), rows.end(), '\n'), sim->ropeNodes());
}

}  // namespace
}  // namespace crane_twin

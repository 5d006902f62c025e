// The result protocol's series names: built in one place, parsed back by the readers.
#include "core/results/series_names.hpp"

#include <gtest/gtest.h>

namespace tmlab {
namespace {

TEST(SeriesNames, VectorQuantitiesAreFourSeries) {
  SeriesTable t;
  series_names::add_vector(t, series_names::reaction("base"), "N", 3.0, 0.0, 4.0);
  series_names::add_vector(t, series_names::probe("tip"), "m", 1.0, 2.0, 2.0);
  std::vector<std::string> names;
  for (const auto& s : t.series()) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"reaction_base_x", "reaction_base_y", "reaction_base_z",
                                             "reaction_base_norm", "probe_tip_x", "probe_tip_y",
                                             "probe_tip_z", "probe_tip_norm"}));
  EXPECT_DOUBLE_EQ(t.last("reaction_base_norm"), 5.0);
  EXPECT_DOUBLE_EQ(t.last("probe_tip_norm"), 3.0);
  EXPECT_EQ(series_names::last_vector(t, series_names::probe("tip")), (std::array<double, 3>{1.0, 2.0, 2.0}));
}

TEST(SeriesNames, ReactionConditionsAreFoundByTheirXSeries) {
  const std::vector<std::string> names{
      "time",        "reaction_base_x",   "reaction_base_y", "reaction_x_x", "reaction__x",
      "probe_tip_x", "reaction_top_norm", "reaction_top_x",  "reaction_"};
  // "reaction__x" would be a condition with an empty name, which no case can declare: not one.
  EXPECT_EQ(series_names::reaction_conditions(names), (std::vector<std::string>{"base", "x", "top"}));
}

TEST(SeriesNames, ContactBodiesAreFoundByTheirForceXSeries) {
  const std::vector<std::string> names{"time",
                                       "contact_platen_force_x",
                                       "contact_platen_force_y",
                                       "contact_platen_area",
                                       "contact__force_x",
                                       "reaction_base_x",
                                       "contact_ball_force_x",
                                       "contact_force_x"};
  // "contact__force_x" would be a body with an empty name; "contact_force_x" has no body at all.
  EXPECT_EQ(series_names::contact_bodies(names), (std::vector<std::string>{"platen", "ball"}));
}

}  // namespace
}  // namespace tmlab

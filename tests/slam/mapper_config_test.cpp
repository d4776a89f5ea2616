// Validate(MapperConfig): the allowed values declared once in mapper_config_fields.hpp,
// enforced in slam whoever builds the config.
#include "slam/mapping/mapper_config.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "slam/mapping/mapper.hpp"

namespace lifelong::slam {
namespace {

TEST(MapperConfigValidate, TheDefaultsAreValid) {
  EXPECT_FALSE(Validate(MapperConfig{}).has_value());
}

TEST(MapperConfigValidate, NamesTheDottedFieldOutOfRange) {
  MapperConfig c;
  c.loops.min_score = 1.5;
  const auto problem = Validate(c);
  ASSERT_TRUE(problem.has_value());
  EXPECT_EQ(problem->fields, "loops.min_score");
  EXPECT_NE(problem->message.find("in [0, 1]"), std::string::npos) << problem->message;

  MapperConfig d;
  d.loops.verify.min_group = 0;
  ASSERT_TRUE(Validate(d).has_value());
  EXPECT_EQ(Validate(d)->fields, "loops.verify.min_group");

  MapperConfig e;
  e.grid.resolution_m = std::nan("");
  ASSERT_TRUE(Validate(e).has_value());
  EXPECT_EQ(Validate(e)->fields, "grid.resolution_m");
}

TEST(MapperConfigValidate, OrderAndChoicesAndPowersOfTwo) {
  MapperConfig c;
  c.loops.min_window_m = 3.0;
  c.loops.max_window_m = 2.0;
  ASSERT_TRUE(Validate(c).has_value());
  EXPECT_EQ(Validate(c)->fields, "loops.max_window_m");

  MapperConfig d;
  d.pruning.mode = {"oldest-first+chow-liu", "oldest-first", "chow-liu"};
  ASSERT_TRUE(Validate(d).has_value());
  EXPECT_EQ(Validate(d)->fields, "pruning.mode");

  MapperConfig e;
  e.incremental.matcher.coarse_factor = 12;
  ASSERT_TRUE(Validate(e).has_value());
  EXPECT_EQ(Validate(e)->fields, "incremental.matcher.coarse_factor");
}

TEST(MapperConfigValidate, BoundsAcrossSettings) {
  MapperConfig c;  // each in range, together a table of terabytes
  c.loops.max_window_m = 50.0;
  c.loops.matcher.resolution_m = 0.005;
  ASSERT_TRUE(Validate(c).has_value());
  EXPECT_NE(Validate(c)->fields.find("loops.max_window_m"), std::string::npos);

  MapperConfig d;
  d.loops.global.descriptor.rings = 200;
  d.loops.global.descriptor.sectors = 200;
  ASSERT_TRUE(Validate(d).has_value());
  EXPECT_EQ(Validate(d)->fields, "loops.global.rings, loops.global.sectors");
}

TEST(MapperConfigValidate, TheMapperRefusesAnInvalidConfig) {
  MapperConfig c;
  c.keyframes.min_translation_m = -1.0;
  try {
    Mapper mapper(c);
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("keyframes.min_translation_m"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace lifelong::slam

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "stage_references.hpp"

using namespace pbms;
using namespace pbms::coupler;

namespace {

std::map<std::string, StageResults> elastic_done(double e) {
  StageResults r;
  r.add_scalar("youngs_modulus_100", e, "GPa");
  r.add_column("isotherm", "pressure", "GPa", {0.0, 5.0});
  return {{"elastic", r}};
}

}  // namespace

// A scalar arrives in metal units (GPa to bar), a table as its columns.
TEST(StageReferences, ScalarsInMetalUnitsTablesAsColumns) {
  const YAML::Node params = YAML::Load(
      "{continuum: {youngs_modulus: {from: elastic.youngs_modulus_100}}, "
      "table: {from: elastic.isotherm}}");
  const YAML::Node out = resolve_references(params, elastic_done(98.0), "stages[2]");
  EXPECT_DOUBLE_EQ(out["continuum"]["youngs_modulus"].as<double>(), 98.0e4);
  EXPECT_EQ(out["table"]["pressure"]["unit"].as<std::string>(), "GPa");
}

// A NaN or infinite source is refused before the stage runs, naming the
// key that takes it, the source and its stage; a missing one as before.
TEST(StageReferences, ANonFiniteSourceIsAnErrorNamingTheKey) {
  const YAML::Node params =
      YAML::Load("{continuum: {youngs_modulus: {from: elastic.youngs_modulus_100}}}");
  for (const double bad : {std::nan(""), HUGE_VAL}) {
    try {
      (void)resolve_references(params, elastic_done(bad), "stages[2]");
      FAIL() << "no error for " << bad;
    } catch (const NonFiniteReference& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("stages[2].continuum.youngs_modulus: {from: elastic.youngs_modulus_100}"),
                std::string::npos)
          << m;
      EXPECT_NE(m.find("stage 'elastic' did not measure it"), std::string::npos) << m;
    }
  }
  const YAML::Node materials = YAML::Load(
      "{cu_j2: {kind: j2_plasticity, youngs_modulus: {from: elastic.youngs_modulus_100}}, "
      "later: {kind: j2_plasticity, youngs_modulus: {from: not_yet.e}}}");
  EXPECT_THROW((void)resolve_materials(materials, elastic_done(std::nan(""))), NonFiniteReference);
  const YAML::Node seen = resolve_materials(materials, elastic_done(98.0));
  EXPECT_TRUE(seen["cu_j2"]);
  EXPECT_FALSE(seen["later"]);  // its stage has not run: not this stage's material
  EXPECT_THROW((void)resolve_references(YAML::Load("{e: {from: elastic.missing}}"),
                                        elastic_done(98.0), "stages[2]"),
               Error);
}

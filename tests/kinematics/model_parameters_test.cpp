#include "host/kinematics/model_parameters.h"

#include <gtest/gtest.h>

#include "host/kinematics/model12.h"
#include "host/kinematics/model31.h"

namespace h4 {
namespace {

TEST(ModelParameters, LengthsOfBothModelsArePositiveLengths) {
  for (const char* name : {"h", "arm", "forearm", "R", "arm3", "forearm4"}) {
    EXPECT_TRUE(IsPositiveLengthParameter(name)) << name;
  }
  // Positions may be zero or negative: base joint positions, the offset d, frame translations.
  for (const char* name : {"d", "x2", "z4", "X_BC.tx", "alpha1"}) {
    EXPECT_FALSE(IsPositiveLengthParameter(name)) << name;
  }
}

TEST(ModelParameters, ModelAnglesAndFrameRotationsAreAngles) {
  for (const char* name : {"alpha", "alpha2", "q0", "q03", "psi1", "beta4"}) {
    EXPECT_TRUE(IsModelAngleParameter(name)) << name;
    EXPECT_TRUE(IsAngleParameter(name)) << name;
  }
  for (const char* name : {"X_BC.rx", "X_TE.rz"}) {
    EXPECT_FALSE(IsModelAngleParameter(name)) << name;
    EXPECT_TRUE(IsAngleParameter(name)) << name;
  }
  for (const char* name : {"X_BC.tx", "X_TE.tz", "h", "R", "d", "y3"}) {
    EXPECT_FALSE(IsAngleParameter(name)) << name;
  }
}

TEST(ModelParameters, EachModelsNamesAreItsTablesInOrderWithTheirUnits) {
  ASSERT_EQ(Model12ParameterTable().size(), host::Model12::ParameterNames().size());
  ASSERT_EQ(Model31ParameterTable().size(), 31u);
  for (size_t k = 0; k < Model31ParameterTable().size(); ++k) {
    EXPECT_EQ(Model31ParameterTable()[k].name, host::Model31::ParameterNames()[k]);
  }
  EXPECT_EQ(host::Model12::ParameterNames().front(), "h");
  EXPECT_EQ(host::Model31::ParameterNames().back(), "d");
  EXPECT_EQ(UnitOf(*ModelParameterKind("psi3")), "rad");
  EXPECT_EQ(UnitOf(*ModelParameterKind("x4")), "m");
  EXPECT_EQ(ModelParameterKind("X_BC.tx"), std::nullopt);
  EXPECT_EQ(ModelParameterKind("alpha5"), std::nullopt);
}

}  // namespace
}  // namespace h4

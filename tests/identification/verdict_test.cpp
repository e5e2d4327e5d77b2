// The verdict on an identification (host/identification/verdict.h): each case decided from
// the figures that define it, in the order the checks run.
#include "host/identification/verdict.h"

#include <gtest/gtest.h>

#include "tests/support/options_check.h"

namespace h4::host {
namespace {

// A Model 12 fit of 81 poses whose misfit is the camera noise.
VerdictInputs GoodFit() {
  VerdictInputs in;
  in.model = ModelKind::k12;
  in.poses_given = 81;
  in.poses_in_fit = 81;
  in.free_parameters = 21;
  in.residuals = 6 * 81;
  in.converged = true;
  in.has_covariance = true;
  in.chi2 = 1.02 * (in.residuals - in.free_parameters);
  in.condition_number = 300.0;
  in.position_misfit_m = 0.2e-3;
  return in;
}

Verdict Decide(const VerdictInputs& in, std::string* text = nullptr) {
  Verdict verdict = Verdict::kGood;
  const ResultVerdict result = DecideVerdict(in, VerdictOptions{}, &verdict);
  EXPECT_EQ(result.code, VerdictCode(verdict));
  EXPECT_FALSE(result.text.empty());
  if (text != nullptr) *text = result.text;
  return verdict;
}

TEST(VerdictTest, AFitWithinTheNoiseIsGood) { EXPECT_EQ(Decide(GoodFit()), Verdict::kGood); }

TEST(VerdictTest, AMisfitBeyondTheNoiseTellsModel12ToUseModel31) {
  VerdictInputs in = GoodFit();
  in.chi2 = 200.0 * (in.residuals - in.free_parameters);
  in.position_misfit_m = 3e-3;
  std::string text;
  EXPECT_EQ(Decide(in, &text), Verdict::kModelCannotDescribe);
  EXPECT_NE(text.find("Use Model 31"), std::string::npos) << text;
}

TEST(VerdictTest, TheChiSquareTestToleratesACameraCovarianceOffByLessThanTwo) {
  VerdictInputs in = GoodFit();
  in.chi2 = 2.5 * (in.residuals - in.free_parameters);  // sigma off by 1.6
  EXPECT_EQ(Decide(in), Verdict::kGood);
  in.chi2 = 4.0 * (in.residuals - in.free_parameters);
  EXPECT_EQ(Decide(in), Verdict::kModelCannotDescribe);
}

TEST(VerdictTest, ANegligibleMisfitBeyondAnOptimisticCovarianceIsStillGoodAndSaysSo) {
  // The live demo's rendered camera: Model 31 misses by 0.015 mm, chi-square / dof 3.1.
  VerdictInputs in = GoodFit();
  in.model = ModelKind::k31;
  in.chi2 = 3.13 * (in.residuals - in.free_parameters);
  in.position_misfit_m = 0.015e-3;
  std::string text;
  EXPECT_EQ(Decide(in, &text), Verdict::kGood);
  EXPECT_NE(text.find("optimistic"), std::string::npos) << text;
  in.position_misfit_m = 0.1e-3;  // 0.08 mm unexplained: not negligible
  EXPECT_EQ(Decide(in), Verdict::kModelCannotDescribe);
}

TEST(VerdictTest, ACentimetreMisfitOrPosesOutOfReachAreDataInconsistentWithTheRobot) {
  VerdictInputs in = GoodFit();
  in.chi2 = 1e5 * (in.residuals - in.free_parameters);
  in.position_misfit_m = 0.05;
  std::string text;
  EXPECT_EQ(Decide(in, &text), Verdict::kInconsistentWithApriori);
  EXPECT_NE(text.find("robot.yaml"), std::string::npos) << text;
  in = GoodFit();
  in.out_of_reach = 20;
  EXPECT_EQ(Decide(in), Verdict::kInconsistentWithApriori);
}

TEST(VerdictTest, ALengthMovedFarFromItsAprioriIsDataInconsistentWithTheRobot) {
  VerdictInputs in = GoodFit();
  in.largest_length_change = 0.999;  // arm: 260 read as metres
  in.largest_length_parameter = "arm";
  std::string text;
  EXPECT_EQ(Decide(in, &text), Verdict::kInconsistentWithApriori);
  EXPECT_NE(text.find("arm"), std::string::npos) << text;
}

TEST(VerdictTest, NoCovarianceOrAnIllConditionedFitIsNotIdentifiable) {
  VerdictInputs in = GoodFit();
  in.has_covariance = false;
  EXPECT_EQ(Decide(in), Verdict::kNotIdentifiable);
  in = GoodFit();
  in.condition_number = 1e7;
  EXPECT_EQ(Decide(in), Verdict::kNotIdentifiable);
}

TEST(VerdictTest, TenPosesAreTooFewWhateverTheirFit) {
  VerdictInputs in = GoodFit();
  in.poses_given = in.poses_in_fit = 10;
  in.residuals = 60;
  in.chi2 = 1e6;
  std::string text;
  EXPECT_EQ(Decide(in, &text), Verdict::kTooFewPoses);
  EXPECT_NE(text.find("10 in the fit"), std::string::npos) << text;
}

TEST(VerdictTest, ChiSquareUpperTailMatchesKnownQuantiles) {
  // chi2(100) 0.95 quantile 124.342, 0.999 quantile 149.449; chi2(10) 0.95 quantile 18.307.
  EXPECT_NEAR(ChiSquareUpperTail(124.342, 100), 0.05, 0.002);
  EXPECT_NEAR(ChiSquareUpperTail(149.449, 100), 0.001, 0.0002);
  EXPECT_NEAR(ChiSquareUpperTail(18.307, 10), 0.05, 0.003);
  EXPECT_NEAR(ChiSquareUpperTail(0.0, 10), 1.0, 1e-6);
}

TEST(VerdictTest, CodesParseBack) {
  for (Verdict v :
       {Verdict::kGood, Verdict::kModelCannotDescribe, Verdict::kInconsistentWithApriori,
        Verdict::kNotIdentifiable, Verdict::kTooFewPoses}) {
    EXPECT_EQ(ParseVerdictCode(VerdictCode(v)), v);
  }
  EXPECT_FALSE(ParseVerdictCode("usable"));
}

TEST(VerdictTest, InvalidOptionsAreRefusedWithAReason) {
  VerdictOptions options;
  options.significance = 0.0;
  EXPECT_TRUE(RefusedNaming(options, "significance"));
  EXPECT_TRUE(VerdictOptions{}.IsValid(nullptr));
}

}  // namespace
}  // namespace h4::host

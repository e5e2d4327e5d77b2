// Tests for firmware/render/render_options: the response curves give the published
// values, the presets are valid and differ as documented, text is parsed and out-of-range
// values are rejected with a message naming them.
#include "firmware/render/render_options.h"

#include <gtest/gtest.h>

namespace h4::cam {
namespace {

RenderOptions WithResponse(const std::string& text) {
  RenderOptions options;
  std::string why;
  EXPECT_TRUE(ParseResponseCurve(text, &options, &why)) << why;
  return options;
}

// Reference values of the sRGB encoding (IEC 61966-2-1): linear 0.5 encodes to 0.7354
// (8-bit 188), 18 % grey to 0.4614 (118); the linear toe ends at 0.0031308 -> 0.04045.
TEST(RenderOptionsTest, SrgbResponseGivesThePublishedValues) {
  const RenderOptions srgb = WithResponse("srgb");
  EXPECT_NEAR(ApplyResponseCurve(srgb, 0.5), 0.735357, 1e-5);
  EXPECT_NEAR(ApplyResponseCurve(srgb, 0.18), 0.461356, 1e-5);
  EXPECT_NEAR(ApplyResponseCurve(srgb, 0.0031308), 0.04045, 1e-5);
  EXPECT_NEAR(ApplyResponseCurve(srgb, 0.001), 0.01292, 1e-7);  // the toe is linear
  EXPECT_DOUBLE_EQ(ApplyResponseCurve(srgb, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(ApplyResponseCurve(srgb, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(ApplyResponseCurve(srgb, 1.7), 1.0);  // saturated
}

TEST(RenderOptionsTest, GammaAndTableResponses) {
  const RenderOptions gamma = WithResponse("gamma:0.7");
  EXPECT_EQ(gamma.response, ResponseCurve::kGamma);
  EXPECT_NEAR(ApplyResponseCurve(gamma, 0.5), 0.615572, 1e-6);  // 0.5^0.7
  const RenderOptions table = WithResponse("table:0,0.8,1");
  EXPECT_NEAR(ApplyResponseCurve(table, 0.25), 0.4, 1e-12);
  EXPECT_NEAR(ApplyResponseCurve(table, 0.75), 0.9, 1e-12);
  EXPECT_NEAR(ApplyResponseCurve(WithResponse("linear"), 0.3), 0.3, 1e-15);
}

TEST(RenderOptionsTest, MalformedResponsesAreRejectedWithTheText) {
  RenderOptions options;
  for (const char* text : {"cubic", "gamma:", "gamma:0.7x", "table:0,a,1", "srgb2"}) {
    std::string why;
    EXPECT_FALSE(ParseResponseCurve(text, &options, &why)) << text;
    EXPECT_NE(why.find(text), std::string::npos) << why;
  }
}

TEST(RenderOptionsTest, PresetsAreValidAndCleanIsTheHistoricalDefault) {
  RenderOptions clean, processed;
  ASSERT_TRUE(RenderPresetByName("clean", &clean));
  ASSERT_TRUE(RenderPresetByName("processed", &processed));
  EXPECT_FALSE(RenderPresetByName("raw", &clean));
  std::string why;
  EXPECT_TRUE(clean.IsValid(&why)) << why;
  EXPECT_TRUE(processed.IsValid(&why)) << why;
  EXPECT_EQ(clean.response, ResponseCurve::kLinear);
  EXPECT_EQ(clean.blur_sigma_px, 0.8);
  EXPECT_EQ(clean.noise_sigma, 2.0);
  EXPECT_EQ(clean.full_well_electrons, 0.0);
  EXPECT_EQ(processed.response, ResponseCurve::kSrgb);
  EXPECT_EQ(processed.illumination_gradient, 0.2);
  EXPECT_GT(processed.full_well_electrons, 0.0);
  EXPECT_GT(processed.focus_distance, 0.0);  // the PSF is not only a Gaussian
  // The brightest white (+10 % light) stays below full scale.
  EXPECT_LT(processed.white_level * (1 + 0.5 * processed.illumination_gradient), 255 * 0.85);
}

TEST(RenderOptionsTest, AbsurdValuesAreRejectedNamingTheOption) {
  auto why_for = [](auto change) {
    RenderOptions options;
    change(options);
    std::string why;
    EXPECT_FALSE(options.IsValid(&why));
    return why;
  };
  EXPECT_NE(why_for([](RenderOptions& o) { o.blur_sigma_px = 25; }).find("blur"),
            std::string::npos);
  EXPECT_NE(why_for([](RenderOptions& o) { o.vignetting = 0.95; }).find("vignetting"),
            std::string::npos);
  EXPECT_NE(why_for([](RenderOptions& o) { o.illumination_gradient = -0.1; }).find("gradient"),
            std::string::npos);
  EXPECT_NE(why_for([](RenderOptions& o) { o.full_well_electrons = 10; }).find("full well"),
            std::string::npos);
  EXPECT_NE(why_for([](RenderOptions& o) { o.aperture_diameter = 1; }).find("aperture"),
            std::string::npos);
  EXPECT_NE(why_for([](RenderOptions& o) {
              o.response = ResponseCurve::kGamma;
              o.response_gamma = 0.01;
            }).find("gamma"),
            std::string::npos);
  EXPECT_NE(why_for([](RenderOptions& o) {
              o.response = ResponseCurve::kTable;
              o.response_table = {0, 0.6, 0.5, 1};
            }).find("decrease"),
            std::string::npos);
}

}  // namespace
}  // namespace h4::cam

// Render options: presets, validation, the response curves; see render_options.h.
#include "firmware/render/render_options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "common/text/invalid_reason.h"

namespace h4::cam {
namespace {

bool InRange(double value, double lo, double hi) { return value >= lo && value <= hi; }

// Parses a whole string as a finite number.
bool ParseNumber(const std::string& text, double* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(*value);
}

double Srgb(double x) {
  return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

double Table(const std::vector<double>& table, double x) {
  const double position = x * static_cast<double>(table.size() - 1);
  const size_t k = std::min(static_cast<size_t>(position), table.size() - 2);
  const double t = position - static_cast<double>(k);
  return (1 - t) * table[k] + t * table[k + 1];
}

bool ResponseIsValid(const RenderOptions& o, std::string* why) {
  if (o.response == ResponseCurve::kGamma && !InRange(o.response_gamma, 0.1, 10)) {
    return Invalid(why, fmt::format("response gamma {:g}: expected 0.1..10", o.response_gamma));
  }
  if (o.response == ResponseCurve::kTable) {
    if (o.response_table.size() < 2) return Invalid(why, "response table: expected >= 2 values");
    for (size_t k = 0; k < o.response_table.size(); ++k) {
      if (!InRange(o.response_table[k], 0, 1)) {
        return Invalid(why, fmt::format("response table value {}: expected 0..1", k));
      }
      if (k > 0 && o.response_table[k] < o.response_table[k - 1]) {
        return Invalid(why, fmt::format("response table value {}: must not decrease", k));
      }
    }
  }
  return true;
}

}  // namespace

RenderOptions RenderOptions::Clean() { return RenderOptions{}; }

RenderOptions RenderOptions::Processed() {
  RenderOptions o;
  o.white_level = 180.0;  // ~70 % of full scale: +10 % gradient and noise stay below 255
  o.black_level = 11.0;   // printed black reflects ~6 % of what the white does
  o.background_level = 60.0;
  o.illumination_gradient = 0.2;
  o.illumination_gradient_direction_deg = 30.0;
  o.vignetting = 0.15;
  o.blur_sigma_px = 0.9;
  o.focus_distance = 1.0;        // fixed-focus module: sharp from ~1 m
  o.aperture_diameter = 1.9e-3;  // 3.8 mm lens at f/2
  o.full_well_electrons = 6000.0;
  o.noise_sigma = 1.0;
  o.response = ResponseCurve::kSrgb;
  return o;
}

bool RenderOptions::IsValid(std::string* why) const {
  if (samples_per_pixel < 1 || samples_per_pixel > 4096) {
    return Invalid(why, "samples_per_pixel must be 1..4096");
  }
  if (supersampling < 1 || supersampling > 8) return Invalid(why, "supersampling must be 1..8");
  if (!InRange(black_level, 0, 1e4) || !InRange(white_level, 0, 1e4) ||
      !InRange(background_level, 0, 1e4)) {
    return Invalid(why, "black/white/background levels must be 0..10000 grey levels");
  }
  if (!InRange(illumination_gradient, 0, 1)) {
    return Invalid(why,
                   fmt::format("illumination gradient {:g}: expected 0..1", illumination_gradient));
  }
  if (!std::isfinite(illumination_gradient_direction_deg)) {
    return Invalid(why, "illumination gradient direction must be a finite angle in deg");
  }
  if (!InRange(vignetting, 0, 0.9)) {
    return Invalid(why, fmt::format("vignetting {:g}: expected 0..0.9", vignetting));
  }
  if (!InRange(blur_sigma_px, 0, 20)) {
    return Invalid(why, fmt::format("blur sigma {:g} px: expected 0..20 px", blur_sigma_px));
  }
  if (!InRange(pixel_blur_sigma_px, 0, 20)) {
    return Invalid(why,
                   fmt::format("pixel blur sigma {:g} px: expected 0..20 px", pixel_blur_sigma_px));
  }
  if (!InRange(focus_distance, 0, 1e3)) {
    return Invalid(why, fmt::format("focus distance {:g} m: expected 0..1000 m", focus_distance));
  }
  if (!InRange(aperture_diameter, 0, 0.05)) {
    return Invalid(why,
                   fmt::format("aperture diameter {:g} m: expected 0..0.05 m", aperture_diameter));
  }
  if (!(full_well_electrons == 0 || InRange(full_well_electrons, 100, 1e7))) {
    return Invalid(why,
                   fmt::format("full well {:g} e-: expected 0 or 100..1e7", full_well_electrons));
  }
  if (!InRange(noise_sigma, 0, 50)) {
    return Invalid(why, fmt::format("read noise {:g}: expected 0..50 grey levels", noise_sigma));
  }
  return ResponseIsValid(*this, why);
}

RenderOptions RenderOptionsOf(RenderPreset preset) {
  return preset == RenderPreset::kClean ? RenderOptions::Clean() : RenderOptions::Processed();
}

bool RenderPresetByName(const std::string& name, RenderOptions* options) {
  const std::optional<RenderPreset> preset = kRenderPresetNames.ValueNamed(name);
  if (!preset) return false;
  *options = RenderOptionsOf(*preset);
  return true;
}

bool ParseResponseCurve(const std::string& text, RenderOptions* options, std::string* why) {
  auto fail = [why, &text](const std::string& message) {
    if (why != nullptr) *why = "response '" + text + "': " + message;
    return false;
  };
  if (text == "linear") {
    options->response = ResponseCurve::kLinear;
  } else if (text == "srgb") {
    options->response = ResponseCurve::kSrgb;
  } else if (text.rfind("gamma:", 0) == 0) {
    double exponent = 0;
    if (!ParseNumber(text.substr(6), &exponent)) return fail("expected gamma:EXPONENT");
    options->response = ResponseCurve::kGamma;
    options->response_gamma = exponent;
  } else if (text.rfind("table:", 0) == 0) {
    std::vector<double> table;
    std::istringstream in(text.substr(6));
    for (std::string item; std::getline(in, item, ',');) {
      double value = 0;
      if (!ParseNumber(item, &value)) return fail("expected table:V0,V1,... (numbers)");
      table.push_back(value);
    }
    options->response = ResponseCurve::kTable;
    options->response_table = table;
  } else {
    return fail("expected linear, srgb, gamma:EXPONENT or table:V0,V1,...");
  }
  return true;
}

double ApplyResponseCurve(const RenderOptions& options, double linear) {
  const double x = std::clamp(linear, 0.0, 1.0);
  switch (options.response) {
    case ResponseCurve::kLinear:
      return x;
    case ResponseCurve::kGamma:
      return std::pow(x, options.response_gamma);
    case ResponseCurve::kSrgb:
      return Srgb(x);
    case ResponseCurve::kTable:
      return options.response_table.size() < 2 ? x : Table(options.response_table, x);
  }
  return x;
}

}  // namespace h4::cam

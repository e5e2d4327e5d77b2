// What the board renderer simulates, in the order a camera forms an image, all in linear
// light until the response curve: printed radiance x illumination (gradient, vignetting)
// -> optical PSF (Gaussian, plus a defocus disk that grows away from the focus distance)
// -> pixel integration -> optional blur of the pixel values -> sensor (shot + read noise, saturation at full scale) -> response
// curve -> 8-bit quantisation. Two presets: "clean" (the renderer's historical images:
// linear, Gaussian blur and noise) and "processed" (a Raspberry Pi camera module's
// processed YUV output: sRGB-like response, ~1 px blur, 20 % gradient, shot + read noise).
#pragma once

#include <string>
#include <vector>

#include "common/text/enum_names.h"

namespace h4::cam {

/// How the linear signal (0..1 of full scale) becomes the output code (0..1 of 255).
enum class ResponseCurve {
  kLinear,  ///< out = in
  kGamma,   ///< out = in^response_gamma
  kSrgb,    ///< the sRGB encoding: 12.92 in below 0.0031308, else 1.055 in^(1/2.4) - 0.055
  kTable,   ///< piecewise linear through response_table
};

struct RenderOptions {
  // Geometry sampling.
  /// The board's region is rendered this many times finer per axis, blurred there, then
  /// averaged back to pixels (optical blur before pixel integration, as in a camera). 1..8.
  int supersampling = 4;
  /// Area samples per pixel where a colour boundary crosses it, spread over its
  /// supersampling^2 sub-pixels as jittered strata (unbiased whatever the edge direction).
  int samples_per_pixel = 256;
  double margin = -1.0;  ///< white border around the pattern, m (<0: one tag/square)

  // Scene radiance: the linear signal (reflectance x exposure) each surface gives under
  // illumination 1, in grey levels of full scale (255 = saturation; above it clips).
  double black_level = 30.0;       ///< printed black, 0..10000
  double white_level = 220.0;      ///< printed white, 0..10000
  double background_level = 90.0;  ///< off the board, 0..10000

  // Illumination, a factor on the radiance (1 at the image centre).
  /// Relative change of the light across the image along the direction below, fraction
  /// 0..1 (0.2: from 0.9 to 1.1 of the centre's light). 0 = uniform.
  double illumination_gradient = 0.0;
  /// Direction in which the light grows, deg from +u toward +v.
  double illumination_gradient_direction_deg = 0.0;
  /// Light lost at the image corners with a cos^4-shaped fall-off 1 / (1 + k r^2)^2,
  /// fraction 0..0.9. 0 = none.
  double vignetting = 0.0;

  // Optics: the PSF is this Gaussian convolved with the defocus disk.
  double blur_sigma_px = 0.8;  ///< Gaussian sigma, px, 0..20 (0 = none)
  /// Distance the lens is focused at (depth along the optical axis), m; 0 = no defocus.
  double focus_distance = 0.0;
  /// Entrance pupil diameter, m (3.8 mm lens at f/2: 1.9e-3), 0..0.05. A board point at
  /// depth z is spread over a disk (pillbox) of radius
  /// aperture_diameter / 2 * fx_px * |1/z - 1/focus_distance| px.
  double aperture_diameter = 0.0;

  /// Gaussian blur of the pixel values after the pixels integrated the light, px, 0..20
  /// (0 = none): what an image pipeline's demosaicing and denoising (or a renderer that
  /// blurs its pixels) do. Unlike the optical blur it acts on a sampled edge, whose profile
  /// then depends on where the edge falls within its pixel: an edge model written for the
  /// optical blur alone locks to the pixel grid on edges along the pixel axes.
  double pixel_blur_sigma_px = 0.0;

  // Sensor.
  /// Electrons at full scale: shot noise variance = signal * 255 / full_well_electrons
  /// (grey levels^2 of the linear signal). 0 = no shot noise; else 100..1e7.
  double full_well_electrons = 0.0;
  double noise_sigma = 2.0;  ///< read noise, grey levels of the linear signal, 0..50

  // Response curve, applied after saturation, before 8-bit quantisation.
  ResponseCurve response = ResponseCurve::kLinear;
  double response_gamma = 1.0;  ///< kGamma exponent, 0.1..10
  /// kTable: output (0..1) at evenly spaced inputs 0, 1/(n-1), ..., 1; non-decreasing, n >= 2.
  std::vector<double> response_table;

  /// The historical renderer (linear, Gaussian PSF and noise): the default above.
  static RenderOptions Clean();
  /// A Raspberry Pi camera module's processed (YUV) output at ~0.5 m: sRGB response, a
  /// fixed-focus 3.8 mm f/2 lens focused at 1 m (defocus disk 0.4-1 px at 0.45-0.65 m) on
  /// a 0.9 px Gaussian, 20 % gradient, 15 % vignetting, shot noise (6000 e- full well) and
  /// read noise 1 level, the white exposed at ~70 % of full scale so it does not clip.
  static RenderOptions Processed();

  bool IsValid(std::string* why) const;
};

/// The two image formations a name on the command line or in h4cam.yaml (`sim.preset`) picks.
enum class RenderPreset { kClean, kProcessed };
constexpr EnumNames<RenderPreset, RenderPreset::kProcessed> kRenderPresetNames = {"clean",
                                                                                  "processed"};

/// The preset's options: RenderOptions::Clean() or Processed().
RenderOptions RenderOptionsOf(RenderPreset preset);

/// Sets `options` to the preset `name` (kRenderPresetNames); false for other names.
bool RenderPresetByName(const std::string& name, RenderOptions* options);

/// Parses "linear", "srgb", "gamma:E" or "table:v0,v1,...,vn" into options->response and
/// its parameters; false with `why` set on a malformed text (values are checked by
/// IsValid).
bool ParseResponseCurve(const std::string& text, RenderOptions* options, std::string* why);

/// The response curve of `options` at a linear signal in 0..1 (clamped), in 0..1.
double ApplyResponseCurve(const RenderOptions& options, double linear);

}  // namespace h4::cam

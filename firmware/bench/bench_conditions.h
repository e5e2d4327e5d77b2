// The image conditions the measuring benchmarks render under (firmware/render/
// render_options.h): each effect of a real camera alone at a realistic strength, then all
// of them together (the "processed" preset). Shared by h4_measure_accuracy and
// h4_measure_corners so that their rows describe the same scenes.
#pragma once

#include <vector>

#include "firmware/render/render_options.h"

namespace h4::cam::bench {

struct Condition {
  const char* name;
  RenderOptions render;
};

inline std::vector<Condition> AllConditions() {
  const RenderOptions clean = RenderOptions::Clean();
  RenderOptions blur = clean, gamma = clean, srgb = clean, gradient = clean;
  blur.blur_sigma_px = 1.4;
  gamma.response = ResponseCurve::kGamma;
  gamma.response_gamma = 0.7;
  gamma.blur_sigma_px = 0.7;
  srgb.response = ResponseCurve::kSrgb;
  srgb.blur_sigma_px = 1.0;
  gradient.illumination_gradient = 0.3;
  gradient.illumination_gradient_direction_deg = 30;
  gradient.vignetting = 0.2;
  // An ISP's encoded output (issue 41's scenes): gamma 0.7 after 1.4 px of optical blur, with
  // light fall-off and shot noise.
  RenderOptions isp = gamma;
  isp.blur_sigma_px = 1.4;
  isp.illumination_gradient = 0.2;
  isp.vignetting = 0.15;
  isp.full_well_electrons = 6000;
  isp.noise_sigma = 1.0;
  // The blur acting on the pixel values after integration instead of on the light before
  // it (as a renderer that blurs its pixels, or an ISP's demosaicing, does): an image
  // formation the edge model does not assume (render_options.h), linear so that only the
  // sampling differs.
  RenderOptions pixel_blur = clean;
  pixel_blur.blur_sigma_px = 0.0;
  pixel_blur.pixel_blur_sigma_px = 0.7;
  return {{"clean", clean},
          {"blur1.4", blur},
          {"gamma0.7+blur0.7", gamma},
          {"srgb+blur1.0", srgb},
          {"gradient", gradient},
          {"all", RenderOptions::Processed()},
          {"isp:gamma0.7+blur1.4", isp},
          {"pixelblur0.7", pixel_blur}};
}

}  // namespace h4::cam::bench

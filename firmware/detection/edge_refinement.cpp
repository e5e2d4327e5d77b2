// Blurred-step edge fitting; see edge_refinement.h.
#include "firmware/detection/edge_refinement.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace h4::cam {
namespace {

struct Sample {
  Eigen::Vector2d q;  // ideal coordinates relative to the side's midpoint
  double value;
  double t;  // ideal distance along the side from its first corner
};

struct Line {
  Eigen::Vector2d mid;  // a point on the side (ideal), origin of the fit
  double phi = 0;       // normal direction n = (cos phi, sin phi), pointing dark -> bright
  double c = 0;         // n . (q - mid) = c on the line
  Eigen::Vector2d n() const { return {std::cos(phi), std::sin(phi)}; }
  Eigen::Vector2d point() const { return mid + c * n(); }
};

constexpr double kInvSqrt2 = 0.70710678118654752440;
constexpr double kInvSqrt2Pi = 0.39894228040143267794;

// Pixels of the band -band_in <= distance <= band_px around the line, between the corners a
// and b (ideal) less the corner clearance at each end.
std::vector<Sample> SelectBand(const cv::Mat& image, const IdealPixelMap& map, const Line& line,
                               const Eigen::Vector2d& a_px, const Eigen::Vector2d& b_px,
                               const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                               const EdgeFitOptions& options, double band_in) {
  std::vector<Sample> samples;
  const Eigen::Vector2d n = line.n();
  const Eigen::Vector2d along = (b - a).normalized();
  const double length = (b - a).norm();
  const double margin = options.band_px + 3.0;
  const int u0 = std::max(0, static_cast<int>(std::floor(std::min(a_px.x(), b_px.x()) - margin)));
  const int u1 =
      std::min(image.cols - 1, static_cast<int>(std::ceil(std::max(a_px.x(), b_px.x()) + margin)));
  const int v0 = std::max(0, static_cast<int>(std::floor(std::min(a_px.y(), b_px.y()) - margin)));
  const int v1 =
      std::min(image.rows - 1, static_cast<int>(std::ceil(std::max(a_px.y(), b_px.y()) + margin)));
  for (int v = v0; v <= v1; ++v) {
    const float* row = image.ptr<float>(v);
    for (int u = u0; u <= u1; ++u) {
      const Eigen::Vector2d q = map.At(u, v) - line.mid;
      const double d = n.dot(q) - line.c;
      if (d > options.band_px || d < -band_in) continue;
      const double t = along.dot(map.At(u, v) - a);
      if (t < options.corner_clearance_px || t > length - options.corner_clearance_px) continue;
      samples.push_back({q, static_cast<double>(row[u]), t});
    }
  }
  return samples;
}

// Phi(z) and pdf(z) from one exponential: Abramowitz & Stegun 7.1.26 for erf (absolute
// error below 1.5e-7, i.e. 3e-5 grey levels on a 200-level edge), twice as fast as
// std::erf plus std::exp in the fit's inner loop.
struct PhiPdf {
  double phi, pdf;
};
PhiPdf PhiAndPdf(double z) {
  const double x = std::abs(z) * kInvSqrt2;
  const double e = std::exp(-x * x);  // = exp(-z^2 / 2)
  const double t = 1.0 / (1.0 + 0.3275911 * x);
  const double poly =
      t *
      (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
  const double erf_abs = 1.0 - poly * e;
  return {0.5 * (1.0 + (z < 0 ? -erf_abs : erf_abs)), kInvSqrt2Pi * e};
}
// G(z) = z Phi(z) + pdf(z) is the integral of Phi, H(z) = ((z^2 + 1) Phi(z) + z pdf(z)) / 2
// the integral of G.

// Profile of a pixel at signed distance d from the edge: a unit step blurred by a
// Gaussian (sigma s) and averaged over the pixel, whose projection onto the edge normal
// is a trapezoid, the convolution of boxes of widths w1 >= w2 (|cos|, |sin| of the
// normal's angle). With only a few distinct pixel-to-edge offsets (edges aligned with
// the pixel grid), an approximate profile would shift the fitted edge; this one is exact
// for the Gaussian blur. Returns F and its derivatives by d and s.
struct Profile {
  double w1 = 1, w2 = 0;
  void Eval(double d, double s, double* F, double* dF_dd, double* dF_ds) const {
    if (w2 < 0.05) {  // one box: its second side adds a variance below w2^2/12
      const double zp = (d + 0.5 * w1) / s, zm = (d - 0.5 * w1) / s;
      const PhiPdf p = PhiAndPdf(zp), m = PhiAndPdf(zm);
      const double phi_p = p.phi, phi_m = m.phi, pdf_p = p.pdf, pdf_m = m.pdf;
      *F = s / w1 * (zp * phi_p + pdf_p - zm * phi_m - pdf_m);
      *dF_dd = (phi_p - phi_m) / w1;
      *dF_ds = (pdf_p - pdf_m) / w1;
      return;
    }
    const double offsets[4] = {0.5 * (w1 + w2), 0.5 * (w1 - w2), -0.5 * (w1 - w2),
                               -0.5 * (w1 + w2)};
    const double signs[4] = {1, -1, -1, 1};
    double sum_h = 0, sum_g = 0, sum_phi = 0;
    for (int i = 0; i < 4; ++i) {
      const double z = (d + offsets[i]) / s;
      const PhiPdf pp = PhiAndPdf(z);
      const double phi = pp.phi, pdf = pp.pdf;
      sum_h += signs[i] * (0.5 * (z * z + 1.0) * phi + 0.5 * z * pdf);  // H(z)
      sum_g += signs[i] * (z * phi + pdf);                              // G(z)
      sum_phi += signs[i] * phi;
    }
    const double k = 1.0 / (w1 * w2);
    *F = k * s * s * sum_h;
    *dF_dd = k * s * sum_g;
    *dF_ds = k * s * sum_phi;
  }
};

// Where the blur acted (see BlurStage in edge_refinement.h). A pixel blur is a sampled
// Gaussian kernel (sigma s) over the neighbouring pixels, as an ISP's filters or a renderer's
// (OpenCV's GaussianBlur: radius 4 sigma) apply it, on pixels that integrated a step blurred
// optically by `optical` (a lens always blurs a little; RefitWithPixelBlur tries a few): along
// the normal's major pixel axis the neighbours sit one pixel apart (offsets `step` in d);
// across it (offsets of step * tan, under a tenth of a pixel on a side near that axis) the
// kernel is taken as a Gaussian of the same spread in d, added to the optical blur.
struct EdgeProfile {
  static constexpr int kMaxRadius = 20;
  BlurStage stage = BlurStage::kOptical;
  Profile box;        // the pixel's footprint along the normal
  double s = 1;       // the blur: optical, or the pixel blur's kernel sigma
  double step = 1;    // d between neighbouring pixels along the major axis
  // Pixel blur only: the optical blur under it with the kernel's spread across the major
  // axis, its derivative by s, and the kernel, normalised to 1, with its derivative by s.
  double s_box = 0, ds_box_ds = 0;
  int radius = 0;
  std::array<double, 2 * kMaxRadius + 1> weight{}, dweight_ds{};

  // F and its derivatives by d and by s.
  void Eval(double d, double* F, double* dF_dd, double* dF_ds) const {
    if (stage == BlurStage::kOptical) return box.Eval(d, s, F, dF_dd, dF_ds);
    if (box.w2 < 0.05) return EvalOneBox(d, F, dF_dd, dF_ds);
    double sum_F = 0, sum_dd = 0, sum_ds_box = 0, sum_F_dweight = 0;
    for (int i = -radius; i <= radius; ++i) {
      const size_t k = static_cast<size_t>(i + radius);
      double Fi, dFi_dd, dFi_ds;
      box.Eval(d + step * i, s_box, &Fi, &dFi_dd, &dFi_ds);
      sum_F += weight[k] * Fi;
      sum_dd += weight[k] * dFi_dd;
      sum_ds_box += weight[k] * dFi_ds;
      sum_F_dweight += dweight_ds[k] * Fi;
    }
    *F = sum_F;
    *dF_dd = sum_dd;
    *dF_ds = sum_F_dweight + ds_box_ds * sum_ds_box;
  }

  // The same where the footprint is one box (Profile::Eval's first case) and the neighbours
  // sit one box width apart: each tap's upper end is the next one's lower end, so the kernel
  // needs 2 radius + 2 evaluations of Phi rather than twice 2 radius + 1.
  void EvalOneBox(double d, double* F, double* dF_dd, double* dF_ds) const {
    std::array<PhiPdf, 2 * kMaxRadius + 2> ends;
    std::array<double, 2 * kMaxRadius + 2> z;
    for (int j = -radius; j <= radius + 1; ++j) {
      const size_t k = static_cast<size_t>(j + radius);
      z[k] = (d + step * (j - 0.5)) / s_box;
      ends[k] = PhiAndPdf(z[k]);
    }
    double sum_F = 0, sum_dd = 0, sum_ds_box = 0, sum_F_dweight = 0;
    for (size_t k = 0; k <= static_cast<size_t>(2 * radius); ++k) {
      const PhiPdf& m = ends[k];
      const PhiPdf& p = ends[k + 1];
      const double Fi = s_box / box.w1 * (z[k + 1] * p.phi + p.pdf - z[k] * m.phi - m.pdf);
      sum_F += weight[k] * Fi;
      sum_dd += weight[k] * (p.phi - m.phi) / box.w1;
      sum_ds_box += weight[k] * (p.pdf - m.pdf) / box.w1;
      sum_F_dweight += dweight_ds[k] * Fi;
    }
    *F = sum_F;
    *dF_dd = sum_dd;
    *dF_ds = sum_F_dweight + ds_box_ds * sum_ds_box;
  }
};

// The profile of a side with outward normal n for blur s (and, for a pixel blur, the
// optical blur `optical` under it).
EdgeProfile ProfileFor(const Eigen::Vector2d& n, double pixel_scale, BlurStage stage, double s,
                       double optical) {
  EdgeProfile p;
  p.stage = stage;
  p.s = s;
  const double c = std::abs(n.x()) * pixel_scale, r = std::abs(n.y()) * pixel_scale;
  p.box.w1 = std::max(c, r);
  p.box.w2 = std::min(c, r);
  p.step = p.box.w1;
  if (stage == BlurStage::kOptical) return p;
  const double s_across = p.box.w2 * s;
  p.s_box = std::sqrt(optical * optical + s_across * s_across);
  p.ds_box_ds = s_across * p.box.w2 / p.s_box;
  p.radius = std::clamp(static_cast<int>(std::ceil(4.0 * s)), 1, EdgeProfile::kMaxRadius);
  double weight_sum = 0, dweight_sum = 0;
  for (int i = -p.radius; i <= p.radius; ++i) {
    const size_t k = static_cast<size_t>(i + p.radius);
    p.weight[k] = std::exp(-0.5 * i * i / (s * s));
    p.dweight_ds[k] = p.weight[k] * i * i / (s * s * s);
    weight_sum += p.weight[k];
    dweight_sum += p.dweight_ds[k];
  }
  for (size_t k = 0; k <= static_cast<size_t>(2 * p.radius); ++k) {
    p.weight[k] /= weight_sum;
    p.dweight_ds[k] = p.dweight_ds[k] / weight_sum - p.weight[k] * dweight_sum / weight_sum;
  }
  return p;
}

// The black border's inner edge, `thickness` inside the side, seen where the data cell
// next to the border is white: a rectangle [t_j, t_j + cell] along the side, beyond
// d = -thickness. Blurred by a Gaussian it adds w(t) (1 - F(d + thickness)) to the unit
// step, w(t) = sum over white cells of Phi((t - t_j) / s) - Phi((t - t_j - cell) / s)
// (separable; the pixel's width along the side is neglected there).
struct InnerEdge {
  bool enabled = false;
  double thickness = 0;
  double cell = 0;
  std::vector<bool> white;  // cells along the side's inner row, from its first corner

  bool WhiteAt(int j) const {
    return j >= 0 && j < static_cast<int>(white.size()) && white[static_cast<size_t>(j)];
  }
  // White fraction seen at t (only the cell at t and its neighbours reach it).
  double Weight(double t, double s) const {
    const int j0 = static_cast<int>(std::floor(t / cell));
    if (WhiteAt(j0 - 1) == WhiteAt(j0) && WhiteAt(j0) == WhiteAt(j0 + 1))
      return WhiteAt(j0) ? 1 : 0;
    double w = 0;
    for (int j = j0 - 1; j <= j0 + 1; ++j) {
      if (!WhiteAt(j)) continue;
      w += PhiAndPdf((t - j * cell) / s).phi - PhiAndPdf((t - (j + 1) * cell) / s).phi;
    }
    return w;
  }
};

// Adds the inner edge's term to a sample's unit profile F and its derivatives (w(t)'s own
// dependence on s is left out of the Jacobian: with an exact model the residuals vanish at
// the true edge, which stays the fixed point; the approximation only slows convergence).
void AddInnerEdge(const InnerEdge& inner, const EdgeProfile& profile, double t, double d,
                  double s, double* F, double* dF_dd, double* dF_ds) {
  const double d_inner = d + inner.thickness;
  if (!inner.enabled || d_inner > 4.0 * s + 1.0) return;  // tail below 3e-5
  const double w = inner.Weight(t, s);
  if (w == 0) return;
  double G, dG_dd, dG_ds;
  profile.Eval(d_inner, &G, &dG_dd, &dG_ds);
  *F += w * (1.0 - G);
  *dF_dd -= w * dG_dd;
  *dF_ds -= w * dG_ds;
}

constexpr int kEdgeParameters = 6;  // phi, c, a, b, s, k
using EdgeVector = Eigen::Matrix<double, kEdgeParameters, 1>;
using EdgeMatrix = Eigen::Matrix<double, kEdgeParameters, kEdgeParameters>;

// H += J J^T on and below the diagonal only (21 of 36 products: the fit's inner loop).
void AddLowerOuterProduct(const EdgeVector& J, EdgeMatrix* H) {
  for (int col = 0; col < kEdgeParameters; ++col) {
    for (int row = col; row < kEdgeParameters; ++row) (*H)(row, col) += J[row] * J[col];
  }
}

// Holds parameter i of a Gauss-Newton step at its value.
void HoldParameter(int i, EdgeMatrix* H, EdgeVector* g) {
  H->row(i).setZero();
  H->col(i).setZero();
  (*H)(i, i) = 1.0;
  (*g)[i] = 0.0;
}

// Gauss-Newton on (phi, c, a, b, s, k) for I = (1 + k tau) (a + b (F(n . q - c; s) + inner
// edge term)), tau in [-1, 1] along the side: the light falling on a side changes along it
// (an illumination gradient, vignetting), scaling its dark and bright levels together; a
// model with constant levels would tilt the fitted line toward the darker end.
// `line_covariance` receives the covariance of (phi, c) from the pixel noise the residuals
// show (sigma^2 H^-1, marginal over the levels, blur and shading). The residuals and H are
// those at the start of the last iteration: its step is below a thousandth of the line's
// noise when converged, and evaluating every pixel once more would cost a tenth of the fit.
bool FitEdge(const std::vector<Sample>& samples, int iterations, double tolerance_px,
             double pixel_scale, BlurStage stage, double optical, bool fit_shading,
             const InnerEdge& inner,
             Line* line, double* a, double* b, double* s, double* rms,
             Eigen::Matrix2d* line_covariance) {
  double t_min = samples.front().t, t_max = samples.front().t;
  for (const Sample& sample : samples) {
    t_min = std::min(t_min, sample.t);
    t_max = std::max(t_max, sample.t);
  }
  const double t_mid = 0.5 * (t_min + t_max);
  const double t_half = std::max(0.5 * (t_max - t_min), 1e-9);
  double k = 0;
  EdgeMatrix H = EdgeMatrix::Zero();
  double sum = 0;  // of squared residuals at the last iteration's start
  for (int it = 0; it < iterations; ++it) {
    H.setZero();
    sum = 0;
    EdgeVector g = EdgeVector::Zero();
    const Eigen::Vector2d n = line->n();
    const Eigen::Vector2d n_perp(-n.y(), n.x());
    const EdgeProfile profile = ProfileFor(n, pixel_scale, stage, *s, optical);
    for (const Sample& sample : samples) {
      const double d = n.dot(sample.q) - line->c;
      double F, dF_dd, dF_ds;
      profile.Eval(d, &F, &dF_dd, &dF_ds);
      AddInnerEdge(inner, profile, sample.t, d, *s, &F, &dF_dd, &dF_ds);
      const double tau = (sample.t - t_mid) / t_half;
      const double gain = 1.0 + k * tau;
      const double level = *a + *b * F;
      const double r = gain * level - sample.value;
      const double dI_dd = gain * *b * dF_dd;
      EdgeVector J;
      J << dI_dd * n_perp.dot(sample.q), -dI_dd, gain, gain * F, gain * *b * dF_ds, tau * level;
      AddLowerOuterProduct(J, &H);
      g.noalias() += J * r;
      sum += r * r;
    }
    H.triangularView<Eigen::StrictlyUpper>() = H.transpose();
    if (!fit_shading) HoldParameter(5, &H, &g);  // k held at 0
    H.diagonal() *= 1.0 + 1e-9;
    const EdgeVector step = H.ldlt().solve(-g);
    if (!step.allFinite()) return false;
    line->phi += step[0];
    line->c += step[1];
    *a += step[2];
    *b += step[3];
    *s = std::clamp(*s + step[4], 0.2, 5.0);
    k = std::clamp(k + step[5], -0.5, 0.5);
    // The angle's step over a 100 px side moves its ends as much as tolerance_px.
    if (std::abs(step[1]) < tolerance_px && std::abs(step[0]) < 0.01 * tolerance_px) break;
  }
  *rms = std::sqrt(sum / static_cast<double>(samples.size()));
  const int free_parameters = kEdgeParameters - (fit_shading ? 0 : 1);
  const double dof = static_cast<double>(samples.size()) - free_parameters;
  Eigen::FullPivLU<EdgeMatrix> lu(H);
  if (dof <= 0 || !lu.isInvertible()) return false;
  *line_covariance = (sum / dof) * lu.inverse().topLeftCorner<2, 2>();
  return std::isfinite(line->c) && *b > 0 && line_covariance->allFinite();
}

bool Intersect(const Line& l1, const Line& l2, Eigen::Vector2d* p) {
  Eigen::Matrix2d A;
  A.row(0) = l1.n().transpose();
  A.row(1) = l2.n().transpose();
  const Eigen::Vector2d rhs(l1.n().dot(l1.point()), l2.n().dot(l2.point()));
  if (std::abs(A.determinant()) < 1e-6) return false;
  *p = A.inverse() * rhs;
  return true;
}

// Jacobian of the pixel position by the ideal position at p (central differences over a
// tenth of a pixel, `pixel_scale` being a pixel's size in ideal coordinates).
Eigen::Matrix2d PixelJacobian(const IdealPixelMap& map, const Eigen::Vector2d& p,
                              double pixel_scale) {
  const double h = 0.05 * pixel_scale;
  Eigen::Matrix2d J;
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d step = h * Eigen::Vector2d::Unit(i);
    J.col(i) = (map.PixelFromIdeal(p + step) - map.PixelFromIdeal(p - step)) / (2 * h);
  }
  return J;
}

// Pixel displacement of the corner p = l1 x l2 per unit of each line's standardised noise:
// with n_i . (p - mid_i) = c_i, A = [n1^T; n2^T], dp = A^-1 [dc_i + n_perp_i . (mid_i - p)
// dphi_i], and (dphi_i, dc_i) = L_i z_i, L_i L_i^T the line's covariance. Columns: z of
// line l1 (2), then of l2 (2).
Eigen::Matrix<double, 2, 4> CornerNoise(const Eigen::Matrix2d& pixel_jacobian, const Line& l1,
                                        const Eigen::Matrix2d& L1, const Line& l2,
                                        const Eigen::Matrix2d& L2, const Eigen::Vector2d& p) {
  Eigen::Matrix2d A;
  A.row(0) = l1.n().transpose();
  A.row(1) = l2.n().transpose();
  const Eigen::Matrix2d A_inverse = A.inverse();
  const auto by_line = [&](const Line& l, int row, const Eigen::Matrix2d& L) {
    const Eigen::Vector2d n_perp(-l.n().y(), l.n().x());
    Eigen::Matrix2d dp_dline;  // columns: by phi, by c
    dp_dline.col(0) = A_inverse.col(row) * n_perp.dot(l.mid - p);
    dp_dline.col(1) = A_inverse.col(row);
    return (pixel_jacobian * dp_dline * L).eval();
  };
  Eigen::Matrix<double, 2, 4> noise;
  noise << by_line(l1, 0, L1), by_line(l2, 1, L2);
  return noise;
}

// Pixel displacement of the corner p (ideal) of lines l1 and l2 when both move inward
// (against their outward normals) by one image pixel, i.e. by `pixel_scale` in ideal
// coordinates: the corner moves by -m with [n1^T; n2^T] m = [1; 1], mapped to pixels
// through the distortion (a central difference over a tenth of a pixel).
Eigen::Vector2d ErosionDirection(const IdealPixelMap& map, const Line& l1, const Line& l2,
                                 const Eigen::Vector2d& p, double pixel_scale) {
  Eigen::Matrix2d A;
  A.row(0) = l1.n().transpose();
  A.row(1) = l2.n().transpose();
  const Eigen::Vector2d m = A.inverse() * Eigen::Vector2d(1.0, 1.0);
  const double h = 0.05;
  const Eigen::Vector2d step = h * pixel_scale * m;
  return (map.PixelFromIdeal(p - step) - map.PixelFromIdeal(p + step)) / (2 * h);
}

// Size of a pixel in ideal coordinates near `uv` (distortion scales it slightly).
double PixelScaleAt(const IdealPixelMap& map, const Eigen::Vector2d& uv) {
  const int mu = std::clamp(static_cast<int>(uv.x()), 0, map.width() - 2);
  const int mv = std::clamp(static_cast<int>(uv.y()), 0, map.height() - 1);
  return (map.At(mu + 1, mv) - map.At(mu, mv)).norm();
}

// Thickness of the quad's black border next to side k (from corner k to k+1), ideal
// coordinates: the distance to the opposite side over the width in cells, times the
// border's cells; 0 when unknown.
double BorderThickness(const std::array<Eigen::Vector2d, 4>& ideal, size_t k,
                       const EdgeFitOptions& options) {
  if (options.tag_width_cells <= 0) return 0;
  const Eigen::Vector2d mid = 0.5 * (ideal[k] + ideal[(k + 1) % 4]);
  const Eigen::Vector2d& c = ideal[(k + 2) % 4];
  const Eigen::Vector2d& d = ideal[(k + 3) % 4];
  Eigen::Vector2d n_opposite(-(d - c).y(), (d - c).x());
  n_opposite.normalize();
  return std::abs(n_opposite.dot(mid - c)) * options.border_thickness_cells /
         options.tag_width_cells;
}

// How far the band reaches into the dark side: band_px, less where the border's inner
// edge (and its blurred tail, blur_sigma in ideal coordinates) would enter it.
double DarkSideWidth(const EdgeFitOptions& options, double thickness, double blur_sigma) {
  if (thickness <= 0) return options.band_px;
  const double clearance = options.inner_clearance_px + options.inner_clearance_blur * blur_sigma;
  return std::clamp(thickness - clearance, 1.0, options.band_px);
}

// Value of the pixel nearest to the ideal point p, or NaN outside the image.
double ValueAt(const cv::Mat& image, const IdealPixelMap& map, const Eigen::Vector2d& p) {
  const Eigen::Vector2d uv = map.PixelFromIdeal(p);
  // Bounds checked in floating point first: rounding a NaN or huge value is not defined.
  if (!(uv.x() > -0.5 && uv.y() > -0.5 && uv.x() < image.cols - 0.5 && uv.y() < image.rows - 0.5)) {
    return NAN;
  }
  const int u = static_cast<int>(std::lround(uv.x())), v = static_cast<int>(std::lround(uv.y()));
  return image.at<float>(std::min(v, image.rows - 1), std::min(u, image.cols - 1));
}

// Reads, from the image, which cells of the row inside side a -> b (outward normal n) are
// white: each cell's centre against the mean of the border's black corner cells and the
// white quiet zone outside the side. The tag was decoded, so its cells are clear. The
// border's own cells at both ends stay black.
InnerEdge ReadInnerEdge(const cv::Mat& image, const IdealPixelMap& map, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b, const Eigen::Vector2d& n, double thickness,
                        const EdgeFitOptions& options) {
  InnerEdge inner;
  const int width = options.tag_width_cells, border = options.border_thickness_cells;
  if (width < 2 * border + 1 || thickness <= 0) return inner;
  const Eigen::Vector2d along = (b - a).normalized();
  inner.thickness = thickness;
  inner.cell = (b - a).norm() / width;
  const auto centre = [&](int j) {
    return a + (j + 0.5) * inner.cell * along - (thickness + 0.5 * inner.cell) * n;
  };
  const double black =
      0.5 * (ValueAt(image, map, centre(0)) + ValueAt(image, map, centre(width - 1)));
  const double white = ValueAt(image, map, 0.5 * (a + b) + 1.5 * inner.cell * n);
  if (!(white - black > 1.0)) return inner;
  inner.white.assign(static_cast<size_t>(width), false);
  for (int j = border; j + border < width; ++j) {
    inner.white[static_cast<size_t>(j)] = ValueAt(image, map, centre(j)) > 0.5 * (black + white);
  }
  inner.enabled = true;
  return inner;
}

// The step's two levels to start the fit from: the darkest and brightest sides of the band
// (more than 0.8 px inside, more than 1 px outside). False without both sides or contrast.
bool InitialLevels(const std::vector<Sample>& samples, const Line& line, double* level_a,
                   double* level_b) {
  double dark = 0, bright = 0;
  int n_dark = 0, n_bright = 0;
  const Eigen::Vector2d nn = line.n();
  for (const Sample& sample : samples) {
    const double d = nn.dot(sample.q) - line.c;
    if (d < -0.8) dark += sample.value, ++n_dark;
    if (d > 1.0) bright += sample.value, ++n_bright;
  }
  if (n_dark == 0 || n_bright == 0) return false;
  *level_a = dark / n_dark;
  *level_b = bright / n_bright - *level_a;
  return *level_b > 1.0;
}

// Whether the side's normal `n` lies within `degrees` of a pixel axis.
bool NearPixelAxis(const Eigen::Vector2d& n, double degrees) {
  return std::min(std::abs(n.x()), std::abs(n.y())) < std::sin(degrees * M_PI / 180.0);
}

// One fit of a side: its line, levels, residuals' RMS and the line's covariance.
struct SideFit {
  Line line;
  double a = 0, b = 0, s = 0;
  double rms = INFINITY;
  Eigen::Matrix2d line_covariance = Eigen::Matrix2d::Zero();
};

// The side fitted with a pixel blur over `optical` of optical blur, from `start` (the optical
// fit); rms stays infinite when the fit fails.
SideFit FitPixelBlur(const std::vector<Sample>& pixels, const SideFit& start, double optical,
                     int iterations, double pixel_scale, bool fit_shading,
                     const InnerEdge& inner) {
  SideFit fit = start;
  if (!FitEdge(pixels, iterations, 1e-5, pixel_scale, BlurStage::kPixel, optical, fit_shading,
               inner, &fit.line, &fit.a, &fit.b, &fit.s, &fit.rms, &fit.line_covariance)) {
    fit.rms = INFINITY;
  }
  return fit;
}

// The best pixel-blur fit of the side. The lens's own blur under the pixel blur is tried at a
// few values rather than fitted (with the pixel blur's sigma it is nearly degenerate, and
// Gauss-Newton on both diverges from some starts), then once more at the vertex of the
// parabola through the best value and its neighbours. A short trial comes first, three
// iterations on every third pixel of the band (on a side along the pixel axes every row sees
// the same offsets): where its residuals' RMS is not below kScreenRatio of the optical fit's
// (an optical blur, the usual case) nothing else is tried and the result's rms is infinite.
// The screen is most of what the refit costs there (h4_measure_speed,
// BM_DetectEdgeFitAxisAligned; h4_measure_accuracy roll=aligned, CPU per pose).
SideFit BestPixelBlurFit(const std::vector<Sample>& samples, const SideFit& optical_fit,
                         const EdgeFitOptions& options, double pixel_scale,
                         const InnerEdge& inner) {
  constexpr std::array<double, 4> kOpticalParts = {0.05, 0.25, 0.45, 0.65};
  constexpr size_t kFirstTrial = 1;
  constexpr int kScreenIterations = 3;
  constexpr size_t kScreenStride = 3;
  // Looser than the 0.8 RefitWithPixelBlur asks of the best fit: the screen's fit is short.
  constexpr double kScreenRatio = 0.85;
  const auto fit = [&](const std::vector<Sample>& pixels, double optical, int iterations) {
    return FitPixelBlur(pixels, optical_fit, optical, iterations, pixel_scale,
                        options.fit_shading, inner);
  };
  std::vector<Sample> screen;
  for (size_t i = 0; i < samples.size(); i += kScreenStride) screen.push_back(samples[i]);
  if (static_cast<int>(screen.size()) >= options.min_pixels &&
      !(fit(screen, kOpticalParts[kFirstTrial], kScreenIterations).rms <
        kScreenRatio * optical_fit.rms)) {
    return SideFit{};
  }
  std::array<SideFit, kOpticalParts.size()> trials;
  for (size_t i = 0; i < kOpticalParts.size(); ++i) {
    trials[i] = fit(samples, kOpticalParts[i], options.iterations);
  }
  const auto by_rms = [](const SideFit& x, const SideFit& y) { return x.rms < y.rms; };
  const size_t best =
      static_cast<size_t>(std::min_element(trials.begin(), trials.end(), by_rms) - trials.begin());
  if (best == 0 || best + 1 == kOpticalParts.size()) return trials[best];
  // Equally spaced: the vertex lies h (f- - f+) / (2 (f- - 2 f0 + f+)) from the middle.
  const double f_minus = std::pow(trials[best - 1].rms, 2), f0 = std::pow(trials[best].rms, 2),
               f_plus = std::pow(trials[best + 1].rms, 2);
  const double curvature = f_minus - 2 * f0 + f_plus;
  const double h = kOpticalParts[1] - kOpticalParts[0];
  if (!std::isfinite(curvature) || !(curvature > 0)) return trials[best];
  const SideFit vertex = fit(samples, kOpticalParts[best] + 0.5 * h * (f_minus - f_plus) / curvature,
                             options.iterations);
  return std::min(vertex, trials[best], by_rms);
}

// A side along the pixel axes samples only a few pixel-to-edge offsets, so the profile's
// shape there decides where the edge lands: a blur of the pixel values fitted as an optical
// blur locks the edge to the pixel grid (0.04 px on h4_measure_corners' pixelblur0.7 scenes
// with roll=aligned). Fits the side again with a pixel blur, from the optical fit, and keeps
// that fit where it explains the pixels clearly better. On tilted sides the two agree and
// nothing is refitted.
void RefitWithPixelBlur(const std::vector<Sample>& samples, const EdgeFitOptions& options,
                        double pixel_scale, const InnerEdge& inner, SideFit* side) {
  const SideFit pixel = BestPixelBlurFit(samples, *side, options, pixel_scale, inner);
  if (!std::isfinite(pixel.rms)) return;
  // Where the two profiles hardly differ (strong blur, a side a few degrees off the axis),
  // the pixels' noise picks one at random; where the image's response is not linear (gamma),
  // neither profile fits and the pixel blur's explains a little more while biasing the side
  // more. So the pixel blur must explain the pixels clearly better: its residuals' RMS below
  // kMaxRatio of the optical fit's, and their sum of squares lower by kEvidence times the
  // noise's variance. Measured with h4_measure_corners roll=aligned scenes=3 while the pixel
  // blur had no optical part, the RMS ratio per side was 0.49 on average with a blur of the
  // pixel values (830 of 864 sides below 0.8) and above 0.9 on every side of the
  // optical-blur conditions, gamma and sRGB included; with the optical part tried, the
  // benchmark's optical-blur figures stay unchanged (docs/results.md).
  constexpr double kMaxRatio = 0.8;
  constexpr double kEvidence = 9.0;
  const double n = static_cast<double>(samples.size());
  const double noise_variance = pixel.rms * pixel.rms * n / std::max(n - kEdgeParameters, 1.0);
  if (pixel.rms < kMaxRatio * side->rms &&
      n * (side->rms * side->rms - pixel.rms * pixel.rms) > kEvidence * noise_variance) {
    *side = pixel;
  }
}

// The quad's side k, from corner k to k+1: a blurred step fitted in ideal coordinates over
// options.passes passes, each placing the next pass's band with the blur it fitted. The
// line and the square root of its (c, phi) covariance; false when the side is not a clean
// step.
bool FitSide(const cv::Mat& image32f, const IdealPixelMap& map, const EdgeFitOptions& options,
             const std::array<Eigen::Vector2d, 4>& corners,
             const std::array<Eigen::Vector2d, 4>& ideal, const Eigen::Vector2d& centre, size_t k,
             Line* line, Eigen::Matrix2d* line_sqrt_covariance) {
  const Eigen::Vector2d& a = ideal[k];
  const Eigen::Vector2d& b = ideal[(k + 1) % 4];
  line->mid = 0.5 * (a + b);
  Eigen::Vector2d n(-(b - a).y(), (b - a).x());
  n.normalize();
  if (n.dot(line->mid - centre) < 0) n = -n;  // outward: from the dark border to the white
  line->phi = std::atan2(n.y(), n.x());
  const double thickness = BorderThickness(ideal, k, options);
  const double pixel_scale = PixelScaleAt(map, corners[k]);
  const InnerEdge inner = options.model_inner_edge
                              ? ReadInnerEdge(image32f, map, a, b, line->n(), thickness, options)
                              : InnerEdge{};
  SideFit side;
  side.line = *line;
  side.s = 0.8;  // the first pass's start; each next pass's band uses the blur fitted before
  std::vector<Sample> samples;
  for (int pass = 0; pass < options.passes; ++pass) {
    const double band_in = DarkSideWidth(options, thickness, side.s);
    samples = SelectBand(image32f, map, side.line, corners[k], corners[(k + 1) % 4], a, b,
                         options, band_in);
    if (static_cast<int>(samples.size()) < options.min_pixels) return false;
    if (pass == 0 && !InitialLevels(samples, side.line, &side.a, &side.b)) return false;
    // Earlier passes only place the next pass's band: a hundredth of a pixel is enough
    // there; the last converges well below the noise of a line (~1e-3 px).
    const double tolerance_px = pass == options.passes - 1 ? 1e-5 : 1e-2;
    if (!FitEdge(samples, options.iterations, tolerance_px, pixel_scale, BlurStage::kOptical, 0.0,
                 options.fit_shading, inner, &side.line, &side.a, &side.b, &side.s, &side.rms,
                 &side.line_covariance)) {
      return false;
    }
  }
  if (NearPixelAxis(side.line.n(), options.pixel_blur_check_deg)) {
    RefitWithPixelBlur(samples, options, pixel_scale, inner, &side);
  }
  *line = side.line;
  Eigen::LLT<Eigen::Matrix2d> llt(side.line_covariance);
  if (llt.info() != Eigen::Success) return false;
  *line_sqrt_covariance = llt.matrixL();
  // Something else in the band (an occluder, a shadow, a neighbour): not a clean step.
  return side.rms <= options.max_residual * side.b;
}

// The refined corners: each the intersection of its two fitted sides, back in pixels, with
// the direction an erosion of the tag moves it and its noise by the eight line parameters.
// False when two sides do not meet or a corner moved more than options.max_shift_px.
bool CornersFromSides(const IdealPixelMap& map, const EdgeFitOptions& options,
                      const std::array<Line, 4>& lines,
                      const std::array<Eigen::Matrix2d, 4>& line_sqrt_covariance,
                      const std::array<Eigen::Vector2d, 4>& start,
                      std::array<Eigen::Vector2d, 4>* refined,
                      std::array<Eigen::Vector2d, 4>* erosion,
                      std::array<CornerNoisePx, 4>* noise) {
  for (size_t k = 0; k < 4; ++k) {
    // Corner k joins side k-1 (from corner k-1 to k) and side k (from k to k+1).
    const Line& before = lines[(k + 3) % 4];
    Eigen::Vector2d p;
    if (!Intersect(before, lines[k], &p)) return false;
    (*refined)[k] = map.PixelFromIdeal(p);
    if (!(*refined)[k].allFinite() || ((*refined)[k] - start[k]).norm() > options.max_shift_px) {
      return false;
    }
    const double pixel_scale = PixelScaleAt(map, (*refined)[k]);
    (*erosion)[k] = ErosionDirection(map, before, lines[k], p, pixel_scale);
    if (!(*erosion)[k].allFinite()) return false;
    const Eigen::Matrix<double, 2, 4> by_two_lines =
        CornerNoise(PixelJacobian(map, p, pixel_scale), before, line_sqrt_covariance[(k + 3) % 4],
                    lines[k], line_sqrt_covariance[k], p);
    if (!by_two_lines.allFinite()) return false;
    CornerNoisePx& corner_noise = (*noise)[k];
    corner_noise.setZero();
    corner_noise.middleCols<2>(2 * static_cast<Eigen::Index>((k + 3) % 4)) =
        by_two_lines.leftCols<2>();
    corner_noise.middleCols<2>(2 * static_cast<Eigen::Index>(k)) = by_two_lines.rightCols<2>();
  }
  return true;
}

}  // namespace

bool RefineQuadCorners(const cv::Mat& image32f, const IdealPixelMap& map,
                       const EdgeFitOptions& options, std::array<Eigen::Vector2d, 4>* corners,
                       std::array<Eigen::Vector2d, 4>* erosion_px,
                       std::array<CornerNoisePx, 4>* noise_px) {
  if (image32f.type() != CV_32FC1 || image32f.cols != map.width() ||
      image32f.rows != map.height()) {
    return false;
  }
  std::array<Eigen::Vector2d, 4> ideal;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < 4; ++k) {
    ideal[k] = map.IdealFromPixel((*corners)[k]);
    centre += 0.25 * ideal[k];
  }
  std::array<Line, 4> lines;
  std::array<Eigen::Matrix2d, 4> line_sqrt_covariance;
  for (size_t k = 0; k < 4; ++k) {
    if (!FitSide(image32f, map, options, *corners, ideal, centre, k, &lines[k],
                 &line_sqrt_covariance[k])) {
      return false;
    }
  }
  std::array<Eigen::Vector2d, 4> refined, erosion;
  std::array<CornerNoisePx, 4> noise;
  if (!CornersFromSides(map, options, lines, line_sqrt_covariance, *corners, &refined, &erosion,
                        &noise)) {
    return false;
  }
  *corners = refined;
  if (erosion_px != nullptr) *erosion_px = erosion;
  if (noise_px != nullptr) *noise_px = noise;
  return true;
}

}  // namespace h4::cam

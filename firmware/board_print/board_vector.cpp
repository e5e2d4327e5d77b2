// SVG and PDF writers of a board page; see board_print.h. Both are plain text written
// by hand: rectangles in mm are exact, no library can move an edge.
#include <cstdio>
#include <iterator>
#include <vector>

#include <fmt/format.h>

#include "common/text/markup_escape.h"
#include "firmware/board_print/board_print.h"

namespace h4::cam {
namespace {

constexpr double kMmPerM = 1000.0;
constexpr double kPointsPerMm = 72.0 / 25.4;

// mm with 4 decimals (0.1 um): far below any printer's resolution, short files.
std::string Num(double mm) {
  std::string s = fmt::format("{:.4f}", mm);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string PdfEscape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '(' || c == ')' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string BoardSvg(const BoardLayout& layout) {
  const std::string w = Num(layout.width * kMmPerM), h = Num(layout.height * kMmPerM);
  std::string svg = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<!-- h4cam make-board: print at 100% scale; 1 user unit = 1 mm -->\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0}mm\" height=\"{1}mm\" "
      "viewBox=\"0 0 {0} {1}\">\n"
      "<rect x=\"0\" y=\"0\" width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n"
      "<g fill=\"#000000\" shape-rendering=\"crispEdges\">\n",
      w, h);
  auto out = std::back_inserter(svg);
  auto rect = [&out](const PrintRect& r, const char* id) {
    fmt::format_to(out, "<rect{} x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>\n",
                   id ? fmt::format(" id=\"{}\"", id) : "", Num(r.x * kMmPerM), Num(r.y * kMmPerM),
                   Num(r.w * kMmPerM), Num(r.h * kMmPerM));
  };
  for (const auto& r : layout.black) rect(r, nullptr);
  if (layout.scale_bar.w > 0) rect(layout.scale_bar, "scale_bar_100mm");
  svg += "</g>\n";
  for (const auto& t : layout.texts) {
    fmt::format_to(out,
                   "<text x=\"{}\" y=\"{}\" font-family=\"Helvetica, Arial, sans-serif\" "
                   "font-size=\"{}\" fill=\"#000000\">{}</text>\n",
                   Num(t.x * kMmPerM), Num(t.y * kMmPerM), Num(t.size * kMmPerM),
                   MarkupEscape(t.text));
  }
  svg += "</svg>\n";
  return svg;
}

std::string BoardPdf(const BoardLayout& layout) {
  const double h_mm = layout.height * kMmPerM;
  // Content stream in mm (the cm operator scales to points), y up from the bottom edge.
  std::string stream = fmt::format("{0} 0 0 {0} 0 0 cm\n0 g\n", Num(kPointsPerMm));
  auto out = std::back_inserter(stream);
  auto rect = [&](const PrintRect& r) {
    fmt::format_to(out, "{} {} {} {} re\n", Num(r.x * kMmPerM), Num(h_mm - (r.y + r.h) * kMmPerM),
                   Num(r.w * kMmPerM), Num(r.h * kMmPerM));
  };
  for (const auto& r : layout.black) rect(r);
  if (layout.scale_bar.w > 0) rect(layout.scale_bar);
  stream += "f\n";
  for (const auto& t : layout.texts) {
    fmt::format_to(out, "BT /F1 {} Tf {} {} Td ({}) Tj ET\n", Num(t.size * kMmPerM),
                   Num(t.x * kMmPerM), Num(h_mm - t.y * kMmPerM), PdfEscape(t.text));
  }

  const std::string w_pt = Num(layout.width * kMmPerM * kPointsPerMm);
  const std::string h_pt = Num(h_mm * kPointsPerMm);
  const std::vector<std::string> objects = {
      "<< /Type /Catalog /Pages 2 0 R >>",
      "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
      "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + w_pt + " " + h_pt +
          "] /Resources << /Font << /F1 5 0 R >> >> /Contents 4 0 R >>",
      fmt::format("<< /Length {} >>\nstream\n{}endstream", stream.size(), stream),
      "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>",
  };
  std::string pdf = "%PDF-1.4\n%\xE2\xE3\xCF\xD3\n";  // binary marker line, as the spec advises
  std::vector<size_t> offsets;
  for (size_t i = 0; i < objects.size(); ++i) {
    offsets.push_back(pdf.size());
    pdf += fmt::format("{} 0 obj\n{}\nendobj\n", i + 1, objects[i]);
  }
  const size_t xref = pdf.size();
  pdf += fmt::format("xref\n0 {}\n0000000000 65535 f \n", objects.size() + 1);
  for (const size_t offset : offsets) {
    pdf += fmt::format("{:010} 00000 n \n", offset);  // 20 bytes each
  }
  pdf += fmt::format("trailer\n<< /Size {} /Root 1 0 R >>\nstartxref\n{}\n%%EOF\n",
                     objects.size() + 1, xref);
  return pdf;
}

}  // namespace h4::cam

// SVG and PDF writers of a board page; see board_print.h. Both are plain text written
// by hand: rectangles in mm are exact, no library can move an edge.
#include <cstdio>
#include <sstream>
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
  const double w = layout.width * kMmPerM, h = layout.height * kMmPerM;
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<!-- h4cam make-board: print at 100% scale; 1 user unit = 1 mm -->\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" << Num(w)
      << "mm\" height=\"" << Num(h) << "mm\" viewBox=\"0 0 " << Num(w) << " " << Num(h) << "\">\n"
      << "<rect x=\"0\" y=\"0\" width=\"" << Num(w) << "\" height=\"" << Num(h)
      << "\" fill=\"#ffffff\"/>\n"
      << "<g fill=\"#000000\" shape-rendering=\"crispEdges\">\n";
  auto rect = [&out](const PrintRect& r, const char* id) {
    out << "<rect" << (id ? std::string(" id=\"") + id + "\"" : "") << " x=\"" << Num(r.x * kMmPerM)
        << "\" y=\"" << Num(r.y * kMmPerM) << "\" width=\"" << Num(r.w * kMmPerM) << "\" height=\""
        << Num(r.h * kMmPerM) << "\"/>\n";
  };
  for (const auto& r : layout.black) rect(r, nullptr);
  if (layout.scale_bar.w > 0) rect(layout.scale_bar, "scale_bar_100mm");
  out << "</g>\n";
  for (const auto& t : layout.texts) {
    out << "<text x=\"" << Num(t.x * kMmPerM) << "\" y=\"" << Num(t.y * kMmPerM)
        << "\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"" << Num(t.size * kMmPerM)
        << "\" fill=\"#000000\">" << MarkupEscape(t.text) << "</text>\n";
  }
  out << "</svg>\n";
  return out.str();
}

std::string BoardPdf(const BoardLayout& layout) {
  const double h_mm = layout.height * kMmPerM;
  // Content stream in mm (the cm operator scales to points), y up from the bottom edge.
  std::ostringstream content;
  content << Num(kPointsPerMm) << " 0 0 " << Num(kPointsPerMm) << " 0 0 cm\n0 g\n";
  auto rect = [&](const PrintRect& r) {
    content << Num(r.x * kMmPerM) << " " << Num(h_mm - (r.y + r.h) * kMmPerM) << " "
            << Num(r.w * kMmPerM) << " " << Num(r.h * kMmPerM) << " re\n";
  };
  for (const auto& r : layout.black) rect(r);
  if (layout.scale_bar.w > 0) rect(layout.scale_bar);
  content << "f\n";
  for (const auto& t : layout.texts) {
    content << "BT /F1 " << Num(t.size * kMmPerM) << " Tf " << Num(t.x * kMmPerM) << " "
            << Num(h_mm - t.y * kMmPerM) << " Td (" << PdfEscape(t.text) << ") Tj ET\n";
  }
  const std::string stream = content.str();

  const std::string w_pt = Num(layout.width * kMmPerM * kPointsPerMm);
  const std::string h_pt = Num(h_mm * kPointsPerMm);
  const std::vector<std::string> objects = {
      "<< /Type /Catalog /Pages 2 0 R >>",
      "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
      "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 " + w_pt + " " + h_pt +
          "] /Resources << /Font << /F1 5 0 R >> >> /Contents 4 0 R >>",
      "<< /Length " + std::to_string(stream.size()) + " >>\nstream\n" + stream + "endstream",
      "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>",
  };
  std::string pdf = "%PDF-1.4\n%\xE2\xE3\xCF\xD3\n";  // binary marker line, as the spec advises
  std::vector<size_t> offsets;
  for (size_t i = 0; i < objects.size(); ++i) {
    offsets.push_back(pdf.size());
    pdf += std::to_string(i + 1) + " 0 obj\n" + objects[i] + "\nendobj\n";
  }
  const size_t xref = pdf.size();
  pdf += "xref\n0 " + std::to_string(objects.size() + 1) + "\n0000000000 65535 f \n";
  for (const size_t offset : offsets) {
    pdf += fmt::format("{:010} 00000 n \n", offset);  // 20 bytes each
  }
  pdf += "trailer\n<< /Size " + std::to_string(objects.size() + 1) +
         " /Root 1 0 R >>\nstartxref\n" + std::to_string(xref) + "\n%%EOF\n";
  return pdf;
}

}  // namespace h4::cam

// Escaping text for XML and HTML (SVG boards written by h4cam, HTML reports written by
// h4cal): the one place both sides take it from.
#pragma once

#include <string>

namespace h4 {

/// Replaces & < > " with their entities, so the text is safe in element content and in
/// double-quoted attributes of XML, SVG and HTML.
std::string MarkupEscape(const std::string& text);

}  // namespace h4

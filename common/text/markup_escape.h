// Escaping text for XML and HTML (SVG boards written by h4cam, HTML reports written by
// h4cal): the one place both sides take it from.
#pragma once

#include <string>

namespace h4 {

/// Replaces & < > " with their entities, so the text is safe in element content and in
/// double-quoted attributes of XML, SVG and HTML.
std::string MarkupEscape(const std::string& text);

/// A link to the file `path` relative to the page (a name beside it, or below it): "./" and
/// the path percent-encoded but for A-Z a-z 0-9 - . _ ~ /, so that no name can make it a
/// scheme ("javascript:alert(1);x.yaml" becomes "./javascript%3Aalert%281%29%3Bx.yaml") or
/// break out of an attribute. Safe in a double-quoted href or src as it is.
std::string RelativeFileUrl(const std::string& path);

}  // namespace h4

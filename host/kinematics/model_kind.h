// Which of the two kinematic models of an H4 (common/README.md): Model 12, the design
// model, or Model 31, the calibration model. The code passes ModelKind; the text "12" /
// "31" exists only at the edges: command-line options, the result JSON and truth.yaml
// (common/formats/README.md).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace h4 {

enum class ModelKind { k12, k31 };

/// "12" or "31", as the files and the command line write it.
constexpr const char* ToString(ModelKind kind) { return kind == ModelKind::k12 ? "12" : "31"; }

/// "Model 12" or "Model 31", for messages.
inline std::string ModelLabel(ModelKind kind) { return std::string("Model ") + ToString(kind); }

/// Parses "12" or "31"; nullopt for any other text.
constexpr std::optional<ModelKind> ParseModelKind(std::string_view text) {
  if (text == "12") return ModelKind::k12;
  if (text == "31") return ModelKind::k31;
  return std::nullopt;
}

}  // namespace h4

#pragma once

// For tests of the localizer's settings: the shipped configs/localizer.yaml, as text to edit
// and load again.

#include <string>

#include "common/config_paths.h"
#include "common/strict_yaml.h"
#include "localizer/localizer_config.h"

namespace stickrep::localizer {

inline std::string Shipped() { return ReadYamlText(DefaultConfigDir() + "/localizer.yaml"); }

// `text` read as the shipped file (named by its real path, so that the error model files it
// names resolve).
inline LocalizerSettings Load(const std::string& text) {
  return LoadLocalizerSettings(
      StrictYaml::LoadString(text, DefaultConfigDir() + "/localizer.yaml").Child("localizer"));
}

}  // namespace stickrep::localizer

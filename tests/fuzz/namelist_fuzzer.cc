// fit3dof: aerodynamic coefficients from 3DOF gas-bearing motion.
//
// libFuzzer harness: a legacy NAMELIST deck (tools/fuzz). Parsing, the
// deck's runs and each run's config must end in a value or an InputError.

#include <cstddef>
#include <cstdint>
#include <string>

#include "config_node.h"
#include "fit3dof/input_error.h"
#include "fit3dof/namelist.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const fit3dof::Deck deck = fit3dof::ParseDeck(text, "fuzz.deck");
    for (const fit3dof::DeckRun& run : fit3dof::DeckRuns(deck, "data.csv")) {
      try {
        fit3dof::ParseConfigNode(
            fit3dof::ParseYamlText(run.config_yaml, "fuzz.deck"),
            "fuzz.deck",
            "/nonexistent",
            false);
      } catch (const fit3dof::InputError&) {
      }
    }
  } catch (const fit3dof::InputError&) {
  }
  return 0;
}

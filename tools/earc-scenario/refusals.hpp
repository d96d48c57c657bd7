// What earc-scenario's subcommands share: the generators' refusals are
// about what the user asked for, so they are bad input (one line, exit 2)
// naming the option, not failures of the program (exit 1).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "earc/gen/generators.hpp"
#include "earc/io/input_error.hpp"

namespace earc::scenario_cli {

// make() with SettingError and CrowdedError as InputError; `file` names
// the input the scenario is made from ("" for none).
template <class Make>
Scenario generateOrRefuse(const std::string& file, Make make) {
  try {
    return make();
  } catch (const gen::SettingError& e) {
    // Every setting a user can give is an option of the same name.
    throw InputError(file, "--" + e.setting(), e.reason());
  } catch (const gen::CrowdedError& e) {
    throw InputError(file, "--robots", e.what());
  }
}

// --radius is the disc's; with a box it would be ignored without a word.
inline void requireDiscForRadius(const CLI::Option* shape, const std::string& shape_value, const CLI::Option* radius) {
  if (radius->count() && shape_value != "disc")
    throw CLI::ValidationError("--radius", std::string("applies to --shape disc only") +
                                               (shape->count() ? "" : " (the default shape is box)"));
}

}  // namespace earc::scenario_cli

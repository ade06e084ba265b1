#pragma once
/// @file
/// Command-line options generated from a declared parameter table
/// (talus/core/parameter_table.hpp): one option per parameter, spelled
/// --kebab-case (a flag whose default is true: --no-kebab-case), its help
/// the parameter's documentation and accepted values, its default shown,
/// and its value parsed and checked by the table as it is read (a bad value
/// is an InputError naming the option, before anything is loaded).
#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "talus/core/parameter_table.hpp"

namespace talus::experiments {

template <class Options>
void add_parameter_options(CLI::App& app, const ParameterTable<Options>& table, Options& target) {
  using Table = ParameterTable<Options>;
  for (const Parameter<Options>& p : table.entries()) {
    const std::string spelling = Table::spelled(p, ParameterSpelling::kCli);
    const std::string name = p.name;
    if (p.kind == ParameterKind::kFlag) {
      // Both spellings: --name turns it on, --no-name off (a negated flag
      // counts negatively); the help lists the one that changes the default.
      const bool on_by_default = std::get<bool>(Table::default_value(p));
      const std::string positive = cli_spelling(p.name);
      const std::string negative = "--no-" + positive.substr(2);
      app.add_flag_function(
          on_by_default ? negative + ",!" + positive : positive + ",!" + negative,
          [&table, &target, name, on_by_default](std::int64_t count) {
            table.set(target, name, on_by_default ? count < 0 : count > 0);
          },
          (on_by_default ? "(on by default; this turns it off) " : "") + p.doc);
      continue;
    }
    app.add_option_function<std::string>(
           spelling,
           [&table, &target, name](const std::string& text) {
             table.set_text(target, name, text, ParameterSpelling::kCli);
           },
           p.doc + "; " + Table::accepted(p))
        ->default_str(value_text(Table::default_value(p)))
        ->type_name(p.kind == ParameterKind::kInteger       ? "INT"
                    : p.kind == ParameterKind::kReal        ? "FLOAT"
                    : p.kind == ParameterKind::kIntegerList ? "INT,..."
                                                            : "TEXT");
  }
}

}  // namespace talus::experiments

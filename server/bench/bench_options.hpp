// Flags that several lgh-bench subcommands share, with the same checks and help: positive
// numbers (lists of them comma separated), names of an enum, the frame size, timed and untimed
// iterations. Each helper adds the option as the subcommands spelled it out before: the
// delimiter, then the check, then the default shown in --help.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli_common.hpp"

namespace lgh::bench {

namespace detail {
template <typename T>
inline constexpr bool kIsList = false;
template <typename T>
inline constexpr bool kIsList<std::vector<T>> = true;

template <typename T>
CLI::Option* addChecked(CLI::App& sub, const std::string& name, T& value,
                        const std::string& description, const CLI::Validator& check) {
  CLI::Option* option = sub.add_option(name, value, description);
  if constexpr (kIsList<T>) option->delimiter(',');
  return option->check(check)->capture_default_str();
}
}  // namespace detail

// A positive number, or a comma-separated list of them.
template <typename T>
CLI::Option* addPositiveOption(CLI::App& sub, const std::string& name, T& value,
                               const std::string& description) {
  return detail::addChecked(sub, name, value, description, CLI::PositiveNumber);
}

// A name of `Enum` (EnumNames) but those in `skip`, or a comma-separated list of them.
template <typename Enum, typename T>
CLI::Option* addEnumOption(CLI::App& sub, const std::string& name, T& value,
                           const std::string& description,
                           std::initializer_list<std::string_view> skip = {}) {
  return detail::addChecked(sub, name, value, description,
                            CLI::IsMember(cli::enumChoices<Enum>(skip)));
}

// --width and --height of the frames.
inline void addFrameSizeOptions(CLI::App& sub, int& width, int& height) {
  addPositiveOption(sub, "--width", width, "frame width");
  addPositiveOption(sub, "--height", height, "frame height");
}

// --iterations (timed, at least one) and --warmup (untimed first): "timed frames per run",
// "untimed frames first".
inline void addIterationOptions(CLI::App& sub, int& iterations, const std::string& timed,
                                int& warmup, const std::string& untimed) {
  addPositiveOption(sub, "--iterations", iterations, timed);
  detail::addChecked(sub, "--warmup", warmup, untimed, CLI::NonNegativeNumber);
}

}  // namespace lgh::bench

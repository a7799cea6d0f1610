#pragma once
// Bounded JSON input: every JSON text ambid reads (sidecars, model files, daemon configs,
// scenarios) is checked for size and nesting depth before a parser sees it, so a hostile or
// broken file costs at most a linear scan (nlohmann's parse cost and memory grow with depth).
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace ambid {

// Far above any contract file (a sidecar with a 64-state controller is ~200 KB), far below
// what would stall a daemon.
inline constexpr std::size_t kMaxJsonBytes = 16u << 20;
inline constexpr int kMaxJsonDepth = 64;  // the contract nests at most 4 levels

// Throws Error "JSON text of N bytes exceeds the limit of M bytes" or "JSON nested deeper than
// 64 levels (at byte K)". Brackets inside strings do not count.
void check_json_bounds(std::string_view text);

// read_text_file refusing files over kMaxJsonBytes before reading them. Errors name the file.
std::string read_json_file(const std::filesystem::path& path);

// check_json_bounds + parse. Throws Error "malformed JSON: ..." naming the parse position.
nlohmann::json parse_json_text(std::string_view text);

}  // namespace ambid

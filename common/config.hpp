#pragma once
// Typed configuration from TOML. A stage describes each key it reads (type,
// default, unit, allowed range, one line of help) at the point where it reads
// it; afterwards every key in the file that nobody read is rejected. The
// same descriptions produce --print-config, so the documentation of a key
// and its check cannot drift apart.

#include <toml++/toml.h>

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace aniso::config {

/// Closed or open interval of allowed values.
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_inclusive = true;
  bool max_inclusive = true;

  [[nodiscard]] bool contains(double value) const;
  [[nodiscard]] std::string describe() const; ///< for example "(0, 1]"

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), false, true}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), true, true}; }
  static Range closed(double low, double high) { return {low, high, true, true}; }
  static Range open_closed(double low, double high) { return {low, high, false, true}; }
  static Range open(double low, double high) { return {low, high, false, false}; }
};

/// Reads typed values from a TOML table, records what it read, and rejects the rest.
class Reader {
public:
  /// `source` names where the table came from (a file path, or "defaults") for messages.
  Reader(toml::table table, std::string source);

  /// Keys are dotted paths such as "dem.material.shear_modulus".
  double real(std::string_view key, double fallback, std::string_view unit, Range range,
              std::string_view help);
  std::int64_t integer(std::string_view key, std::int64_t fallback, Range range, std::string_view help);
  bool boolean(std::string_view key, bool fallback, std::string_view help);
  /// One of a fixed set of words.
  std::string choice(std::string_view key, std::string_view fallback, const std::vector<std::string>& allowed,
                     std::string_view help);
  /// Free text such as a file path.
  std::string text(std::string_view key, std::string_view fallback, std::string_view help);
  /// A list of reals, each in range; `min_count` elements at least.
  std::vector<double> reals(std::string_view key, const std::vector<double>& fallback, std::string_view unit,
                            Range range, std::size_t min_count, std::string_view help);

  /// Top-level sections that belong to other stages: tolerated, not checked here.
  void tolerate_sections(const std::vector<std::string>& sections);
  /// Throws InputError naming every key present in the table that was never read.
  void reject_unknown() const;
  /// The effective configuration (every key read, with defaults filled in) as commented TOML.
  [[nodiscard]] std::string effective_toml() const;

  /// True when the table (the config file or a --set) gives this key.
  [[nodiscard]] bool given(std::string_view key) const { return find(key) != nullptr; }
  /// Records another value for a key already read (one that an input file fixes), with a note
  /// on where it came from, so that the effective configuration says what was used.
  void replace(std::string_view key, std::string value_toml, std::string_view note);

private:
  struct Entry {
    std::string key;
    std::string value_toml;
    std::string unit;
    std::string allowed;
    std::string help;
  };
  const toml::node* find(std::string_view key) const;
  void remember(std::string_view key, std::string value_toml, std::string_view unit, std::string allowed,
                std::string_view help);

  toml::table table_;
  std::string source_;
  std::vector<Entry> entries_;
  std::vector<std::string> tolerated_;
};

/// Parses a TOML file; a syntax error names the file, line and column.
toml::table load_file(const std::string& path);
/// Applies one `key=value` override (value in TOML syntax; bare words are taken as strings).
void apply_override(toml::table& table, std::string_view assignment);

} // namespace aniso::config

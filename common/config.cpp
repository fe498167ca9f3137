#include "common/config.hpp"

#include "common/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace aniso::config {
namespace {

std::string node_text(const toml::node& node) {
  std::ostringstream out;
  node.visit([&out](const auto& value) { out << value; });
  return out.str();
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
  case toml::node_type::string: return "a string";
  case toml::node_type::integer: return "an integer";
  case toml::node_type::floating_point: return "a real number";
  case toml::node_type::boolean: return "a boolean";
  case toml::node_type::array: return "an array";
  case toml::node_type::table: return "a table";
  default: return "a date or time";
  }
}

std::string format_real(double value) {
  return fmt::format("{}", value);
}

double as_real(const toml::node& node, std::string_view key, const std::string& source) {
  if (const auto* real = node.as_floating_point()) return real->get();
  if (const auto* integer = node.as_integer()) return static_cast<double>(integer->get());
  throw InputError(fmt::format("config key '{}' in {}: value {} is {}, expected a real number", key, source,
                               node_text(node), type_name(node)));
}

void collect_leaf_keys(const toml::table& table, const std::string& prefix, const std::string& source,
                       std::vector<std::string>& keys) {
  for (const auto& [name, node] : table) {
    // A quoted key with a dot ("dem.seed" = 7) is one key named dem.seed, not dem -> seed: it
    // would match a known key's spelling here and yet never be read.
    if (name.str().find('.') != std::string_view::npos) {
      throw InputError(fmt::format("config key \"{}\"{} in {}: a quoted key must not contain a dot; write "
                                   "{} = ... without quotes, or as a [table]",
                                   name.str(), prefix.empty() ? "" : " of [" + prefix + "]", source,
                                   name.str()));
    }
    const std::string key = prefix.empty() ? std::string(name.str()) : prefix + "." + std::string(name.str());
    if (const auto* child = node.as_table()) {
      collect_leaf_keys(*child, key, source, keys);
    } else {
      keys.push_back(key);
    }
  }
}

} // namespace

bool Range::contains(double value) const {
  // No setting is infinite: an unbounded range means "any finite value" (inf as a density or
  // a pressure made runs that never end).
  if (!std::isfinite(value)) return false;
  const bool above = min_inclusive ? value >= min : value > min;
  const bool below = max_inclusive ? value <= max : value < max;
  return above && below;
}

std::string Range::describe() const {
  const auto bound = [](double value) {
    if (std::isinf(value)) return std::string(value > 0 ? "inf" : "-inf");
    return format_real(value);
  };
  return fmt::format("{}{}, {}{}", min_inclusive && !std::isinf(min) ? '[' : '(', bound(min), bound(max),
                     max_inclusive && !std::isinf(max) ? ']' : ')');
}

Reader::Reader(toml::table table, std::string source)
    : table_(std::move(table)), source_(std::move(source)) {}

const toml::node* Reader::find(std::string_view key) const {
  const toml::node_view<const toml::node> view = table_.at_path(key);
  return view.node();
}

void Reader::remember(std::string_view key, std::string value_toml, std::string_view unit,
                      std::string allowed, std::string_view help) {
  entries_.push_back(
      {std::string(key), std::move(value_toml), std::string(unit), std::move(allowed), std::string(help)});
}

void Reader::replace(std::string_view key, std::string value_toml, std::string_view note) {
  for (Entry& entry : entries_) {
    if (entry.key != key) continue;
    entry.value_toml = std::move(value_toml);
    entry.help = std::string(note) + "; " + entry.help;
    return;
  }
  throw Error(ExitCode::internal_error, fmt::format("config key '{}' replaced before it was read", key));
}

double Reader::real(std::string_view key, double fallback, std::string_view unit, Range range,
                    std::string_view help) {
  const toml::node* node = find(key);
  const double value = node ? as_real(*node, key, source_) : fallback;
  if (!range.contains(value)) {
    // A dimensionless unit ("1") would read as a second number: "value 0.7 1 is out of range".
    const std::string with_unit = unit.empty() || unit == "1" ? "" : " " + std::string(unit);
    throw InputError(fmt::format("config key '{}' in {}: value {}{} is out of range, expected {} ({})", key,
                                 node ? source_ : "defaults", format_real(value), with_unit, range.describe(),
                                 help));
  }
  remember(key, format_real(value), unit, range.describe(), help);
  return value;
}

std::int64_t Reader::integer(std::string_view key, std::int64_t fallback, Range range,
                             std::string_view help) {
  const toml::node* node = find(key);
  std::int64_t value = fallback;
  if (node) {
    const auto* integer_node = node->as_integer();
    if (!integer_node) {
      throw InputError(fmt::format("config key '{}' in {}: value {} is {}, expected an integer", key, source_,
                                   node_text(*node), type_name(*node)));
    }
    value = integer_node->get();
  }
  if (!range.contains(static_cast<double>(value))) {
    throw InputError(fmt::format("config key '{}' in {}: value {} is out of range, expected {} ({})", key,
                                 node ? source_ : "defaults", value, range.describe(), help));
  }
  remember(key, std::to_string(value), "", range.describe(), help);
  return value;
}

bool Reader::boolean(std::string_view key, bool fallback, std::string_view help) {
  const toml::node* node = find(key);
  bool value = fallback;
  if (node) {
    const auto* boolean_node = node->as_boolean();
    if (!boolean_node) {
      throw InputError(fmt::format("config key '{}' in {}: value {} is {}, expected true or false", key,
                                   source_, node_text(*node), type_name(*node)));
    }
    value = boolean_node->get();
  }
  remember(key, value ? "true" : "false", "", "true | false", help);
  return value;
}

std::string Reader::choice(std::string_view key, std::string_view fallback,
                           const std::vector<std::string>& allowed, std::string_view help) {
  const std::string value = text(key, fallback, help);
  entries_.pop_back(); // re-recorded below with the allowed words
  std::string words;
  for (const auto& word : allowed)
    words += (words.empty() ? "" : " | ") + word;
  if (std::find(allowed.begin(), allowed.end(), value) == allowed.end()) {
    throw InputError(
        fmt::format("config key '{}' in {}: value \"{}\" is not allowed, expected one of {} ({})", key,
                    source_, value, words, help));
  }
  remember(key, fmt::format("\"{}\"", value), "", words, help);
  return value;
}

std::string Reader::text(std::string_view key, std::string_view fallback, std::string_view help) {
  const toml::node* node = find(key);
  std::string value(fallback);
  if (node) {
    const auto* string_node = node->as_string();
    if (!string_node) {
      throw InputError(fmt::format("config key '{}' in {}: value {} is {}, expected a string", key, source_,
                                   node_text(*node), type_name(*node)));
    }
    value = string_node->get();
  }
  remember(key, fmt::format("\"{}\"", value), "", "text", help);
  return value;
}

std::vector<double> Reader::reals(std::string_view key, const std::vector<double>& fallback,
                                  std::string_view unit, Range range, std::size_t min_count,
                                  std::string_view help) {
  const toml::node* node = find(key);
  std::vector<double> values = fallback;
  if (node) {
    const auto* array = node->as_array();
    if (!array) {
      throw InputError(fmt::format("config key '{}' in {}: value {} is {}, expected an array of real numbers",
                                   key, source_, node_text(*node), type_name(*node)));
    }
    values.clear();
    for (const auto& element : *array)
      values.push_back(as_real(element, key, source_));
  }
  if (values.size() < min_count) {
    throw InputError(fmt::format("config key '{}' in {}: {} values given, expected at least {} ({})", key,
                                 source_, values.size(), min_count, help));
  }
  std::string listing;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!range.contains(values[i])) {
      throw InputError(
          fmt::format("config key '{}' in {}: element {} = {} {} is out of range, expected {} ({})", key,
                      source_, i, format_real(values[i]), unit, range.describe(), help));
    }
    if (i > 0) listing += ", "; // piecewise, as in join_command_line (GCC 12, LTO)
    listing += format_real(values[i]);
  }
  remember(key, "[" + listing + "]", unit, "each in " + range.describe(), help);
  return values;
}

void Reader::tolerate_sections(const std::vector<std::string>& sections) {
  tolerated_.insert(tolerated_.end(), sections.begin(), sections.end());
}

void Reader::reject_unknown() const {
  std::vector<std::string> keys;
  collect_leaf_keys(table_, "", source_, keys);
  std::vector<std::string> unknown;
  for (const auto& key : keys) {
    const std::string section = key.substr(0, key.find('.'));
    const bool tolerated = key.find('.') != std::string::npos &&
                           std::find(tolerated_.begin(), tolerated_.end(), section) != tolerated_.end();
    const bool known =
        std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == key; });
    if (!known && !tolerated) unknown.push_back(key);
  }
  if (unknown.empty()) return;
  std::string listing;
  for (const auto& key : unknown)
    listing += (listing.empty() ? "'" : ", '") + key + "'";
  throw InputError(
      fmt::format("unknown config key{} {} in {} (--print-config lists the keys this program accepts)",
                  unknown.size() > 1 ? "s" : "", listing, source_));
}

std::string Reader::effective_toml() const {
  // Group keys by their table so the output is itself a valid TOML file.
  std::vector<Entry> sorted = entries_;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Entry& a, const Entry& b) {
    const auto table_of = [](const std::string& key) {
      const auto dot = key.rfind('.');
      return dot == std::string::npos ? std::string() : key.substr(0, dot);
    };
    return table_of(a.key) < table_of(b.key);
  });
  std::string out;
  std::string current_table;
  for (const auto& entry : sorted) {
    const auto dot = entry.key.rfind('.');
    const std::string table = dot == std::string::npos ? "" : entry.key.substr(0, dot);
    const std::string name = dot == std::string::npos ? entry.key : entry.key.substr(dot + 1);
    if (table != current_table || out.empty()) {
      if (!table.empty()) out += fmt::format("{}[{}]\n", out.empty() ? "" : "\n", table);
      current_table = table;
    }
    std::string comment = entry.help;
    if (!entry.unit.empty() && entry.unit != "1") comment += fmt::format(" [{}]", entry.unit);
    comment += fmt::format("; allowed: {}", entry.allowed);
    out += fmt::format("{} = {}  # {}\n", name, entry.value_toml, comment);
  }
  return out;
}

toml::table load_file(const std::string& path) {
  std::error_code status;
  require_file(std::filesystem::exists(path, status), fmt::format("config file '{}' does not exist", path));
  require_file(!std::filesystem::is_directory(path, status),
               fmt::format("config file '{}' is a folder, not a file", path));
  try {
    return toml::parse_file(path);
  } catch (const toml::parse_error& error) {
    const auto& where = error.source().begin;
    if (where.line == 0)
      throw FileError(fmt::format("cannot read config file '{}': {}", path, error.description()));
    throw InputError(fmt::format("config file '{}' line {} column {}: {}", path, where.line, where.column,
                                 error.description()));
  }
}

void apply_override(toml::table& table, std::string_view assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string_view::npos || equals == 0) {
    throw InputError(fmt::format("--set '{}': expected key=value, for example --set dem.particles.count=1000",
                                 assignment));
  }
  const std::string key(assignment.substr(0, equals));
  const std::string value(assignment.substr(equals + 1));
  toml::table parsed;
  try {
    parsed = toml::parse("value = " + value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"value", value}}; // a bare word is a string
  }
  // Walk or create the tables along the dotted path, then set the leaf.
  toml::table* current = &table;
  std::size_t start = 0;
  for (auto dot = key.find('.'); dot != std::string::npos; dot = key.find('.', start)) {
    const std::string part = key.substr(start, dot - start);
    auto* child = current->get(part);
    if (!child) {
      current->insert(part, toml::table{});
      child = current->get(part);
    }
    if (!child->is_table()) {
      throw InputError(
          fmt::format("--set '{}': '{}' is a value, not a table", assignment, key.substr(0, dot)));
    }
    current = child->as_table();
    start = dot + 1;
  }
  const std::string leaf = key.substr(start);
  if (leaf.empty()) throw InputError(fmt::format("--set '{}': empty key", assignment));
  current->insert_or_assign(leaf, *parsed.get("value"));
}

} // namespace aniso::config

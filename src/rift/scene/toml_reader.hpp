// A strict reader over one TOML table: typed getters that report the key and its position, and a
// finish() that rejects keys nobody asked for (typos must not be silently ignored).
#pragma once
#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rift/core/error.hpp"

namespace rift::scene {

class TomlReader {
 public:
  TomlReader(const toml::table& table, std::string path, std::string file)
      : table_(table), path_(std::move(path)), file_(std::move(file)) {}

  SourceLocation where() const { return at(table_); }
  SourceLocation where(const std::string& key) const {
    const toml::node* n = table_.get(key);
    return n ? at(*n) : where();
  }
  std::string key(const std::string& k) const { return path_.empty() ? k : path_ + "." + k; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  bool has(const std::string& k) {
    seen_.insert(k);
    return table_.contains(k);
  }
  const toml::node* node(const std::string& k) {
    seen_.insert(k);
    return table_.get(k);
  }

  [[noreturn]] void fail(const std::string& k, const std::string& msg) const {
    throw SceneError(where(k), key(k), msg);
  }

  std::optional<double> number(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return std::nullopt;
    if (auto v = n->value<double>(); v && (n->is_floating_point() || n->is_integer())) {
      if (!std::isfinite(*v)) fail(k, "must be a finite number, got " + fmt_double(*v));
      return *v;
    }
    fail(k, "expected a number, got " + type_name(*n));
  }
  double number(const std::string& k, double fallback) { return number(k).value_or(fallback); }
  double required_number(const std::string& k, const std::string& meaning) {
    auto v = number(k);
    if (!v) throw SceneError(where(), key(k), "missing required key (" + meaning + ")");
    return *v;
  }
  double positive(const std::string& k, double v) const {
    if (!(v > 0.0)) fail(k, "must be > 0, got " + fmt_double(v));
    return v;
  }
  double non_negative(const std::string& k, double v) const {
    if (!(v >= 0.0)) fail(k, "must be >= 0, got " + fmt_double(v));
    return v;
  }
  std::optional<long long> integer(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return std::nullopt;
    if (!n->is_integer()) fail(k, "expected an integer, got " + type_name(*n));
    return *n->value<long long>();
  }
  /// An integer in [lo, hi] (64 bits read, then bounded by what the code that takes it holds);
  /// `meaning` says what it counts, for the message.
  std::optional<long long> count(const std::string& k, long long lo, long long hi, const std::string& meaning) {
    auto v = integer(k);
    if (v && (*v < lo || *v > hi))
      fail(k, "must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + " (" + meaning + "), got " + std::to_string(*v));
    return v;
  }
  std::optional<bool> boolean(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return std::nullopt;
    if (!n->is_boolean()) fail(k, "expected true or false, got " + type_name(*n));
    return *n->value<bool>();
  }
  std::optional<std::string> string(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return std::nullopt;
    if (!n->is_string()) fail(k, "expected a string, got " + type_name(*n));
    return *n->value<std::string>();
  }
  std::optional<std::string> choice(const std::string& k, const std::vector<std::string>& allowed) {
    auto s = string(k);
    if (!s) return s;
    for (const auto& a : allowed)
      if (*s == a) return s;
    fail(k, "unknown value \"" + *s + "\"; allowed: " + join(allowed));
  }
  /// A list of exactly `count` numbers (count < 0: any length >= 1).
  std::optional<std::vector<double>> numbers(const std::string& k, int count) {
    const toml::node* n = node(k);
    if (!n) return std::nullopt;
    return numbers_of(*n, k, count);
  }
  std::vector<double> numbers_of(const toml::node& n, const std::string& k, int count) const {
    const toml::array* a = n.as_array();
    if (!a) fail(k, "expected an array of " + count_text(count) + " numbers, got " + type_name(n));
    if ((count >= 0 && static_cast<int>(a->size()) != count) || a->empty())
      fail(k, "expected " + count_text(count) + " numbers, got " + std::to_string(a->size()));
    std::vector<double> out;
    for (const auto& e : *a) {
      auto v = e.value<double>();
      if (!v || !(e.is_integer() || e.is_floating_point()))
        throw SceneError(at(e), key(k), "expected a number, got " + type_name(e));
      if (!std::isfinite(*v)) throw SceneError(at(e), key(k), "must be finite numbers, got " + fmt_double(*v));
      out.push_back(*v);
    }
    return out;
  }
  std::optional<std::vector<std::string>> strings(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return std::nullopt;
    const toml::array* a = n->as_array();
    if (!a) fail(k, "expected an array of strings, got " + type_name(*n));
    std::vector<std::string> out;
    for (const auto& e : *a) {
      if (!e.is_string()) throw SceneError(at(e), key(k), "expected a string, got " + type_name(e));
      out.push_back(*e.value<std::string>());
    }
    return out;
  }
  const toml::table* table(const std::string& k) {
    const toml::node* n = node(k);
    if (!n) return nullptr;
    if (!n->is_table()) fail(k, "expected a table, got " + type_name(*n));
    return n->as_table();
  }

  /// Reject every key that was not asked for.
  void finish(const std::vector<std::string>& allowed) const {
    for (const auto& [k, v] : table_) {
      std::string name(k.str());
      if (!seen_.count(name))
        throw SceneError(at(v), key(name), "unknown key; allowed here: " + join(allowed));
    }
  }

  SourceLocation at(const toml::node& n) const {
    const auto& s = n.source();
    return {file_, static_cast<int>(s.begin.line), static_cast<int>(s.begin.column)};
  }
  static std::string type_name(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::table: return "a table";
      case toml::node_type::array: return "an array";
      case toml::node_type::string: return "a string";
      case toml::node_type::integer: return "an integer";
      case toml::node_type::floating_point: return "a number";
      case toml::node_type::boolean: return "a boolean";
      default: return "a date/time";
    }
  }
  static std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
    return s;
  }
  static std::string fmt_double(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
  }

 private:
  static std::string count_text(int c) { return c < 0 ? "one or more" : std::to_string(c); }
  const toml::table& table_;
  std::string path_, file_;
  std::set<std::string> seen_;
};

}  // namespace rift::scene

// A declarative description of one configuration key. Every key a user may
// write is described by a Param, so that validation, defaults, the config
// reference in docs/ and a driver's self-description all come from one place.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "pbms/units.hpp"

namespace pbms::config {

enum class ParamKind {
  kInteger,
  kReal,  // number, or "value unit" when a dimension is set
  kBoolean,
  kString,
  kName,      // identifier: [A-Za-z_][A-Za-z0-9_.-]*
  kFile,      // path to a file that must exist and be readable
  kPath,      // path that need not exist (an output directory)
  kChoice,    // one of `choices`
  kRealList,  // list of kReal
  kIntList,   // list of kInteger
  kMap,       // fixed keys (`fields`); with a discriminator, extra keys per variant
  kMapOf,     // user-named entries, each described by `fields[0]`
  kListOf,    // list, each element described by `fields[0]`
  kTable,     // a table output of an earlier stage, written {from: <stage>.<table>}
};

std::string_view kind_name(ParamKind k);

struct Param {
  std::string name;
  ParamKind kind = ParamKind::kString;
  std::string doc;
  units::Dimension dimension = units::Dimension::kNone;
  bool required = false;
  std::optional<YAML::Node> default_value;
  std::optional<double> min, max;
  bool min_exclusive = false, max_exclusive = false;
  std::optional<size_t> min_length, max_length;
  // Lists: the only lengths allowed, when not every length in between is
  // (one number for all axes, or one per axis: {1, 3}).
  std::vector<size_t> lengths;
  std::vector<std::string> choices;
  bool allow_reference = false;  // may be {from: <stage>.<output>}
  bool names_material = false;   // value must name an entry of `materials`
  bool allow_auto = false;       // kReal may also be the word `auto`
  // kName: the value names an earlier stage of one of these kinds.
  std::vector<std::string> stage_kinds;
  // kName: the value names an entry (its `name`) of one of these lists of
  // the same stage, e.g. a motion's group: {"bodies", "groups"}.
  std::vector<std::string> entry_lists;
  // kListOf of maps: each entry's `name` is a name of the stage's one
  // namespace, shared by every list that declares names (bodies and
  // groups): a name given twice is an error.
  bool declares_names = false;
  // kMap: the keys of a lower and an upper bound (numbers or equal-length
  // lists), each entry of the first below the second's: a box or block
  // with lo >= hi holds nothing.
  std::pair<std::string, std::string> lower_upper;
  bool one_key = false;  // kMap: exactly one of its keys is given
  // kFile: the file holds, in the same format, the map of the sibling key
  // named here, which may be given inline instead (a material's
  // potential_file and potential): one of the two is required.
  std::string holds;
  // Given only when the sibling key `first` resolves to `second` (empty
  // `first`: always allowed), e.g. md_tension's initial_strain with
  // lateral: periodic. Travels in --describe, so the coupler refuses it
  // before any rank starts.
  std::pair<std::string, std::string> only_with;
  // Required when the sibling key `first` resolves to `second` (dpd_run's
  // `tension` map with mode: tension). Travels in --describe.
  std::pair<std::string, std::string> required_with;
  // Not given together with the sibling key named here (an empty list
  // counts as not given): `initial` and `bodies` both say where a stage's
  // particles come from.
  std::string excludes;
  std::vector<Param> fields;
  // kMap with variants: `discriminator` names the key whose value picks the
  // extra fields in `variants` (stage "kind", material "kind").
  std::string discriminator;
  std::map<std::string, std::vector<Param>> variants;
  std::map<std::string, std::string> variant_docs;

  // Builders. Chaining on a temporary is safe: the caller copies the result.
  static Param integer(std::string name, std::string doc);
  static Param real(std::string name, units::Dimension dim, std::string doc);
  static Param boolean(std::string name, std::string doc);
  static Param string(std::string name, std::string doc);
  static Param identifier(std::string name, std::string doc);
  static Param file(std::string name, std::string doc);
  static Param path(std::string name, std::string doc);
  static Param choice(std::string name, std::vector<std::string> choices, std::string doc);
  static Param real_list(std::string name, units::Dimension dim, std::string doc);
  static Param int_list(std::string name, std::string doc);
  static Param map(std::string name, std::vector<Param> fields, std::string doc);
  static Param map_of(std::string name, Param element, std::string doc);
  static Param list_of(std::string name, Param element, std::string doc);
  // Reaches the stage as a map of columns: {name: {unit, values}}.
  static Param table(std::string name, std::string doc);

  Param& require() {
    required = true;
    return *this;
  }
  template <typename T>
  Param& def(const T& v) {
    default_value = YAML::Node(v);
    return *this;
  }
  Param& at_least(double v) {
    min = v;
    min_exclusive = false;
    return *this;
  }
  Param& above(double v) {
    min = v;
    min_exclusive = true;
    return *this;
  }
  Param& at_most(double v) {
    max = v;
    max_exclusive = false;
    return *this;
  }
  Param& below(double v) {
    max = v;
    max_exclusive = true;
    return *this;
  }
  Param& holding(std::string sibling) {
    holds = std::move(sibling);
    return *this;
  }
  Param& length_one_of(std::vector<size_t> allowed) {
    lengths = std::move(allowed);
    return *this;
  }
  Param& length(size_t lo, size_t hi) {
    min_length = lo;
    max_length = hi;
    return *this;
  }
  Param& or_auto() {
    allow_auto = true;
    return *this;
  }
  Param& referable() {
    allow_reference = true;
    return *this;
  }
  Param& material() {
    names_material = true;
    return *this;
  }
  Param& earlier_stage(std::vector<std::string> kinds) {
    stage_kinds = std::move(kinds);
    return *this;
  }
  Param& names_entry_of(std::vector<std::string> lists) {
    entry_lists = std::move(lists);
    return *this;
  }
  Param& bounds(std::string lower, std::string upper) {
    lower_upper = {std::move(lower), std::move(upper)};
    return *this;
  }
  Param& with_stage_names() {
    declares_names = true;
    return *this;
  }
  Param& not_with(std::string sibling) {
    excludes = std::move(sibling);
    return *this;
  }
  Param& only_when(std::string key, std::string value) {
    only_with = {std::move(key), std::move(value)};
    return *this;
  }
  Param& required_when(std::string key, std::string value) {
    required_with = {std::move(key), std::move(value)};
    return *this;
  }
  Param& exactly_one_key() {
    one_key = true;
    return *this;
  }
  Param& variant(const std::string& value, std::vector<Param> extra, std::string doc);
  Param& discriminated_by(std::string key) {
    discriminator = std::move(key);
    return *this;
  }

  [[nodiscard]] const Param* field(std::string_view key) const;
  // All keys valid in a map node whose discriminator has value `variant`.
  [[nodiscard]] std::vector<const Param*> fields_for(const std::string& variant) const;
  // One-line type description for error messages and docs ("real [bar]").
  [[nodiscard]] std::string type_text() const;
};

// Round trip through YAML, so that a driver can declare its stage kinds'
// parameters to the coupler (`md_driver --describe`).
YAML::Node to_yaml(const Param& p);
Param param_from_yaml(const YAML::Node& n);

}  // namespace pbms::config

#include "pbms/grid/shape_function.hpp"

#include <map>
#include <utility>

#include "pbms/error.hpp"
#include "pbms/grid/shape_function_linear.hpp"

namespace pbms::grid {

namespace {

using Table = std::map<std::string, ShapeFunctionRegistry::Factory, std::less<>>;

// The built-in styles; a new shape function adds its line here.
Table& table() {
  static Table t{
      {"linear", [] { return std::make_unique<ShapeFunctionLinear>(); }},
  };
  return t;
}

std::string joined_names() {
  std::string s;
  for (const auto& [name, factory] : table()) {
    if (!s.empty()) s += ", ";
    s += name;
  }
  return s;
}

}  // namespace

std::unique_ptr<ShapeFunction> ShapeFunctionRegistry::create(std::string_view name) {
  const auto it = table().find(name);
  if (it == table().end()) {
    throw Error("unknown shape function '" + std::string(name) + "'; available: " + joined_names());
  }
  return it->second();
}

std::vector<std::string> ShapeFunctionRegistry::names() {
  std::vector<std::string> out;
  for (const auto& [name, factory] : table()) out.push_back(name);
  return out;
}

bool ShapeFunctionRegistry::contains(std::string_view name) {
  return table().find(name) != table().end();
}

void ShapeFunctionRegistry::add(std::string name, Factory factory) {
  if (name.empty() || !factory) throw Error("a shape function style needs a name and a factory");
  if (contains(name)) throw Error("shape function '" + name + "' is already registered");
  table().emplace(std::move(name), std::move(factory));
}

}  // namespace pbms::grid

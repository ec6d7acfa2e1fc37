#include "material_registry.hpp"

#include <map>
#include <utility>

#include "cubic_j2_plasticity.hpp"
#include "ideal_gas.hpp"
#include "j2_plasticity.hpp"
#include "linear_elastic.hpp"
#include "pbms/error.hpp"

namespace pbms::mpm {

namespace {

// Built-ins are listed here rather than self-registering from their own files:
// static-initialiser registration is silently dropped when a static library's
// object file has no other referenced symbol.
std::map<std::string, MaterialFactory, std::less<>>& factories() {
  static std::map<std::string, MaterialFactory, std::less<>> table = {
      {std::string(LinearElastic::kStyle), &LinearElastic::create},
      {std::string(J2Plasticity::kStyle), &J2Plasticity::create},
      {std::string(IdealGas::kStyle), &IdealGas::create},
      {std::string(CubicJ2Plasticity::kStyle), &CubicJ2Plasticity::create},
  };
  return table;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

std::unique_ptr<grid::Material> MaterialRegistry::create(std::string_view style,
                                                         const MaterialParameters& params) {
  const auto& table = factories();
  const auto it = table.find(style);
  if (it == table.end()) {
    throw Error("unknown material style '" + std::string(style) +
                "'; known styles: " + joined(styles()));
  }
  return it->second(params);
}

void MaterialRegistry::add(std::string style, MaterialFactory factory) {
  auto& table = factories();
  if (table.count(style) != 0) {
    throw Error("material style '" + style + "' is already registered");
  }
  table.emplace(std::move(style), std::move(factory));
}

std::vector<config::MaterialKindSpec> MaterialRegistry::specs() {
  return {LinearElastic::spec(), J2Plasticity::spec(), CubicJ2Plasticity::spec(), IdealGas::spec()};
}

std::vector<std::string> MaterialRegistry::styles() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : factories()) names.push_back(name);
  return names;
}

}  // namespace pbms::mpm

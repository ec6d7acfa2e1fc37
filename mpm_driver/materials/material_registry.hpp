// Material styles by name, as LAMMPS looks up pair and fix styles: a
// configuration names a style and gives its numeric parameters, the registry
// returns the constitutive model or a pbms::Error a user can act on.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "material_parameters.hpp"
#include "pbms/config/stage_kind_spec.hpp"
#include "pbms/grid/material.hpp"

namespace pbms::mpm {

using MaterialFactory = std::function<std::unique_ptr<grid::Material>(const MaterialParameters&)>;

class MaterialRegistry {
 public:
  // Built-in styles: linear_elastic, j2_plasticity, ideal_gas. Throws
  // pbms::Error for an unknown style (listing the known ones) and for missing,
  // unknown or out-of-range parameters (naming the parameter and its range).
  static std::unique_ptr<grid::Material> create(std::string_view style,
                                                const MaterialParameters& params);

  // Adds a style from outside this directory. Throws pbms::Error if the name
  // is taken. Not thread-safe: register before any concurrent create().
  static void add(std::string style, MaterialFactory factory);

  // Known style names, sorted.
  static std::vector<std::string> styles();
  // The built-in styles' material kinds, for a driver to publish.
  static std::vector<config::MaterialKindSpec> specs();
};

}  // namespace pbms::mpm

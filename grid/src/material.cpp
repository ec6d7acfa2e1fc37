#include "pbms/grid/material.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "pbms/error.hpp"

namespace pbms::grid {

MaterialPointState Material::initial_state(double density, double pressure) const {
  if (!(density > 0.0) || !std::isfinite(density)) {
    std::ostringstream msg;
    msg << style() << ": initial density " << density << " must be finite and > 0";
    throw Error(msg.str());
  }
  if (!std::isfinite(pressure)) {
    throw Error(std::string(style()) + ": initial pressure must be finite");
  }
  MaterialPointState state;
  state.density = density;
  state.stress = SymmetricTensor::isotropic(-pressure);
  return state;
}

}  // namespace pbms::grid

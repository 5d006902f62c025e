#include "tensormass/materials/stvk_material.hpp"

#include "core/base/error.hpp"

#include <cmath>
#include <sstream>

namespace tmlab::tm {

StVenantKirchhoff StVenantKirchhoff::from_young_poisson(double young, double poisson) {
  if (!(young > 0.0) || !std::isfinite(young)) {
    std::ostringstream os;
    os << "St Venant-Kirchhoff material: Young's modulus E must be finite and > 0, got E = " << young;
    throw Error(os.str());
  }
  if (!(poisson > -1.0 && poisson < 0.5)) {
    std::ostringstream os;
    os << "St Venant-Kirchhoff material: Poisson's ratio nu must satisfy -1 < nu < 0.5, got nu = " << poisson;
    throw Error(os.str());
  }
  StVenantKirchhoff m;
  // seed eq. 4 (as printed) and eq. 5 corrected (docs/theory/seed-errata.md): mu = E / (2(1+nu)).
  m.lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  m.mu = young / (2.0 * (1.0 + poisson));
  return m;
}

}  // namespace tmlab::tm
